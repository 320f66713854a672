#include "gl/renderer.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "gl/shader.h"

namespace lodline {
namespace {

void setMatrices(GLuint program, const Camera& camera, float aspect) {
  glUniformMatrix4fv(glGetUniformLocation(program, "u_view"), 1, GL_FALSE,
                     glm::value_ptr(camera.view()));
  glUniformMatrix4fv(glGetUniformLocation(program, "u_projection"), 1, GL_FALSE,
                     glm::value_ptr(camera.projection(aspect)));
}

template <class T>
void uploadArray(GLenum target, const GlBuffer& buffer, std::span<const T> data) {
  glBindBuffer(target, buffer.id());
  GLint64 capacity = 0;
  glGetBufferParameteri64v(target, GL_BUFFER_SIZE, &capacity);
  const auto bytes = static_cast<GLsizeiptr>(data.size_bytes());
  if (bytes <= capacity && bytes > 0) {
    glBufferSubData(target, 0, bytes, data.data());
  } else {
    glBufferData(target, bytes + bytes / 2, nullptr, GL_DYNAMIC_DRAW);
    if (bytes > 0) glBufferSubData(target, 0, bytes, data.data());
  }
}

// OpenGL's rows run bottom-up: flips `data` (rows of `row` elements) in place, so row 0 is
// the top (no per-frame copy of the image).
template <class T>
void flipRows(std::vector<T>& data, size_t row, int height) {
  for (int y = 0; y < height / 2; ++y) {
    auto top = data.begin() + static_cast<ptrdiff_t>(y * row);
    std::swap_ranges(top, top + static_cast<ptrdiff_t>(row), data.begin() + static_cast<ptrdiff_t>((height - 1 - y) * row));
  }
}

// A framebuffer with a colour renderbuffer of `color_format` and a 24-bit depth renderbuffer,
// `samples` per pixel (0: not multisampled). `what` names it in the error.
Status makeTargetFramebuffer(GLenum color_format, int width, int height, GLsizei samples, const char* what,
                             GlFramebuffer& fbo, GlRenderbuffer& color, GlRenderbuffer& depth) {
  color = makeRenderbuffer();
  glBindRenderbuffer(GL_RENDERBUFFER, color.id());
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, color_format, width, height);
  depth = makeRenderbuffer();
  glBindRenderbuffer(GL_RENDERBUFFER, depth.id());
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width, height);
  fbo = makeFramebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color.id());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.id());
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!complete) return Error::runtime(std::string(what) + " framebuffer is incomplete");
  return {};
}

}  // namespace

Result<Renderer> Renderer::create() {
  Renderer r;
  auto toon = loadProgram("mesh.vert", "toon.frag");
  if (!toon) return toon.error();
  auto depth = loadProgram("mesh.vert", "depth_only.frag");
  if (!depth) return depth.error();
  auto line = loadProgram("stroke.vert", "stroke.frag");
  if (!line) return line.error();
  r.toon_ = std::move(toon.value());
  r.depth_only_ = std::move(depth.value());
  r.line_ = std::move(line.value());
  auto surface = loadProgram("mesh.vert", "surface.frag");
  if (!surface) return surface.error();
  r.surface_ = std::move(surface.value());
  r.ramp_ = makeTexture();
  if (Status s = r.setObjectCount(1); !s) return s.error();
  return r;
}

Result<Renderer::Object> Renderer::makeObject() const {
  Object o;
  auto chamfer = ChamferLayer::create();
  if (!chamfer) return chamfer.error();
  o.chamfer = std::move(chamfer.value());
  o.mesh_vao = makeVertexArray();
  o.positions = makeBuffer();
  o.normals = makeBuffer();
  o.indices = makeBuffer();
  glBindVertexArray(o.mesh_vao.id());
  glBindBuffer(GL_ARRAY_BUFFER, o.positions.id());
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, o.normals.id());
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, o.indices.id());

  o.line_vao = makeVertexArray();
  o.line_vertices = makeBuffer();
  glBindVertexArray(o.line_vao.id());
  glBindBuffer(GL_ARRAY_BUFFER, o.line_vertices.id());
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, sizeof(StrokeVertex), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(StrokeVertex),
                        reinterpret_cast<const void*>(offsetof(StrokeVertex, half_width)));
  glBindVertexArray(0);
  return o;
}

Status Renderer::setObjectCount(size_t n) {
  if (objects_.size() > n) objects_.resize(n);
  while (objects_.size() < n) {
    auto o = makeObject();
    if (!o) return o.error();
    objects_.push_back(std::move(o.value()));
  }
  return {};
}

void Renderer::setMesh(size_t object, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                       std::span<const std::array<uint32_t, 3>> faces, std::span<const EdgeKey> marked_edges) {
  Object& o = objects_[object];
  o.chamfer.setMesh(positions, faces, marked_edges);
  glBindVertexArray(0);
  uploadArray(GL_ARRAY_BUFFER, o.positions, positions);
  uploadArray(GL_ARRAY_BUFFER, o.normals, normals);
  glBindVertexArray(o.mesh_vao.id());
  uploadArray(GL_ELEMENT_ARRAY_BUFFER, o.indices, faces);
  glBindVertexArray(0);
  o.face_count = faces.size();
}

void Renderer::setLines(size_t object, const ScreenLines& lines) {
  Object& o = objects_[object];
  glBindVertexArray(0);
  uploadArray(GL_ARRAY_BUFFER, o.line_vertices, std::span<const StrokeVertex>(lines.vertices));
  o.first = lines.first;
  o.count = lines.count;
  o.segments = lines.segments;
  o.hidden_segments = lines.hidden_segments;
  o.hidden_first = lines.hidden_first;
  o.hidden_count = lines.hidden_count;
}

size_t Renderer::segmentsDrawn() const {
  size_t n = 0;
  for (const Object& o : objects_) n += o.segments_drawn;
  return n;
}

size_t Renderer::chamferEdgesDrawn() const {
  size_t n = 0;
  for (const Object& o : objects_) n += o.chamfer_drawn;
  return n;
}

void Renderer::drawFaces(Object& o, const Camera& camera, const ObjectStyle& style, const FrameParams& frame) {
  const float aspect = frame.aspect();
  if (style.style == Style::kShaded) {
    // Blinn–Phong with crease-aware corner normals (the chamfer layer's material).
    o.chamfer.drawShadedFaces(camera, style.chamfer, frame.light_dir_eye, frame.width, frame.height);
    return;
  }
  if (style.style == Style::kToon) {
    const ToonParams& t = style.toon;
    const std::array<float, 5> key{t.tones[0], t.tones[1], t.tones[2], t.thresholds[0], t.thresholds[1]};
    if (key != ramp_key_) {
      const std::array<float, 256> ramp = toonRamp(t);
      glBindTexture(GL_TEXTURE_2D, ramp_.id());
      glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, 256, 1, 0, GL_RED, GL_FLOAT, ramp.data());
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      ramp_key_ = key;
    }
    glUseProgram(toon_.id());
    setMatrices(toon_.id(), camera, aspect);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, ramp_.id());
    glUniform1i(glGetUniformLocation(toon_.id(), "u_ramp"), 0);
    glUniform3fv(glGetUniformLocation(toon_.id(), "u_base_color"), 1, glm::value_ptr(t.base_color));
    const glm::vec3 l = glm::normalize(frame.light_dir_eye);
    glUniform3fv(glGetUniformLocation(toon_.id(), "u_light_eye"), 1, glm::value_ptr(l));
  } else {
    // Lines only: the faces take the background colour and only hide hidden lines.
    glUseProgram(depth_only_.id());
    setMatrices(depth_only_.id(), camera, aspect);
    glUniform4fv(glGetUniformLocation(depth_only_.id(), "u_color"), 1, glm::value_ptr(frame.background));
  }
  glBindVertexArray(o.mesh_vao.id());
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(o.face_count * 3), GL_UNSIGNED_INT, nullptr);
}

void Renderer::setBackFaceCulling(size_t object, bool closed, const glm::vec3& center, float radius) {
  Object& o = objects_[object];
  o.closed = closed;
  o.center = center;
  o.radius = radius;
}

void Renderer::drawChamfer(Object& o, const Camera& camera, const ObjectStyle& style, const FrameParams& frame) {
  o.chamfer_drawn = 0;
  const ChamferParams& ch = style.chamfer;
  if (!ch.enabled || !(style.style == Style::kShaded || (style.style == Style::kToon && ch.over_toon))) return;
  if (style.style == Style::kShaded) {
    o.chamfer.draw(camera, ch, frame.light_dir_eye, frame.width, frame.height, true, glm::vec3(frame.background));
  } else {
    // Over toon: a Blinn–Phong whose range matches the ramp (darkest tone in the shade,
    // brightest fully lit), so highlights sit on the toon tones.
    ChamferParams over = ch;
    const ToonParams& t = style.toon;
    over.ambient = t.base_color * t.tones[0];
    over.diffuse = t.base_color * (t.tones[2] - t.tones[0]);
    o.chamfer.draw(camera, over, frame.light_dir_eye, frame.width, frame.height, false);
  }
  o.chamfer_drawn = o.chamfer.edgesDrawn();
}

void Renderer::drawSurfaces(const Camera& camera, const FrameParams& frame, std::span<const ObjectStyle> styles) {
  LODLINE_ASSERT(styles.size() == objects_.size());
  glViewport(0, 0, frame.width, frame.height);
  glClearColor(frame.background.r, frame.background.g, frame.background.b, frame.background.a);
  glClearDepth(1.0);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glCullFace(GL_BACK);  // counter-clockwise faces are front faces (GL's default)
  glDisable(GL_BLEND);

  // 1. Faces of every object, pushed back slightly so the chamfer highlights on their edges
  //    pass the depth test. A lines-style object's faces take the frame's background colour.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 2.0f);
  for (size_t i = 0; i < objects_.size(); ++i) {
    // A closed surface's back faces, with the eye outside its bounding sphere, are hidden by
    // its front faces; not rasterising them shortens a dense model's draw by about a tenth to a
    // fifth (docs/performance.md, "Back faces culled for closed models").
    const Object& o = objects_[i];
    if (o.closed && eyeOutsideSphere(camera, o.center, o.radius)) glEnable(GL_CULL_FACE);
    else glDisable(GL_CULL_FACE);
    drawFaces(objects_[i], camera, styles[i], frame);
  }
  glDisable(GL_CULL_FACE);
  glDisable(GL_POLYGON_OFFSET_FILL);

  // 2. Chamfer highlights on sharp edges, blended over the faces (depth-tested against them).
  for (size_t i = 0; i < objects_.size(); ++i) drawChamfer(objects_[i], camera, styles[i], frame);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glBindVertexArray(0);
}

unsigned Renderer::brushTexture(const std::shared_ptr<const Image>& brush) {
  for (const BrushTexture& b : brushes_)
    if (b.image == brush) return b.texture.id();
  BrushTexture b{brush, makeTexture()};
  glBindTexture(GL_TEXTURE_2D, b.texture.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, brush->width, brush->height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               brush->rgba.data());
  // Already resampled to its size on screen (io/stroke_style_file.h): no mipmaps.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  brushes_.push_back(std::move(b));
  return brushes_.back().texture.id();
}

void Renderer::drawObjectLines(Object& o, const ObjectStyle& style) {
  glBindVertexArray(o.line_vao.id());
  o.segments_drawn = 0;
  const GLint color_loc = glGetUniformLocation(line_.id(), "u_color");
  const GLint period_loc = glGetUniformLocation(line_.id(), "u_brush_period");
  auto draw = [&](const glm::vec4& colour, const StrokeStyle* stroke, uint32_t first, uint32_t count) {
    glUniform4fv(color_loc, 1, glm::value_ptr(colour));
    if (stroke && stroke->brush && stroke->brush->width > 0) {
      glActiveTexture(GL_TEXTURE1);
      glBindTexture(GL_TEXTURE_2D, brushTexture(stroke->brush));
      glUniform1f(period_loc, static_cast<float>(stroke->brush->width));
    } else {
      glUniform1f(period_loc, 0.0f);
    }
    glDrawArrays(GL_TRIANGLES, static_cast<GLint>(first), static_cast<GLsizei>(count));
  };
  // Hidden lines first, under the visible ones.
  if (style.hidden.enabled && o.hidden_count > 0) {
    draw(style.hidden.color, nullptr, o.hidden_first, o.hidden_count);
    o.segments_drawn += o.hidden_segments;
  }
  for (int k = 0; k < kLineKindCount; ++k) {
    const LineStyle& s = style.lines.kinds[k];
    if (!s.enabled || o.count[k] == 0) continue;
    // Highlighted sharp edges replace the crease lines drawn on them.
    if (k == static_cast<int>(LineKind::kCrease) && o.chamfer_drawn > 0 && style.chamfer.replace_creases) continue;
    draw(s.color, &s.stroke, o.first[k], o.count[k]);
    o.segments_drawn += o.segments[k];
  }
}

void Renderer::drawLines(const FrameParams& frame, std::span<const ObjectStyle> styles) {
  LODLINE_ASSERT(styles.size() == objects_.size());
  glViewport(0, 0, frame.width, frame.height);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glUseProgram(line_.id());
  glUniform2f(glGetUniformLocation(line_.id(), "u_viewport"), static_cast<float>(frame.width),
              static_cast<float>(frame.height));
  glUniform1i(glGetUniformLocation(line_.id(), "u_brush"), 1);
  // Brushes no style holds any more (the viewer switched presets) are let go.
  std::erase_if(brushes_, [](const BrushTexture& b) { return b.image.use_count() == 1; });
  for (size_t i = 0; i < objects_.size(); ++i) drawObjectLines(objects_[i], styles[i]);
  glActiveTexture(GL_TEXTURE0);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glBindVertexArray(0);
}

void Renderer::drawSurface(const Camera& camera, int width, int height) {
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  glViewport(0, 0, width, height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glUseProgram(surface_.id());
  setMatrices(surface_.id(), camera, aspect);
  const glm::mat4 inverse_view = glm::inverse(camera.view());
  glUniformMatrix4fv(glGetUniformLocation(surface_.id(), "u_view_inverse"), 1, GL_FALSE, glm::value_ptr(inverse_view));
  const GLint object_loc = glGetUniformLocation(surface_.id(), "u_object");
  for (size_t i = 0; i < objects_.size(); ++i) {
    glUniform1f(object_loc, static_cast<float>(i + 1));
    glBindVertexArray(objects_[i].mesh_vao.id());
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(objects_[i].face_count * 3), GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
}

Result<SurfaceTarget> SurfaceTarget::create(int width, int height) {
  SurfaceTarget t;
  t.width_ = width;
  t.height_ = height;
  if (Status st = makeTargetFramebuffer(GL_RGBA32F, width, height, 0, "surface (RGBA32F)", t.fbo_, t.color_, t.depth_);
      !st)
    return st.error();
  return t;
}

void SurfaceTarget::bindAndClear() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClearDepth(1.0);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void SurfaceTarget::readback(SurfaceImage& out) const {
  out.width = width_;
  out.height = height_;
  out.texels.resize(static_cast<size_t>(width_) * height_);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.id());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, out.texels.data());
  flipRows(out.texels, static_cast<size_t>(width_), height_);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

Result<OffscreenTarget> OffscreenTarget::create(int width, int height, int samples) {
  OffscreenTarget t;
  t.width_ = width;
  t.height_ = height;
  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  t.samples_ = std::clamp(samples, 1, std::max(1, static_cast<int>(max_samples)));
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width > max_size || height > max_size)
    return Error::runtime("image size " + std::to_string(width) + "x" + std::to_string(height) +
                          " exceeds the OpenGL limit of " + std::to_string(max_size) + " px");
  const GLsizei ms = t.samples_ > 1 ? t.samples_ : 0;
  if (Status st = makeTargetFramebuffer(GL_RGBA8, width, height, ms, "offscreen", t.fbo_, t.color_, t.depth_); !st)
    return st.error();
  if (Status st = makeTargetFramebuffer(GL_RGBA8, width, height, 0, "resolve", t.resolve_fbo_, t.resolve_color_,
                                        t.resolve_depth_);
      !st)
    return st.error();
  return t;
}

void OffscreenTarget::bind() const { glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id()); }

Image OffscreenTarget::readback() const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.id());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_.id());
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_.id());
  Image image(width_, height_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  flipRows(image.rgba, static_cast<size_t>(width_) * 4, height_);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return image;
}

void OffscreenTarget::readDepth(DepthImage& d) const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.id());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_.id());
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_.id());
  d.width = width_;
  d.height = height_;
  d.depth.resize(static_cast<size_t>(width_) * height_);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width_, height_, GL_DEPTH_COMPONENT, GL_FLOAT, d.depth.data());
  flipRows(d.depth, static_cast<size_t>(width_), height_);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void OffscreenTarget::blitToBound() const {
  GLint draw_fbo = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fbo);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.id());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_.id());
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_.id());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw_fbo));
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

}  // namespace lodline
