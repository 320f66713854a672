// Han, Wang, "Linear texture coordinate interpolation in rasterization", J. CAD & CG 23(6),
// 2011: §2 constant-depth lines, §3 per-triangle line arrays and the column/row traversal
// with an index offset, §4 error correction (denser lines, linear correction). See raster.h.
#include "raster/raster.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/result.h"
#include "core/timer.h"
#include "core/worker_pool.h"

namespace lodline {
namespace {

constexpr int kSubBits = 8;                 // vertex snapping: 1/256 px
constexpr int64_t kSub = 1 << kSubBits;
constexpr int64_t kHalf = kSub / 2;
constexpr float kGuardBand = 32.0f;         // clip x, y to ±32·w (keeps fixed point in int64)
constexpr int kMaxPolygon = 3 + 6;          // a triangle clipped by 6 planes

int64_t floorDiv(int64_t a, int64_t b) {
  int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}
int64_t ceilDiv(int64_t a, int64_t b) { return -floorDiv(-a, b); }

struct ClipVertex {
  glm::vec4 c;
  float a[kMaxAttributes];
};

// Signed distance to clip plane p (inside ≥ 0): near, far, −x, +x, −y, +y guard band.
float planeDistance(const glm::vec4& c, int p) {
  switch (p) {
    case 0: return c.z + c.w;
    case 1: return c.w - c.z;
    case 2: return kGuardBand * c.w + c.x;
    case 3: return kGuardBand * c.w - c.x;
    case 4: return kGuardBand * c.w + c.y;
    default: return kGuardBand * c.w - c.y;
  }
}

// One screen triangle ready for traversal. Coordinates (o, i) are (x, y) for the column
// traversal and (y, x) for the row traversal; o is the outer (per column/row) axis.
struct TriSetup {
  uint32_t face;
  uint8_t front;
  uint8_t rows;
  int x0, y0, x1, y1;               // inclusive pixel bounds, clamped to the image
  int64_t eo[3], ei[3], ec[3];      // edge E = eo·O + ei·I + ec (fixed point), inside ≥ 0
  double o_ref, i_ref;              // plane origin (vertex 0), pixels
  double z, zo, zi;                 // window depth plane (with polygon offset)
  double q, qo, qi;                 // 1/w plane
  double g;                         // di/do along constant-depth lines
  double vi_min, vi_max;            // range of the line coordinate λ over the three vertices
  double q_min;                     // least 1/w of the three vertices
  uint32_t planes;                  // offset of the attribute planes in the worker's array
};

struct Worker {
  std::vector<TriSetup> setups;
  std::vector<double> planes;                 // per setup: N × (p, po, pi) of attr/w, then N × affine
  std::vector<std::vector<uint32_t>> bins;    // per tile: indices into setups
  std::vector<float> lines;                   // constant-depth line arrays (scratch)
  size_t clipped = 0, fragments = 0, lines_computed = 0;
};

struct Frame {
  const RasterInput* in;
  const RasterParams* params;
  RasterTarget* target;
  int tiles_x, tiles_y, tile;
  size_t plane_size;
};

void setupScreenTriangle(const Frame& f, uint32_t face, const ClipVertex* v[3], Worker& w) {
  const int W = f.target->width, H = f.target->height, N = f.in->attribute_count;
  double px[3], py[3], pz[3], pq[3];
  int64_t X[3], Y[3];
  for (int k = 0; k < 3; ++k) {
    const double iw = 1.0 / static_cast<double>(v[k]->c.w);
    const double nx = v[k]->c.x * iw, ny = v[k]->c.y * iw, nz = v[k]->c.z * iw;
    // Clipping keeps |x|, |y| ≤ 32·w; non-finite input (e.g. an infinite vertex clipped to a
    // NaN) is dropped here, before the fixed-point conversion.
    if (!(std::abs(nx) <= 2.0 * kGuardBand && std::abs(ny) <= 2.0 * kGuardBand && std::isfinite(nz) &&
          iw > 0.0))
      return;
    X[k] = std::llround((nx * 0.5 + 0.5) * W * kSub);
    Y[k] = std::llround((0.5 - ny * 0.5) * H * kSub);
    px[k] = static_cast<double>(X[k]) / kSub;
    py[k] = static_cast<double>(Y[k]) / kSub;
    pz[k] = std::clamp(nz * 0.5 + 0.5, 0.0, 1.0);
    pq[k] = iw;
  }
  int64_t area2 = (X[1] - X[0]) * (Y[2] - Y[0]) - (Y[1] - Y[0]) * (X[2] - X[0]);
  if (area2 == 0) return;
  // OpenGL's front faces are counter-clockwise in window coordinates (y up), i.e. negative
  // area in these y-down pixel coordinates.
  const bool front = area2 < 0;
  if (!front && (f.params->cull_back_faces || (face < f.in->cull.size() && f.in->cull[face]))) return;
  int id[3] = {0, 1, 2};
  if (area2 < 0) std::swap(id[1], id[2]);
  const int64_t minX = std::min({X[0], X[1], X[2]}), maxX = std::max({X[0], X[1], X[2]});
  const int64_t minY = std::min({Y[0], Y[1], Y[2]}), maxY = std::max({Y[0], Y[1], Y[2]});
  const int x0 = static_cast<int>(std::max<int64_t>(ceilDiv(minX - kHalf, kSub), 0));
  const int x1 = static_cast<int>(std::min<int64_t>(floorDiv(maxX - kHalf, kSub), W - 1));
  const int y0 = static_cast<int>(std::max<int64_t>(ceilDiv(minY - kHalf, kSub), 0));
  const int y1 = static_cast<int>(std::min<int64_t>(floorDiv(maxY - kHalf, kSub), H - 1));
  if (x0 > x1 || y0 > y1) return;

  TriSetup t{};
  t.face = face;
  t.front = front ? 1 : 0;
  t.x0 = x0;
  t.x1 = x1;
  t.y0 = y0;
  t.y1 = y1;
  // Planes f(x, y) = f0 + fx·(x − x0) + fy·(y − y0) through the three snapped vertices.
  const double d1x = px[1] - px[0], d1y = py[1] - py[0], d2x = px[2] - px[0], d2y = py[2] - py[0];
  const double inv_det = 1.0 / (d1x * d2y - d1y * d2x);
  auto gradient = [&](double f0, double f1, double f2, double& fx, double& fy) {
    const double df1 = f1 - f0, df2 = f2 - f0;
    fx = (df1 * d2y - df2 * d1y) * inv_det;
    fy = (df2 * d1x - df1 * d2x) * inv_det;
  };
  double zx, zy, qx, qy;
  gradient(pz[0], pz[1], pz[2], zx, zy);
  gradient(pq[0], pq[1], pq[2], qx, qy);
  const double offset = f.params->depth_offset_factor * std::max(std::abs(zx), std::abs(zy)) +
                        f.params->depth_offset_units * std::ldexp(1.0, -24);
  // Han & Wang §2: 1/w is affine in screen space, so its level sets (constant depth) are
  // the parallel lines qx·x + qy·y = const. Walk in columns when they are closer to
  // horizontal (|g| ≤ 1), in rows otherwise, so each column/row meets each line once.
  const bool rows = std::abs(qx) > std::abs(qy);
  t.rows = rows ? 1 : 0;
  double g = 0.0;
  if (rows)
    g = -qy / qx;
  else if (qy != 0.0)
    g = -qx / qy;
  t.g = g;
  auto oc = [&](double x, double y) { return rows ? y : x; };
  auto ic = [&](double x, double y) { return rows ? x : y; };
  t.o_ref = oc(px[0], py[0]);
  t.i_ref = ic(px[0], py[0]);
  t.z = pz[0] + offset;
  t.zo = oc(zx, zy);
  t.zi = ic(zx, zy);
  t.q = pq[0];
  t.qo = oc(qx, qy);
  t.qi = ic(qx, qy);
  // Line coordinate λ = (i − 0.5) − g·(o − o0 − 0.5), o0 = first pixel column (row) of the
  // triangle: the constant-depth lines λ = j/m pass through pixel centres at column o0, the
  // same lattice in every tile.
  const double o0c = (rows ? y0 : x0) + 0.5;
  double vmin = 1e300, vmax = -1e300;
  for (int k = 0; k < 3; ++k) {
    const double l = ic(px[k], py[k]) - 0.5 - g * (oc(px[k], py[k]) - o0c);
    vmin = std::min(vmin, l);
    vmax = std::max(vmax, l);
  }
  t.vi_min = vmin;
  t.vi_max = vmax;
  t.q_min = std::min({pq[0], pq[1], pq[2]});
  // Edges of the counter-clockwise (positive area) ordering: E = dx·(Y − Yi) − dy·(X − Xi).
  // Top-left rule: a pixel centre exactly on an edge belongs to the triangle when the edge
  // is a left edge (dy < 0) or a top edge (dy = 0, dx > 0); otherwise E must be > 0.
  for (int e = 0; e < 3; ++e) {
    const int a = id[e], b = id[(e + 1) % 3];
    const int64_t dx = X[b] - X[a], dy = Y[b] - Y[a];
    const bool top_left = dy < 0 || (dy == 0 && dx > 0);
    const int64_t ex = -dy, ey = dx, c = dy * X[a] - dx * Y[a] - (top_left ? 0 : 1);
    t.eo[e] = rows ? ey : ex;
    t.ei[e] = rows ? ex : ey;
    t.ec[e] = c;
  }
  // Attribute planes: attr/w (perspective, evaluated divided by 1/w) and attr (affine).
  t.planes = static_cast<uint32_t>(w.planes.size());
  for (int a = 0; a < N; ++a) {
    double fx, fy;
    const double p0 = v[0]->a[a] * pq[0], p1 = v[1]->a[a] * pq[1], p2 = v[2]->a[a] * pq[2];
    gradient(p0, p1, p2, fx, fy);
    w.planes.push_back(p0);
    w.planes.push_back(oc(fx, fy));
    w.planes.push_back(ic(fx, fy));
  }
  for (int a = 0; a < N; ++a) {
    double fx, fy;
    gradient(v[0]->a[a], v[1]->a[a], v[2]->a[a], fx, fy);
    w.planes.push_back(v[0]->a[a]);
    w.planes.push_back(oc(fx, fy));
    w.planes.push_back(ic(fx, fy));
  }
  // Range of each attribute over the triangle (a perspective-correct value inside it is a
  // convex combination of the vertex values): clamps values read from lines that pass just
  // outside a nearly edge-on triangle, where extrapolation is unbounded.
  for (int a = 0; a < N; ++a) {
    w.planes.push_back(std::min({v[0]->a[a], v[1]->a[a], v[2]->a[a]}));
    w.planes.push_back(std::max({v[0]->a[a], v[1]->a[a], v[2]->a[a]}));
  }
  w.setups.push_back(t);
  // Bin into every tile the bounding box touches.
  const int ts = f.tile;
  for (int ty = y0 / ts; ty <= y1 / ts; ++ty)
    for (int tx = x0 / ts; tx <= x1 / ts; ++tx)
      w.bins[static_cast<size_t>(ty) * f.tiles_x + tx].push_back(static_cast<uint32_t>(w.setups.size() - 1));
}

// Clips face `face` in homogeneous clip space (Sutherland–Hodgman; each new vertex is
// interpolated from the inside endpoint to the outside one, so the two faces sharing a
// clipped edge get bit-identical vertices) and sets up the resulting fan.
void setupFace(const Frame& f, uint32_t face, Worker& w) {
  const RasterInput& in = *f.in;
  const int N = in.attribute_count;
  const auto& tri = in.faces[face];
  ClipVertex poly[2][kMaxPolygon];
  int n = 3;
  unsigned out_all = 0x3f, out_any = 0;
  for (int k = 0; k < 3; ++k) {
    ClipVertex& cv = poly[0][k];
    cv.c = in.clip[tri[k]];
    for (int a = 0; a < N; ++a) cv.a[a] = in.attributes[static_cast<size_t>(tri[k]) * N + a];
    unsigned code = 0;
    for (int p = 0; p < 6; ++p)
      if (!(planeDistance(cv.c, p) >= 0.0f)) code |= 1u << p;  // NaN counts as outside
    out_all &= code;
    out_any |= code;
  }
  if (out_all) return;  // entirely outside one plane
  int cur = 0;
  if (out_any) {
    ++w.clipped;
    for (int p = 0; p < 6 && n >= 3; ++p) {
      if (!(out_any & (1u << p))) continue;
      const ClipVertex* src = poly[cur];
      ClipVertex* dst = poly[1 - cur];
      int m = 0;
      for (int k = 0; k < n; ++k) {
        const ClipVertex& a = src[k];
        const ClipVertex& b = src[(k + 1) % n];
        const float da = planeDistance(a.c, p), db = planeDistance(b.c, p);
        const bool ina = da >= 0.0f, inb = db >= 0.0f;
        if (ina) dst[m++] = a;
        if (ina != inb) {
          const ClipVertex& i = ina ? a : b;  // inside endpoint first: order-independent
          const ClipVertex& o = ina ? b : a;
          const float di = ina ? da : db, d_o = ina ? db : da;
          const float t = di / (di - d_o);
          ClipVertex& r = dst[m++];
          r.c = i.c + t * (o.c - i.c);
          for (int q = 0; q < N; ++q) r.a[q] = i.a[q] + t * (o.a[q] - i.a[q]);
        }
      }
      n = m;
      cur = 1 - cur;
    }
  }
  for (int k = 1; k + 1 < n; ++k) {
    const ClipVertex* v[3] = {&poly[cur][0], &poly[cur][k], &poly[cur][k + 1]};
    setupScreenTriangle(f, face, v, w);
  }
}

// Per-pixel attribute evaluation for each mode, over one span of a column (or row).
enum class Mode { kNearest, kLinear, kExact, kExactDouble, kAffine };

template <Mode M>
void traverse(const Frame& f, const TriSetup& t, const double* planes, int tx0, int ty0, int tx1, int ty1,
              Worker& w) {
  RasterTarget& target = *f.target;
  const RasterParams& params = *f.params;
  const int N = f.in->attribute_count;
  const int W = target.width;
  const bool rows = t.rows != 0;
  // Tile ∩ triangle bounds in (o, i).
  const int o_lo = rows ? std::max(t.y0, ty0) : std::max(t.x0, tx0);
  const int o_hi = rows ? std::min(t.y1, ty1) : std::min(t.x1, tx1);
  const int i_lo = rows ? std::max(t.x0, tx0) : std::max(t.y0, ty0);
  const int i_hi = rows ? std::min(t.x1, tx1) : std::min(t.y1, ty1);
  if (o_lo > o_hi || i_lo > i_hi) return;
  const size_t stride_o = rows ? static_cast<size_t>(W) : 1, stride_i = rows ? 1 : static_cast<size_t>(W);
  float* depth = target.depth.depth.data();
  uint32_t* face_id = target.face_id.data();
  uint8_t* facing = target.front_facing.data();
  float* attrs = target.attributes.data();
  uint32_t* frags = params.count_fragments ? target.fragments.data() : nullptr;
  const size_t plane = f.plane_size;
  const int m = params.line_density;

  // Planes re-based to this tile's first pixel centre (o_t, i_t), so per-pixel offsets stay
  // small and single precision suffices even for huge (guard-band) triangles.
  const double o_t = o_lo + 0.5, i_t = i_lo + 0.5;
  const double so = o_t - t.o_ref, si = i_t - t.i_ref;
  const float zo = static_cast<float>(t.zo), zi = static_cast<float>(t.zi);
  const float z_t = static_cast<float>(t.z + t.zo * so + t.zi * si);
  float P[kMaxAttributes], Po[kMaxAttributes], Pi[kMaxAttributes];  // exact: attr/w; affine: attr
  float Q = 0.0f, Qo = 0.0f, Qi = 0.0f;
  if constexpr (M == Mode::kExact || M == Mode::kAffine) {
    const double* pl = M == Mode::kExact ? planes : planes + 3 * N;
    for (int a = 0; a < N; ++a) {
      P[a] = static_cast<float>(pl[3 * a] + pl[3 * a + 1] * so + pl[3 * a + 2] * si);
      Po[a] = static_cast<float>(pl[3 * a + 1]);
      Pi[a] = static_cast<float>(pl[3 * a + 2]);
    }
    Q = static_cast<float>(t.q + t.qo * so + t.qi * si);
    Qo = static_cast<float>(t.qo);
    Qi = static_cast<float>(t.qi);
  }

  // Han & Wang §3: the constant-depth lines crossing this tile. Line j is λ = j/m with
  // λ = (i − 0.5) − g·(o − o0 − 0.5) (o0 = the triangle's first column, so the lattice is the
  // same in every tile); it is stored as start value S_j at this tile's first column o_t and
  // step D_j per pixel of o along the line, per attribute:
  //   S_j = p(o_t, i_j) / q_j,  D_j = (p_o + p_i·g) / q_j,  q_j = q(o_t, i_j),
  //   i_j = j/m + 0.5 + g·(o_lo − o0),
  // with p = attr/w and q = 1/w affine in screen space. One division per line, none per pixel.
  const int o0 = rows ? t.y0 : t.x0;
  int64_t j_lo = 0;
  int line_count = 0;
  const float* L = nullptr;
  const double* range = planes + 6 * N;  // per attribute: min, max
  const int LS = 2 * N;  // floats per line
  if constexpr (M == Mode::kNearest || M == Mode::kLinear) {
    // λ over the covered pixels lies within both the tile box's range and the vertices'.
    double lo = 1e300, hi = -1e300;
    for (int oo : {o_lo, o_hi})
      for (int ii : {i_lo, i_hi}) {
        const double l = ii - t.g * (oo - o0);
        lo = std::min(lo, l);
        hi = std::max(hi, l);
      }
    lo = std::max(lo, t.vi_min);
    hi = std::min(hi, t.vi_max);
    if (lo > hi) hi = lo;  // rounding only: covered pixels lie in both ranges
    j_lo = static_cast<int64_t>(std::floor(lo * m)) - 1;
    const int64_t j_hi = static_cast<int64_t>(std::ceil(hi * m)) + 2;
    line_count = static_cast<int>(j_hi - j_lo + 1);
    if (w.lines.size() < static_cast<size_t>(line_count) * LS) w.lines.resize(static_cast<size_t>(line_count) * LS);
    float* out = w.lines.data();
    const double i_shift = 0.5 + t.g * (o_lo - o0) - t.i_ref;
    for (int k = 0; k < line_count; ++k) {
      const double di = static_cast<double>(j_lo + k) / m + i_shift;  // i_j − i_ref
      // Padding lines just outside the triangle extrapolate 1/w; keep it positive (beyond
      // the horizon of a grazing plane it would reach 0). Lines crossing it are unaffected.
      const double q_j = std::max(t.q + t.qo * so + t.qi * di, 0.5 * t.q_min);
      const double inv_q = 1.0 / q_j;
      for (int a = 0; a < N; ++a) {
        const double* p = planes + 3 * a;
        out[k * LS + a] = static_cast<float>((p[0] + p[1] * so + p[2] * di) * inv_q);
        out[k * LS + N + a] = static_cast<float>((p[1] + p[2] * t.g) * inv_q);
      }
    }
    w.lines_computed += static_cast<size_t>(line_count);
    L = out;
  }
  float a_min[kMaxAttributes], a_max[kMaxAttributes];
  for (int a = 0; a < N; ++a) {
    a_min[a] = static_cast<float>(range[2 * a]);
    a_max[a] = static_cast<float>(range[2 * a + 1]);
  }

  for (int o = o_lo; o <= o_hi; ++o) {
    // Span of pixel centres inside all three edges in this column (row): exact integers.
    const int64_t O = o * kSub + kHalf;
    int64_t lo = i_lo, hi = i_hi;
    for (int e = 0; e < 3; ++e) {
      const int64_t ei = t.ei[e];
      const int64_t K = t.eo[e] * O + t.ec[e] + ei * kHalf;  // E(i) = ei·kSub·i + K ≥ 0
      if (ei > 0)
        lo = std::max(lo, ceilDiv(-K, ei * kSub));
      else if (ei < 0)
        hi = std::min(hi, floorDiv(-K, ei * kSub));
      else if (K < 0)
        hi = lo - 1;
    }
    if (lo > hi) continue;
    const float d_o = static_cast<float>(o - o_lo);
    const float di0 = static_cast<float>(lo - i_lo);
    float z = z_t + zo * d_o + zi * di0;
    // Index offset of this column (Han & Wang §3): pixel i lies at scaled line coordinate
    // m·λ = m·i + base, base = −m·g·(o − o0); the fraction is the same down the column.
    int64_t line0 = 0;
    float frac = 0.0f;
    if constexpr (M == Mode::kNearest || M == Mode::kLinear) {
      const double base = -m * t.g * (o - o0);
      const double fl = std::floor(base);
      frac = static_cast<float>(base - fl);
      line0 = static_cast<int64_t>(fl) - j_lo;
      if constexpr (M == Mode::kNearest)
        if (frac >= 0.5f) ++line0;
    }
    float q = 0.0f;
    float p[kMaxAttributes];
    double qd = 0.0, pd[kMaxAttributes];
    if constexpr (M == Mode::kExactDouble) {
      const double od = so + (o - o_lo), id = si;  // offsets from the plane origin
      qd = t.q + t.qo * od + t.qi * id;
      for (int a = 0; a < N; ++a) pd[a] = planes[3 * a] + planes[3 * a + 1] * od + planes[3 * a + 2] * id;
    }
    if constexpr (M == Mode::kExact || M == Mode::kAffine) {
      q = Q + Qo * d_o + Qi * di0;
      for (int a = 0; a < N; ++a) p[a] = P[a] + Po[a] * d_o + Pi[a] * di0;
    }
    size_t idx = static_cast<size_t>(o) * stride_o + static_cast<size_t>(lo) * stride_i;
    w.fragments += static_cast<size_t>(hi - lo + 1);
    for (int64_t i = lo; i <= hi; ++i, idx += stride_i, z += zi) {
      if (frags) ++frags[idx];
      const float zc = std::clamp(z, 0.0f, 1.0f);
      const bool pass = !params.depth_test || zc < depth[idx];
      if (pass) {
        depth[idx] = zc;
        face_id[idx] = t.face;
        facing[idx] = t.front;
        if constexpr (M == Mode::kNearest || M == Mode::kLinear) {
          int64_t k = line0 + m * i;
          k = std::clamp<int64_t>(k, 0, line_count - 2);
          const float* l0 = L + k * LS;
          if constexpr (M == Mode::kNearest) {
            for (int a = 0; a < N; ++a)
              attrs[a * plane + idx] = std::clamp(l0[a] + l0[N + a] * d_o, a_min[a], a_max[a]);
          } else {
            const float* l1 = l0 + LS;
            for (int a = 0; a < N; ++a) {
              const float v0 = l0[a] + l0[N + a] * d_o, v1 = l1[a] + l1[N + a] * d_o;
              attrs[a * plane + idx] = std::clamp(v0 + frac * (v1 - v0), a_min[a], a_max[a]);
            }
          }
        } else if constexpr (M == Mode::kExact) {
          const float r = 1.0f / q;  // the per-pixel division the paper avoids
          for (int a = 0; a < N; ++a) attrs[a * plane + idx] = std::clamp(p[a] * r, a_min[a], a_max[a]);
        } else if constexpr (M == Mode::kExactDouble) {
          const double dd_i = static_cast<double>(i - i_lo);
          const double r = 1.0 / (qd + t.qi * dd_i);
          for (int a = 0; a < N; ++a) {
            const double v = (pd[a] + planes[3 * a + 2] * dd_i) * r;
            attrs[a * plane + idx] = std::clamp(static_cast<float>(v), a_min[a], a_max[a]);
          }
        } else {
          for (int a = 0; a < N; ++a) attrs[a * plane + idx] = std::clamp(p[a], a_min[a], a_max[a]);
        }
      }
      if constexpr (M == Mode::kExact || M == Mode::kAffine) {
        q += Qi;
        for (int a = 0; a < N; ++a) p[a] += Pi[a];
      }
    }
  }
}

}  // namespace

const char* interpolationName(Interpolation m) {
  switch (m) {
    case Interpolation::kConstantDepth: return "constant-depth";
    case Interpolation::kExact: return "exact";
    case Interpolation::kAffine: return "affine";
  }
  return "?";
}

void RasterTarget::resize(int w, int h, int attributes_per_pixel) {
  width = w;
  height = h;
  attribute_count = attributes_per_pixel;
  const size_t n = static_cast<size_t>(w) * h;
  depth.width = w;
  depth.height = h;
  depth.depth.resize(n);
  face_id.resize(n);
  front_facing.resize(n);
  attributes.resize(n * static_cast<size_t>(attributes_per_pixel));
  fragments.resize(n);
  clear();
}

void RasterTarget::clear() {
  std::fill(depth.depth.begin(), depth.depth.end(), 1.0f);
  std::fill(face_id.begin(), face_id.end(), kNoFace);
  std::fill(front_facing.begin(), front_facing.end(), uint8_t{0});
  std::fill(attributes.begin(), attributes.end(), 0.0f);
  std::fill(fragments.begin(), fragments.end(), 0u);
}

ConstantDepthSlope constantDepthSlope(const glm::vec4& c0, const glm::vec4& c1, const glm::vec4& c2,
                                      int width, int height) {
  double px[3], py[3], pq[3];
  const glm::vec4* c[3] = {&c0, &c1, &c2};
  for (int k = 0; k < 3; ++k) {
    pq[k] = 1.0 / c[k]->w;
    px[k] = (c[k]->x * pq[k] * 0.5 + 0.5) * width;
    py[k] = (0.5 - c[k]->y * pq[k] * 0.5) * height;
  }
  const double d1x = px[1] - px[0], d1y = py[1] - py[0], d2x = px[2] - px[0], d2y = py[2] - py[0];
  const double det = d1x * d2y - d1y * d2x;
  if (det == 0.0) return {};
  const double df1 = pq[1] - pq[0], df2 = pq[2] - pq[0];
  const double qx = (df1 * d2y - df2 * d1y) / det, qy = (df2 * d1x - df1 * d2x) / det;
  ConstantDepthSlope s;
  s.rows = std::abs(qx) > std::abs(qy);
  if (s.rows)
    s.g = static_cast<float>(-qy / qx);
  else if (qy != 0.0)
    s.g = static_cast<float>(-qx / qy);
  return s;
}

struct SoftRasterizer::Impl {
  std::vector<Worker> workers;
  std::shared_ptr<WorkerPool> pool;
  bool pool_given = false;  // by setWorkerPool(): RasterParams::threads does not apply
};

SoftRasterizer::SoftRasterizer() : impl_(std::make_unique<Impl>()) {}
SoftRasterizer::~SoftRasterizer() = default;
SoftRasterizer::SoftRasterizer(SoftRasterizer&&) noexcept = default;
SoftRasterizer& SoftRasterizer::operator=(SoftRasterizer&&) noexcept = default;

void SoftRasterizer::draw(const RasterInput& input, const RasterParams& params, RasterTarget& target) {
  stats_ = {};
  stats_.triangles_in = input.faces.size();
  if (target.width <= 0 || target.height <= 0 || input.faces.empty()) return;
  LODLINE_ASSERT(input.attribute_count >= 0 && input.attribute_count <= kMaxAttributes);
  LODLINE_ASSERT(target.attribute_count >= input.attribute_count);
  LODLINE_ASSERT(input.attributes.size() >= input.clip.size() * static_cast<size_t>(input.attribute_count));
  RasterParams p = params;
  p.line_density = p.line_density >= 4 ? 4 : p.line_density >= 2 ? 2 : 1;
  p.tile_size = std::clamp(p.tile_size, 16, 1024);
  if (p.count_fragments && target.fragments.size() != target.depth.depth.size())
    target.fragments.assign(target.depth.depth.size(), 0u);
  // The pool's threads each get a slot: a contiguous range of faces to set up and bin, and
  // their scratch while drawing tiles.
  WorkerPool& pool = workerPool(p.threads);
  const int threads = static_cast<int>(pool.threadCount());

  Frame f{&input, &p, &target, 0, 0, p.tile_size, static_cast<size_t>(target.width) * target.height};
  f.tiles_x = (target.width + f.tile - 1) / f.tile;
  f.tiles_y = (target.height + f.tile - 1) / f.tile;
  const size_t tile_count = static_cast<size_t>(f.tiles_x) * f.tiles_y;
  auto& workers = impl_->workers;
  if (workers.size() < static_cast<size_t>(threads)) workers.resize(threads);
  for (int t = 0; t < threads; ++t) {
    Worker& w = workers[t];
    w.setups.clear();
    w.planes.clear();
    w.bins.resize(tile_count);
    for (auto& b : w.bins) b.clear();
    const size_t share = input.faces.size() / threads + 1;  // no-ops once warmed up
    w.setups.reserve(share);
    w.planes.reserve(share * (8 * static_cast<size_t>(input.attribute_count)));
    w.clipped = w.fragments = w.lines_computed = 0;
  }

  Mode mode = Mode::kLinear;
  if (p.interpolation == Interpolation::kExact)
    mode = p.double_precision ? Mode::kExactDouble : Mode::kExact;
  else if (p.interpolation == Interpolation::kAffine)
    mode = Mode::kAffine;
  else if (!p.linear_correction)
    mode = Mode::kNearest;

  Stopwatch sw;
  // 1. Setup and binning: slot t takes a contiguous range of faces, so each tile's bins,
  //    read in slot order, keep the face order whatever the thread count.
  const size_t nf = input.faces.size();
  pool.forRange(static_cast<size_t>(threads), 1, [&](size_t t0, size_t t1) {
    for (size_t t = t0; t < t1; ++t)
      for (size_t fi = nf * t / threads, end = nf * (t + 1) / threads; fi < end; ++fi)
        setupFace(f, static_cast<uint32_t>(fi), workers[t]);
  });
  stats_.ms_setup = sw.lap();
  // 2. Tiles, each drawing the triangles of all slots' bins in face order, with the
  //    running thread's slot as scratch.
  pool.forRangeWithSlot(tile_count, 1, [&](size_t tile0, size_t tile1, unsigned slot) {
    Worker& w = workers[slot];
    for (size_t tile = tile0; tile < tile1; ++tile) {
      const int tx = static_cast<int>(tile % f.tiles_x), ty = static_cast<int>(tile / f.tiles_x);
      const int x0 = tx * f.tile, y0 = ty * f.tile;
      const int x1 = std::min(x0 + f.tile, target.width) - 1, y1 = std::min(y0 + f.tile, target.height) - 1;
      for (int s = 0; s < threads; ++s) {
        const Worker& src = workers[s];
        for (uint32_t idx : src.bins[tile]) {
          const TriSetup& ts = src.setups[idx];
          const double* planes = src.planes.data() + ts.planes;
          switch (mode) {
            case Mode::kNearest: traverse<Mode::kNearest>(f, ts, planes, x0, y0, x1, y1, w); break;
            case Mode::kLinear: traverse<Mode::kLinear>(f, ts, planes, x0, y0, x1, y1, w); break;
            case Mode::kExact: traverse<Mode::kExact>(f, ts, planes, x0, y0, x1, y1, w); break;
            case Mode::kExactDouble: traverse<Mode::kExactDouble>(f, ts, planes, x0, y0, x1, y1, w); break;
            case Mode::kAffine: traverse<Mode::kAffine>(f, ts, planes, x0, y0, x1, y1, w); break;
          }
        }
      }
    }
  });
  stats_.ms_raster = sw.lap();
  for (int t = 0; t < threads; ++t) {
    stats_.triangles_drawn += workers[t].setups.size();
    stats_.clipped += workers[t].clipped;
    stats_.fragments += workers[t].fragments;
    stats_.lines += workers[t].lines_computed;
  }
}

WorkerPool& SoftRasterizer::workerPool(int threads) {
  if (!impl_->pool ||
      (!impl_->pool_given && threads > 0 && impl_->pool->threadCount() != static_cast<unsigned>(threads)))
    impl_->pool = std::make_shared<WorkerPool>(threads > 0 ? static_cast<unsigned>(threads) : 0u);
  return *impl_->pool;
}

void SoftRasterizer::setWorkerPool(std::shared_ptr<WorkerPool> pool) {
  impl_->pool = std::move(pool);
  impl_->pool_given = impl_->pool != nullptr;
}

void rasterize(const RasterInput& input, const RasterParams& params, RasterTarget& target) {
  SoftRasterizer r;
  r.draw(input, params, target);
}

}  // namespace lodline
