// Toon shading in software (Lake et al. 2000, as in shaders/toon.frag) over the
// constant-depth-scanline rasteriser of Han & Wang 2011 (J. CAD & CG 23(6), §3–4).
#include "raster/soft_renderer.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "core/timer.h"

namespace lodline {
namespace {

uint8_t toByte(float v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

// Blends `rgba` (alpha = coverage) over the pixel like glBlendFuncSeparate(SRC_ALPHA,
// ONE_MINUS_SRC_ALPHA, ONE, ONE_MINUS_SRC_ALPHA) on an RGBA8 target.
void blend(uint8_t* px, const glm::vec4& c) {
  const float a = std::clamp(c.a, 0.0f, 1.0f);
  for (int k = 0; k < 3; ++k) px[k] = toByte(c[k] * a + (px[k] / 255.0f) * (1.0f - a));
  px[3] = toByte(a + (px[3] / 255.0f) * (1.0f - a));
}

}  // namespace

glm::vec4 sampleTexture(const Image& image, float u, float v, TextureFilter filter) {
  const int w = image.width, h = image.height;
  auto texel = [&](int x, int y) {
    x %= w;
    y %= h;
    if (x < 0) x += w;
    if (y < 0) y += h;
    const uint8_t* p = image.pixel(x, y);
    return glm::vec4(p[0], p[1], p[2], p[3]) * (1.0f / 255.0f);
  };
  if (!std::isfinite(u) || !std::isfinite(v)) return texel(0, 0);
  const float x = u * static_cast<float>(w), y = v * static_cast<float>(h);
  if (filter == TextureFilter::kNearest)
    return texel(static_cast<int>(std::floor(x)), static_cast<int>(std::floor(y)));
  const float fx = x - 0.5f, fy = y - 0.5f;
  const float x0 = std::floor(fx), y0 = std::floor(fy);
  const float ax = fx - x0, ay = fy - y0;
  const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
  const glm::vec4 top = texel(ix, iy) * (1.0f - ax) + texel(ix + 1, iy) * ax;
  const glm::vec4 bottom = texel(ix, iy + 1) * (1.0f - ax) + texel(ix + 1, iy + 1) * ax;
  return top * (1.0f - ay) + bottom * ay;
}

size_t drawStrokeTriangles(std::span<const StrokeVertex> vertices, const glm::vec4& colour, const Image* brush,
                           Image& image, WorkerPool& pool) {
  const int W = image.width, H = image.height;
  if (brush && (brush->width <= 0 || brush->height <= 0)) brush = nullptr;
  const float period = brush ? static_cast<float>(brush->width) : 1.0f;
  // Across, texel centres only (GL's CLAMP_TO_EDGE; sampleTexture() would wrap).
  const float v_lo = brush ? 0.5f / static_cast<float>(brush->height) : 0.0f, v_hi = 1.0f - v_lo;
  const size_t triangles = vertices.size() / 3;
  auto draw_band = [&](int row_begin, int row_end) {
    for (size_t t = 0; t < triangles; ++t) {
      const StrokeVertex* v = &vertices[3 * t];
      // Non-finite or absurdly far vertices (bad input) are skipped, not converted to int.
      constexpr float kFar = 1e7f;
      bool sane = true;
      for (int k = 0; k < 3; ++k) sane = sane && std::abs(v[k].px.x) < kFar && std::abs(v[k].px.y) < kFar;
      if (!sane) continue;
      const float min_y = std::min({v[0].px.y, v[1].px.y, v[2].px.y});
      const float max_y = std::max({v[0].px.y, v[1].px.y, v[2].px.y});
      const int y_lo = std::max(static_cast<int>(std::ceil(min_y - 0.5f)), row_begin);
      const int y_hi = std::min(static_cast<int>(std::ceil(max_y - 0.5f)) - 1, row_end - 1);
      if (y_lo > y_hi) continue;
      const float min_x = std::min({v[0].px.x, v[1].px.x, v[2].px.x});
      const float max_x = std::max({v[0].px.x, v[1].px.x, v[2].px.x});
      const int x_lo = std::max(static_cast<int>(std::ceil(min_x - 0.5f)), 0);
      const int x_hi = std::min(static_cast<int>(std::ceil(max_x - 0.5f)) - 1, W - 1);
      if (x_lo > x_hi) continue;
      // Edge functions in double, oriented so the triangle's inside is positive.
      glm::dvec2 p[3] = {glm::dvec2(v[0].px), glm::dvec2(v[1].px), glm::dvec2(v[2].px)};
      int idx[3] = {0, 1, 2};
      double area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x);
      if (area == 0.0) continue;
      if (area < 0.0) {
        std::swap(p[1], p[2]);
        std::swap(idx[1], idx[2]);
        area = -area;
      }
      // Edge k runs from p[k+1] to p[k+2] (opposite vertex k). Top-left rule in y-down
      // pixels: an edge with a pixel centre exactly on it owns the pixel when it is a top
      // edge (horizontal, inside below) or a left edge (inside to its right... going up).
      bool owns[3];
      for (int k = 0; k < 3; ++k) {
        const glm::dvec2 a = p[(k + 1) % 3], b = p[(k + 2) % 3];
        const glm::dvec2 d = b - a;
        owns[k] = (d.y == 0.0 && d.x > 0.0) || d.y < 0.0;
      }
      auto edge = [&](int k, double x, double y) {
        const glm::dvec2 a = p[(k + 1) % 3], b = p[(k + 2) % 3];
        return (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
      };
      const StrokeVertex& v0 = v[idx[0]];
      const StrokeVertex& v1 = v[idx[1]];
      const StrokeVertex& v2 = v[idx[2]];
      const float cap = v[2].cap;  // flat: the last vertex, as OpenGL's provoking vertex
      for (int y = y_lo; y <= y_hi; ++y) {
        const double cy = y + 0.5;
        for (int x = x_lo; x <= x_hi; ++x) {
          const double cx = x + 0.5;
          const double e0 = edge(0, cx, cy), e1 = edge(1, cx, cy), e2 = edge(2, cx, cy);
          if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) continue;
          if ((e0 == 0.0 && !owns[0]) || (e1 == 0.0 && !owns[1]) || (e2 == 0.0 && !owns[2])) continue;
          const float w0 = static_cast<float>(e0 / area), w1 = static_cast<float>(e1 / area);
          const float w2 = 1.0f - w0 - w1;
          const glm::vec2 local = w0 * v0.local + w1 * v1.local + w2 * v2.local;
          const float half_width = w0 * v0.half_width + w1 * v1.half_width + w2 * v2.half_width;
          const float alpha = w0 * v0.alpha + w1 * v1.alpha + w2 * v2.alpha;
          float c = strokeCoverage(local, half_width, cap);
          if (c <= 0.0f) continue;
          if (brush) {
            const float u = w0 * v0.u + w1 * v1.u + w2 * v2.u;
            const glm::vec2 st = brushCoordinates(u, local, half_width, period);
            c *= sampleTexture(*brush, st.x, std::clamp(st.y, v_lo, v_hi), TextureFilter::kBilinear).r;
          }
          blend(image.pixel(x, y), glm::vec4(glm::vec3(colour), colour.a * alpha * c));
        }
      }
    }
  };
  pool.forRange(static_cast<size_t>(H), 16, [&](size_t y0, size_t y1) {
    draw_band(static_cast<int>(y0), static_cast<int>(y1));
  });
  return triangles;
}

SoftRenderer::SoftRenderer(const RasterParams& params) : params_(params) { setObjectCount(1); }

void SoftRenderer::setWorkerPool(std::shared_ptr<WorkerPool> pool) { rasterizer_.setWorkerPool(std::move(pool)); }

void SoftRenderer::setObjectCount(size_t n) { objects_.resize(n); }

void SoftRenderer::setMesh(size_t object, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                           std::span<const std::array<uint32_t, 3>> faces) {
  Object& o = objects_[object];
  o.positions.assign(positions.begin(), positions.end());
  o.normals.assign(normals.begin(), normals.end());
  o.faces.assign(faces.begin(), faces.end());
}

void SoftRenderer::setTexture(size_t object, Image texture, std::span<const glm::vec2> uvs) {
  objects_[object].texture = std::move(texture);
  objects_[object].uvs.assign(uvs.begin(), uvs.end());
}

void SoftRenderer::setLines(size_t object, const ScreenLines& lines) { objects_[object].lines = lines; }

Status SoftRenderer::supports(const ObjectStyle& style) {
  if (style.style == Style::kShaded)
    return Error::usage("the shaded style (Blinn-Phong faces and chamfer highlights) needs OpenGL");
  if (style.style == Style::kToon && style.chamfer.enabled && style.chamfer.over_toon)
    return Error::usage("chamfer highlights (--chamfer on) need OpenGL");
  return {};
}

void SoftRenderer::setBackFaceCulling(size_t object, bool closed, const glm::vec3& center, float radius) {
  Object& o = objects_[object];
  o.closed = closed;
  o.center = center;
  o.radius = radius;
}

void SoftRenderer::gather(const glm::mat4& view, const glm::mat4& view_proj, int attribute_count,
                          const Camera* camera) {
  const glm::mat3 normal_matrix(view);  // as mesh.vert: mat3(u_view) * a_normal
  const int N = attribute_count;
  size_t nv = 0, nf = 0;
  for (const Object& o : objects_) {
    nv += o.positions.size();
    nf += o.faces.size();
  }
  clip_.resize(nv);
  attributes_.assign(nv * N, 0.0f);
  faces_.resize(nf);
  face_object_.resize(nf);
  face_cull_.assign(camera ? nf : 0, 0);
  size_t v0 = 0, f0 = 0;
  for (size_t i = 0; i < objects_.size(); ++i) {
    const Object& o = objects_[i];
    const bool tex = textured(o);
    for (size_t v = 0; v < o.positions.size(); ++v) {
      clip_[v0 + v] = view_proj * glm::vec4(o.positions[v], 1.0f);
      const glm::vec3 n = v < o.normals.size() ? normal_matrix * o.normals[v] : glm::vec3(0.0f, 0.0f, 1.0f);
      float* a = &attributes_[(v0 + v) * N];
      a[0] = n.x;
      a[1] = n.y;
      a[2] = n.z;
      if (tex) {
        a[3] = o.uvs[v].x;
        a[4] = o.uvs[v].y;
      }
    }
    const uint32_t base = static_cast<uint32_t>(v0);
    for (size_t f = 0; f < o.faces.size(); ++f) {
      faces_[f0 + f] = {o.faces[f][0] + base, o.faces[f][1] + base, o.faces[f][2] + base};
      face_object_[f0 + f] = static_cast<uint32_t>(i);
    }
    if (camera) {
      const bool cull = o.closed && eyeOutsideSphere(*camera, o.center, o.radius);
      std::fill(face_cull_.begin() + static_cast<std::ptrdiff_t>(f0),
                face_cull_.begin() + static_cast<std::ptrdiff_t>(f0 + o.faces.size()), cull ? 1 : 0);
    }
    v0 += o.positions.size();
    f0 += o.faces.size();
  }
}

void SoftRenderer::drawSurfaces(const Camera& camera, const FrameParams& frame, std::span<const ObjectStyle> styles) {
  LODLINE_ASSERT(styles.size() == objects_.size());
  Stopwatch sw;
  const int W = frame.width, H = frame.height;
  width_ = W;
  height_ = H;
  const bool any_texture = std::any_of(objects_.begin(), objects_.end(), [&](const Object& o) { return textured(o); });
  const int N = any_texture ? 5 : 3;
  const glm::mat4 view = camera.view();
  const glm::mat4 view_proj = camera.projection(frame.aspect()) * view;
  gather(view, view_proj, N, &camera);
  times_.transform = sw.lap();

  // 1. Faces of every object, pushed back like glPolygonOffset(1, 2) (as the GL renderer's,
  //    so both give the same depth image for the visibility of lines).
  if (target_.width != W || target_.height != H || target_.attribute_count != N)
    target_.resize(W, H, N);
  else
    target_.clear();
  RasterParams rp = params_;
  rp.depth_test = true;
  rp.cull_back_faces = false;  // both sides of open meshes; closed ones' back faces: in.cull
  rp.depth_offset_factor = 1.0f;
  rp.depth_offset_units = 2.0f;
  RasterInput in;
  in.clip = clip_;
  in.attributes = attributes_;
  in.attribute_count = N;
  in.faces = faces_;
  in.cull = face_cull_;
  rasterizer_.draw(in, rp, target_);
  times_.setup = rasterizer_.stats().ms_setup;
  times_.raster = rasterizer_.stats().ms_raster;
  sw.lap();

  // 2. Shading: each object's ramp (as shaders/toon.frag: 256 texels over n·l ∈ [0, 1],
  //    nearest); lines-style objects and the empty image take the background colour.
  if (image_.width != W || image_.height != H) image_ = Image(W, H);
  std::vector<std::array<float, 256>> ramps(objects_.size());
  for (size_t i = 0; i < objects_.size(); ++i) ramps[i] = toonRamp(styles[i].toon);
  const glm::vec3 light = glm::normalize(frame.light_dir_eye);
  const uint8_t bg[4] = {toByte(frame.background.r), toByte(frame.background.g), toByte(frame.background.b),
                         toByte(frame.background.a)};
  const size_t plane = static_cast<size_t>(W) * H;
  pool().forRange(static_cast<size_t>(H), 16, [&](size_t y0, size_t y1) {
    for (int y = static_cast<int>(y0); y < static_cast<int>(y1); ++y)
      for (int x = 0; x < W; ++x) {
        const size_t i = target_.index(x, y);
        uint8_t* px = image_.pixel(x, y);
        const uint32_t face = target_.face_id[i];
        const uint32_t obj = face == kNoFace ? 0 : face_object_[face];
        if (face == kNoFace || styles[obj].style != Style::kToon) {
          std::copy(bg, bg + 4, px);
          continue;
        }
        const ToonParams& toon = styles[obj].toon;
        glm::vec3 n(target_.attributes[i], target_.attributes[plane + i], target_.attributes[2 * plane + i]);
        const float len = glm::length(n);
        n = len > 0.0f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
        if (!target_.front_facing[i]) n = -n;  // two-sided, like gl_FrontFacing
        const float ndotl = std::clamp(glm::dot(n, light), 0.0f, 1.0f);
        const float tone = ramps[obj][std::min(static_cast<int>(ndotl * 256.0f), 255)];
        glm::vec3 c = toon.base_color * tone;
        if (textured(objects_[obj])) {
          const glm::vec4 t = sampleTexture(objects_[obj].texture, target_.attributes[3 * plane + i],
                                            target_.attributes[4 * plane + i], TextureFilter::kBilinear);
          c *= glm::vec3(t);
        }
        px[0] = toByte(c.r);
        px[1] = toByte(c.g);
        px[2] = toByte(c.b);
        px[3] = 255;
      }
  });
  times_.shade = sw.lap();

  times_.lines = 0.0;
}

void SoftRenderer::drawLines(const FrameParams& frame, std::span<const ObjectStyle> styles) {
  LODLINE_ASSERT(styles.size() == objects_.size());
  LODLINE_ASSERT(image_.width == frame.width && image_.height == frame.height);
  (void)frame;
  Stopwatch sw;
  // Every object's lines, blended, no depth test: hidden lines first, then visible ones.
  for (size_t i = 0; i < objects_.size(); ++i) {
    Object& o = objects_[i];
    const ObjectStyle& style = styles[i];
    o.segments_drawn = 0;
    const ScreenLines& l = o.lines;
    if (style.hidden.enabled && l.hidden_count > 0) {
      drawStrokeTriangles(std::span(l.vertices).subspan(l.hidden_first, l.hidden_count), style.hidden.color, nullptr,
                          image_, pool());
      o.segments_drawn += l.hidden_segments;
    }
    for (int k = 0; k < kLineKindCount; ++k) {
      const LineStyle& s = style.lines.kinds[k];
      if (!s.enabled || l.count[k] == 0) continue;
      drawStrokeTriangles(std::span(l.vertices).subspan(l.first[k], l.count[k]), s.color, s.stroke.brush.get(),
                          image_, pool());
      o.segments_drawn += l.segments[k];
    }
  }
  times_.lines = sw.lap();
}

void SoftRenderer::drawSurface(const Camera& camera, SurfaceImage& out) {
  const int W = width_, H = height_;
  const glm::mat4 view_proj = camera.projection(static_cast<float>(W) / static_cast<float>(H)) * camera.view();
  // World positions as the attributes (no polygon offset: the surface itself).
  gather(glm::mat4(1.0f), view_proj, 3);
  size_t v0 = 0;
  for (const Object& o : objects_) {
    for (size_t v = 0; v < o.positions.size(); ++v) {
      float* a = &attributes_[(v0 + v) * 3];
      a[0] = o.positions[v].x;
      a[1] = o.positions[v].y;
      a[2] = o.positions[v].z;
    }
    v0 += o.positions.size();
  }
  if (surface_target_.width != W || surface_target_.height != H || surface_target_.attribute_count != 3)
    surface_target_.resize(W, H, 3);
  else
    surface_target_.clear();
  RasterParams rp = params_;
  rp.depth_test = true;
  rp.cull_back_faces = false;
  rp.interpolation = Interpolation::kExact;  // positions, not texture coordinates: exact
  RasterInput in;
  in.clip = clip_;
  in.attributes = attributes_;
  in.attribute_count = 3;
  in.faces = faces_;
  rasterizer_.draw(in, rp, surface_target_);
  out.width = W;
  out.height = H;
  out.texels.assign(static_cast<size_t>(W) * H, glm::vec4(0.0f));
  const size_t plane = static_cast<size_t>(W) * H;
  for (size_t i = 0; i < plane; ++i) {
    const uint32_t face = surface_target_.face_id[i];
    if (face == kNoFace) continue;
    out.texels[i] = glm::vec4(surface_target_.attributes[i], surface_target_.attributes[plane + i],
                              surface_target_.attributes[2 * plane + i], static_cast<float>(face_object_[face] + 1));
  }
}

}  // namespace lodline
