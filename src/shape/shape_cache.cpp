// Rusinkiewicz 2004, "Estimating Curvatures and Their Derivatives on Triangle Meshes",
// §3–§4; corner areas after Meyer et al. 2002 §3.3. See shape_cache.h.
#include "shape/shape_cache.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <iterator>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "core/result.h"
#include "core/simd_clones.h"
#include "shape/fit_lanes.h"

namespace lodline {
namespace {

constexpr uint8_t kGeomOk = 1, kCurvOk = 2, kDcurvOk = 4;
// What the lane kernels read for lanes without a face (a short block, an invalid face).
alignas(16) constexpr float kZeros[12] = {};

// Runs a lane kernel (fit_lanes.h) on faces[0 .. count), count ≤ lanes::kWidth: each lane's
// input pointers from gather(face, in, lane) where has_input(face) (kZeros otherwise, and for
// the lanes past count), then store(face, out, lane, ok) for each face.
template <int kInputs, class Has, class Gather, class Kernel, class Store>
void runFaceKernel(const uint32_t* faces, uint32_t count, float* out, Has has_input, Gather gather,
                   Kernel kernel, Store store) {
  constexpr int W = lanes::kWidth;
  const float* in[kInputs * W];
  std::fill(std::begin(in), std::end(in), kZeros);
  alignas(32) int32_t ok[W];
  for (uint32_t l = 0; l < count; ++l)
    if (has_input(faces[l])) gather(faces[l], in, static_cast<int>(l));
  kernel(in, out, ok);
  for (uint32_t l = 0; l < count; ++l) store(faces[l], out, static_cast<int>(l), ok[l] != 0);
}
const glm::vec3 kFallbackNormal{0.0f, 0.0f, 1.0f};

inline int nextCorner(int j) { return j == 2 ? 0 : j + 1; }
inline int prevCorner(int j) { return j == 0 ? 2 : j - 1; }

inline bool finite3(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Orthonormal (u, v) with u × v = n, a pure function of the unit normal n (Duff et al.,
// "Building an Orthonormal Basis, Revisited", JCGT 2017).
inline void frameFromNormal(const glm::vec3& n, glm::vec3& u, glm::vec3& v) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  u = glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  u = glm::normalize(u);
  v = glm::cross(n, u);
}

// Mixed Voronoi corner areas of a triangle (docs/design.md §3.1); e[j] is the edge
// opposite corner j, `area` the triangle area (> 0).
inline void cornerAreasOf(const glm::vec3 e[3], float area, std::array<float, 3>& out) {
  const float l2[3] = {glm::dot(e[0], e[0]), glm::dot(e[1], e[1]), glm::dot(e[2], e[2])};
  const float ew[3] = {l2[0] * (l2[1] + l2[2] - l2[0]), l2[1] * (l2[2] + l2[0] - l2[1]),
                       l2[2] * (l2[0] + l2[1] - l2[2])};
  // Obtuse at corner j: the other two corners get (l/8)·tan(angle) each, j the rest.
  for (int j = 0; j < 3; ++j) {
    if (ew[j] <= 0.0f) {
      const int j1 = nextCorner(j), j2 = prevCorner(j);
      // Corner j1 lies between edges e[j] and e[j2] (the edge j–j1 is e[j2]).
      out[j1] = -0.25f * l2[j2] * area / glm::dot(e[j], e[j2]);
      out[j2] = -0.25f * l2[j1] * area / glm::dot(e[j], e[j1]);
      out[j] = area - out[j1] - out[j2];
      for (float& c : out)
        if (!std::isfinite(c) || c < 0.0f) c = 0.0f;
      return;
    }
  }
  const float scale = 0.5f * area / (ew[0] + ew[1] + ew[2]);
  for (int j = 0; j < 3; ++j) out[j] = scale * (ew[nextCorner(j)] + ew[prevCorner(j)]);
}

// Re-expresses the second fundamental form k = (ku, kuv, kv) of the old frame in the new
// frame whose axes have old-frame coordinates (u1, v1) and (u2, v2). T is float (the vertex
// gathers) or lanes::FL (the face kernels): one expression, so both compute the same bits.
template <class T>
[[gnu::always_inline]] inline void projectCurvature(const T (&k)[3], T u1, T v1, T u2, T v2, T (&out)[3]) {
  out[0] = k[0] * u1 * u1 + k[1] * (2.0f * u1 * v1) + k[2] * v1 * v1;
  out[1] = k[0] * u1 * u2 + k[1] * (u1 * v2 + u2 * v1) + k[2] * v1 * v2;
  out[2] = k[0] * u2 * u2 + k[1] * (2.0f * u2 * v2) + k[2] * v2 * v2;
}

// Same for the cubic derivative form c = (C_uuu, C_uuv, C_uvv, C_vvv).
template <class T>
[[gnu::always_inline]] inline void projectDerivative(const T (&c)[4], T u1, T v1, T u2, T v2, T (&out)[4]) {
  out[0] = c[0] * u1 * u1 * u1 + c[1] * 3.0f * u1 * u1 * v1 + c[2] * 3.0f * u1 * v1 * v1 + c[3] * v1 * v1 * v1;
  out[1] = c[0] * u1 * u1 * u2 + c[1] * (u1 * u1 * v2 + 2.0f * u2 * u1 * v1) +
           c[2] * (u2 * v1 * v1 + 2.0f * u1 * v1 * v2) + c[3] * v1 * v1 * v2;
  out[2] = c[0] * u1 * u2 * u2 + c[1] * (u2 * u2 * v1 + 2.0f * u1 * u2 * v2) +
           c[2] * (u1 * v2 * v2 + 2.0f * u2 * v2 * v1) + c[3] * v1 * v2 * v2;
  out[3] = c[0] * u2 * u2 * u2 + c[1] * 3.0f * u2 * u2 * v2 + c[2] * 3.0f * u2 * v2 * v2 + c[3] * v2 * v2 * v2;
}

// Principal frame of a vertex relative to a face: given the corner relation m (vertex frame
// axes (u, w) in face coordinates) and pdir1 = a·u + b·w, pdir2 = −b·u + a·w, the face
// coordinates of pdir1 and pdir2 as q = (u1, v1, u2, v2).
template <class T>
[[gnu::always_inline]] inline void principalInFace(const T (&m)[4], T a, T b, T (&q)[4]) {
  q[0] = a * m[0] + b * m[2];
  q[1] = a * m[1] + b * m[3];
  q[2] = -b * m[0] + a * m[2];
  q[3] = -b * m[1] + a * m[3];
}

// Solves the symmetric tridiagonal system with diagonal d[0..N) and off-diagonal o[0..N-1)
// (the full matrix: entry (i, i+1) = entry (i+1, i) = o[i]; cf. docs/design.md §3.2 on the
// upper-triangle-only bug) in double, through its inverse written with continuants (Usmani
// 1994, "Inversion of a tridiagonal Jacobi matrix"): with θ_k the determinant of the leading
// k×k block and φ_k that of the trailing block from row k,
//   (T⁻¹)_ij = (−1)^(i+j) · o_i···o_(j−1) · θ_i · φ_(j+1) / θ_N   for i ≤ j.
// One division in all, where LDLᵀ divides N + N − 1 times in a dependent chain. The mask is
// false (x then holds garbage) when a pivot θ_(k+1)/θ_k of that LDLᵀ is not clearly positive
// (a degenerate face), tested without dividing as θ_(k+1) > 1e-10·scale·θ_k, or when the
// solution is not finite. D is lanes::DL (fit_lanes.h).
template <int N, class D>
[[gnu::always_inline]] inline auto solveSymTridiagonal(const D (&d)[N], const D (&o)[N - 1], D (&x)[N]) {
  using lanes::both;
  using lanes::finite;
  D scale{};
  for (int i = 0; i < N; ++i) {
    const D ad = lanes::absValue(d[i]);
    scale = lanes::select(scale < ad, ad, scale);
  }
  auto ok = both(scale > D{}, finite(scale));
  const D eps = 1e-10 * scale;
  D theta[N + 1], phi[N + 1];
  theta[0] = D{} + 1.0;
  theta[1] = d[0];
  ok = both(ok, theta[1] > eps);
  for (int k = 2; k <= N; ++k) {
    theta[k] = d[k - 1] * theta[k - 1] - o[k - 2] * o[k - 2] * theta[k - 2];
    ok = both(ok, theta[k] > eps * theta[k - 1]);
  }
  phi[N] = D{} + 1.0;
  phi[N - 1] = d[N - 1];
  for (int k = N - 2; k >= 0; --k) phi[k] = d[k] * phi[k + 1] - o[k] * o[k] * phi[k + 2];
  const D inv_det = 1.0 / theta[N];
  D y[N];
  for (int i = 0; i < N; ++i) {
    D sum{};
    for (int j = 0; j < N; ++j) {
      const int lo = std::min(i, j), hi = std::max(i, j);
      D c = theta[lo] * phi[hi + 1];
      for (int k = lo; k < hi; ++k) c = c * -o[k];
      sum = sum + c * x[j];
    }
    y[i] = sum * inv_det;
  }
  for (int i = 0; i < N; ++i) {
    ok = both(ok, finite(y[i]));
    x[i] = y[i];
  }
  return ok;
}

// The per-face kernels (face geometry; the fits of Rusinkiewicz 2004 §3–§4), for
// lanes::kWidth faces at a time (fit_lanes.h). Their outputs travel as rows of W floats, one
// per lane: `out[k * W + lane]`.
namespace fit {

using F = lanes::FL;
constexpr int W = lanes::kWidth;

// The kernels read their inputs through `src[group * W + lane]`: per group of inputs, a
// pointer to the floats of that group for each lane (lanes::gather).
// Curvature fit inputs: the corners' positions, the vertex frames (n, u, w: 9 floats) at the
// corners, the face normal (the face frame's t and b follow from them: faceFrame()).
constexpr int kP = 0, kFrame = 3, kFn = 6, kCurvIn = 7;
// Outputs: the corner relations rel[j] (4 each), the face's (e, f, g), and (e, f, g) in each
// corner's vertex frame, the term that corner's vertex sums (vertexCurvature()).
constexpr int kRel = 0, kCurv = 12, kCurvTerm = 15, kCurvOut = 24;
// Derivative fit inputs: positions, the face normal, the corner relations (12 floats), the
// vertices' (k1, k2, a, b). Outputs: the face's derivative tensor, and the tensor in each corner's
// principal frame, the term that corner's vertex sums (vertexDerivative()).
constexpr int kDP = 0, kDFn = 3, kDRel = 4, kDKab = 5, kDerivIn = 8;
constexpr int kDcurv = 0, kDcurvTerm = 4, kDerivOut = 16;

// Three consecutive floats from offset k of input group g.
inline lanes::Vec3L<F> load3(const float* const* src, int g, int k = 0) {
  return {lanes::gather(src + g * W, k), lanes::gather(src + g * W, k + 1),
          lanes::gather(src + g * W, k + 2)};
}

[[gnu::always_inline]] inline lanes::Vec3L<F> cross(const lanes::Vec3L<F>& x, const lanes::Vec3L<F>& y) {
  return {x.y * y.z - y.y * x.z, x.z * y.x - y.z * x.x, x.x * y.y - y.x * x.y};  // as glm::cross
}

// The face frame of corners p0, p1, p2 with unit normal n: t along the edge opposite corner 0
// (as glm::normalize: e · 1/√(e·e)), b = n × t. Recomputed where needed rather than stored:
// every kernel computes it with these operations, so it has the same bits in each.
[[gnu::always_inline]] inline void faceFrame(const lanes::Vec3L<F>& p1, const lanes::Vec3L<F>& p2,
                                             const lanes::Vec3L<F>& n, lanes::Vec3L<F>& t,
                                             lanes::Vec3L<F>& b) {
  const lanes::Vec3L<F> e0 = p2 - p1;
  const F inv = 1.0f / lanes::sqrtLanes(lanes::dot(e0, e0));
  t = {e0.x * inv, e0.y * inv, e0.z * inv};
  b = cross(n, t);
}

// The face frame relative to each corner's vertex frame (Rusinkiewicz 2004 §3, "rotating the
// coordinate system": the vertex frame is turned about n_v × n_f into the face's plane, and
// the relation is its axes' coordinates in the face frame; an antipodal normal flips it),
// then the least-squares fit of the second fundamental form to the normal differences along
// the three edges. Returns the fit's mask.
[[gnu::always_inline]] inline auto curvatureFit(const float* const* in, float* out) {
  using lanes::dot;
  using lanes::select;
  using lanes::toDouble;
  using V = lanes::Vec3L<F>;
  using D = lanes::DL;
  V p[3], n[3], u[3], w[3];
  for (int j = 0; j < 3; ++j) {
    p[j] = load3(in, kP + j);
    n[j] = load3(in, kFrame + j, 0);
    u[j] = load3(in, kFrame + j, 3);
    w[j] = load3(in, kFrame + j, 6);
  }
  const V fn = load3(in, kFn);
  V ft, fb;
  faceFrame(p[1], p[2], fn, ft, fb);
  F rel[3][4];
  for (int j = 0; j < 3; ++j) {
    // The vertex frame (u_j, w_j) of normal n_j turned into the plane of fn.
    const F ndot = dot(n[j], fn);
    const V perp_old = fn - ndot * n[j];
    const V dperp = (1.0f / (1.0f + ndot)) * (n[j] + fn);
    const V ru = u[j] - dot(u[j], perp_old) * dperp;
    const V rv = w[j] - dot(w[j], perp_old) * dperp;
    const auto flip = ndot <= -1.0f;
    const V fu{select(flip, -u[j].x, ru.x), select(flip, -u[j].y, ru.y), select(flip, -u[j].z, ru.z)};
    const V fv{select(flip, -w[j].x, rv.x), select(flip, -w[j].y, rv.y), select(flip, -w[j].z, rv.z)};
    rel[j][0] = dot(fu, ft);
    rel[j][1] = dot(fu, fb);
    rel[j][2] = dot(fv, ft);
    rel[j][3] = dot(fv, fb);
    for (int i = 0; i < 4; ++i) lanes::store(out + (kRel + 4 * j + i) * W, rel[j][i]);
  }
  D a{}, b{}, c{}, m[3] = {D{}, D{}, D{}};
  for (int j = 0; j < 3; ++j) {
    const int jp = j == 0 ? 2 : j - 1, jn = j == 2 ? 0 : j + 1;
    const V e = p[jp] - p[jn];
    const V dn = n[jp] - n[jn];
    const D eu = toDouble(dot(e, ft)), ev = toDouble(dot(e, fb));
    const D dnu = toDouble(dot(dn, ft)), dnv = toDouble(dot(dn, fb));
    a = a + eu * eu;
    b = b + eu * ev;
    c = c + ev * ev;
    m[0] = m[0] + dnu * eu;
    m[1] = m[1] + (dnu * ev + dnv * eu);
    m[2] = m[2] + dnv * ev;
  }
  // Normal equations of Δn_t = e·u + f·v, Δn_b = f·u + g·v over the three edges:
  // [[Σu², Σuv, 0], [Σuv, Σu²+Σv², Σuv], [0, Σuv, Σv²]] (full symmetric matrix).
  const D d[3] = {a, a + c, c};
  const D o[2] = {b, b};
  const auto ok = solveSymTridiagonal<3>(d, o, m);
  const F k[3] = {lanes::toFloat(m[0]), lanes::toFloat(m[1]), lanes::toFloat(m[2])};
  for (int i = 0; i < 3; ++i) lanes::store(out + (kCurv + i) * W, k[i]);
  // The face's (e, f, g) in each corner's vertex frame.
  for (int j = 0; j < 3; ++j) {
    F t[3];
    projectCurvature(k, rel[j][0], rel[j][1], rel[j][2], rel[j][3], t);
    for (int i = 0; i < 3; ++i) lanes::store(out + (kCurvTerm + 3 * j + i) * W, t[i]);
  }
  return lanes::toFloatMask(ok);
}

// Each corner's curvature re-expressed in the face frame, then the least-squares fit of the
// derivative tensor C to its differences along the three edges (Rusinkiewicz 2004 §4).
[[gnu::always_inline]] inline auto derivativeFit(const float* const* in, float* out) {
  using lanes::dot;
  using lanes::toDouble;
  using V = lanes::Vec3L<F>;
  using D = lanes::DL;
  V p[3], fcurv[3];
  F principal[3][4];  // per corner, the vertex's principal axes in face coordinates
  for (int j = 0; j < 3; ++j) {
    p[j] = load3(in, kDP + j);
    const float* const* rel = in + kDRel * W;
    const float* const* kab = in + (kDKab + j) * W;
    const F m[4] = {lanes::gather(rel, 4 * j), lanes::gather(rel, 4 * j + 1), lanes::gather(rel, 4 * j + 2),
                    lanes::gather(rel, 4 * j + 3)};
    // The vertex's curvature diag(k1, k2) in face coordinates: the face axes in principal
    // coordinates are the transpose of its principal axes in face coordinates.
    const F kp[3] = {lanes::gather(kab, 0), F{}, lanes::gather(kab, 1)};
    principalInFace(m, lanes::gather(kab, 2), lanes::gather(kab, 3), principal[j]);
    const F(&q)[4] = principal[j];
    F fc[3];
    projectCurvature(kp, q[0], q[2], q[1], q[3], fc);
    fcurv[j] = V{fc[0], fc[1], fc[2]};
  }
  V ft, fb;
  faceFrame(p[1], p[2], load3(in, kDFn), ft, fb);
  D a{}, b{}, c{}, m[4] = {D{}, D{}, D{}, D{}};
  for (int j = 0; j < 3; ++j) {
    const int jp = j == 0 ? 2 : j - 1, jn = j == 2 ? 0 : j + 1;
    const V e = p[jp] - p[jn];
    const V dk = fcurv[jp] - fcurv[jn];
    const D eu = toDouble(dot(e, ft)), ev = toDouble(dot(e, fb));
    const D dk0 = toDouble(dk.x), dk1 = toDouble(dk.y), dk2 = toDouble(dk.z);
    a = a + eu * eu;
    b = b + eu * ev;
    c = c + ev * ev;
    m[0] = m[0] + eu * dk0;
    m[1] = m[1] + (ev * dk0 + 2.0 * eu * dk1);
    m[2] = m[2] + (2.0 * ev * dk1 + eu * dk2);
    m[3] = m[3] + ev * dk2;
  }
  // Normal equations of Δe = C0·u + C1·v, Δf = C1·u + C2·v (weight 2), Δg = C2·u + C3·v:
  // tridiagonal [Σu², 2Σu²+Σv², Σu²+2Σv², Σv²] with off-diagonal [Σuv, 2Σuv, Σuv].
  const D d[4] = {a, 2.0 * a + c, a + 2.0 * c, c};
  const D o[3] = {b, 2.0 * b, b};
  const auto ok = solveSymTridiagonal<4>(d, o, m);
  const F cd[4] = {lanes::toFloat(m[0]), lanes::toFloat(m[1]), lanes::toFloat(m[2]), lanes::toFloat(m[3])};
  for (int i = 0; i < 4; ++i) lanes::store(out + (kDcurv + i) * W, cd[i]);
  // The tensor in each corner vertex's principal frame.
  for (int j = 0; j < 3; ++j) {
    F t[4];
    projectDerivative(cd, principal[j][0], principal[j][1], principal[j][2], principal[j][3], t);
    for (int i = 0; i < 4; ++i) lanes::store(out + (kDcurvTerm + 4 * j + i) * W, t[i]);
  }
  return lanes::toFloatMask(ok);
}

// Face geometry inputs: the corners' positions. Outputs: the unit normal, the corner areas,
// twice the area, the squared edge lengths and, per corner j, e[j−1]·e[j+1] (the normal
// weights' inputs).
constexpr int kGP = 0, kGeomIn = 3;
constexpr int kGN = 0, kGCorner = 3, kGLen = 6, kGL2 = 7, kGDot = 10, kGeomOut = 13;

// faceNormalOf, glm::normalize and cornerAreasOf over lanes (the obtuse cases as selects,
// the first obtuse corner winning as in cornerAreasOf's loop). Returns the mask of faces with
// a finite normal, a positive area and a finite edge direction.
[[gnu::always_inline]] inline auto faceGeometry(const float* const* in, float* out) {
  using lanes::both;
  using lanes::dot;
  using lanes::finite;
  using lanes::select;
  using V = lanes::Vec3L<F>;
  const V p0 = load3(in, kGP), p1 = load3(in, kGP + 1), p2 = load3(in, kGP + 2);
  const V e[3] = {p2 - p1, p0 - p2, p1 - p0};
  const V cr = cross(p2 - p1, p0 - p2);
  const F len = lanes::sqrtLanes(dot(cr, cr));
  const V n{cr.x / len, cr.y / len, cr.z / len};
  V t, b;
  faceFrame(p1, p2, n, t, b);  // only t's finiteness is asked here; the fits recompute both
  auto ok = both(len > 0.0f, finite(len));
  ok = both(ok, both(finite(n.x), both(finite(n.y), finite(n.z))));
  ok = both(ok, both(finite(t.x), both(finite(t.y), finite(t.z))));
  // Corner areas (cornerAreasOf).
  const F area = 0.5f * len;
  const F l2[3] = {dot(e[0], e[0]), dot(e[1], e[1]), dot(e[2], e[2])};
  const F ew[3] = {l2[0] * (l2[1] + l2[2] - l2[0]), l2[1] * (l2[2] + l2[0] - l2[1]),
                   l2[2] * (l2[0] + l2[1] - l2[2])};
  const F scale = 0.5f * area / (ew[0] + ew[1] + ew[2]);
  F corner[3];
  for (int j = 0; j < 3; ++j) {
    const int jn = j == 2 ? 0 : j + 1, jp = j == 0 ? 2 : j - 1;
    corner[j] = scale * (ew[jn] + ew[jp]);
  }
  for (int j = 2; j >= 0; --j) {  // obtuse at corner j: the lowest such j decides
    const int j1 = j == 2 ? 0 : j + 1, j2 = j == 0 ? 2 : j - 1;
    F c[3];
    c[j1] = -0.25f * l2[j2] * area / dot(e[j], e[j2]);
    c[j2] = -0.25f * l2[j1] * area / dot(e[j], e[j1]);
    c[j] = area - c[j1] - c[j2];
    const auto obtuse = ew[j] <= 0.0f;
    for (int i = 0; i < 3; ++i) {
      const F clamped = select(both(finite(c[i]), c[i] >= 0.0f), c[i], F{});
      corner[i] = select(obtuse, clamped, corner[i]);
    }
  }
  auto put = [&](int k, const V& v) {
    lanes::store(out + k * W, v.x);
    lanes::store(out + (k + 1) * W, v.y);
    lanes::store(out + (k + 2) * W, v.z);
  };
  put(kGN, n);
  for (int j = 0; j < 3; ++j) {
    const int jn = j == 2 ? 0 : j + 1, jp = j == 0 ? 2 : j - 1;
    lanes::store(out + (kGCorner + j) * W, corner[j]);
    lanes::store(out + (kGL2 + j) * W, l2[j]);
    lanes::store(out + (kGDot + j) * W, dot(e[jp], e[jn]));
  }
  lanes::store(out + kGLen * W, len);
  return ok;
}

LODLINE_AVX2_CLONES void faceGeometryLanes(const float* const* in, float* out, int32_t* ok) {
  lanes::storeMask(ok, faceGeometry(in, out));
}

// lanes::kWidth faces at once; built for AVX2 as well as the baseline, picked at load.
LODLINE_AVX2_CLONES void curvatureFitLanes(const float* const* in, float* out, int32_t* ok) {
  lanes::storeMask(ok, curvatureFit(in, out));
}
LODLINE_AVX2_CLONES void derivativeFitLanes(const float* const* in, float* out, int32_t* ok) {
  lanes::storeMask(ok, derivativeFit(in, out));
}

}  // namespace fit

}  // namespace

float cubicForm(const glm::vec4& c, glm::vec2 a, glm::vec2 b, glm::vec2 d) {
  return c[0] * a.x * b.x * d.x + c[1] * (a.x * b.x * d.y + a.x * b.y * d.x + a.y * b.x * d.x) +
         c[2] * (a.x * b.y * d.y + a.y * b.x * d.y + a.y * b.y * d.x) + c[3] * a.y * b.y * d.y;
}

void computeCornerAreas(const TriMesh& mesh, std::vector<std::array<float, 3>>& corner_areas,
                        std::vector<float>& point_areas) {
  const size_t nv = mesh.positions.size();
  corner_areas.assign(mesh.faces.size(), {0.0f, 0.0f, 0.0f});
  point_areas.assign(nv, 0.0f);
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv || t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      continue;
    const glm::vec3& p0 = mesh.positions[t[0]];
    const glm::vec3& p1 = mesh.positions[t[1]];
    const glm::vec3& p2 = mesh.positions[t[2]];
    const glm::vec3 e[3] = {p2 - p1, p0 - p2, p1 - p0};
    const float area = 0.5f * glm::length(glm::cross(e[0], e[1]));
    if (!(area > 0.0f) || !std::isfinite(area)) continue;
    cornerAreasOf(e, area, corner_areas[f]);
    for (int j = 0; j < 3; ++j) point_areas[t[j]] += corner_areas[f][j];
  }
}

// The vertices computeFeatureSize samples: `featureSampleCount` of them, evenly strided.
static size_t featureSampleCount(size_t nv, const FeatureSizeParams& params) {
  return std::min<size_t>(nv, std::max<uint32_t>(params.max_samples, 1));
}
static size_t featureSample(size_t i, size_t nv, size_t nsamp) { return i * nv / nsamp; }

float computeFeatureSize(std::span<const float> k1, std::span<const float> k2,
                         float bounding_radius, const FeatureSizeParams& params,
                         std::span<const uint32_t> stored_to_drawn) {
  const size_t nv = std::min(k1.size(), k2.size());
  const float cap = params.max_fraction_of_radius * bounding_radius;
  if (nv == 0 || !(cap > 0.0f)) return cap > 0.0f ? cap : 1.0f;
  const size_t nsamp = featureSampleCount(nv, params);
  std::vector<float> samples;
  samples.reserve(2 * nsamp);
  for (size_t i = 0; i < nsamp; ++i) {
    size_t v = featureSample(i, nv, nsamp);
    if (stored_to_drawn.size() == nv && stored_to_drawn[v] < nv) v = stored_to_drawn[v];
    if (std::isfinite(k1[v])) samples.push_back(std::abs(k1[v]));
    if (std::isfinite(k2[v])) samples.push_back(std::abs(k2[v]));
  }
  if (samples.empty()) return cap;
  const float pct = std::isfinite(params.percentile) ? std::clamp(params.percentile, 0.0f, 1.0f) : 0.1f;
  const size_t which =
      std::min(samples.size() - 1, static_cast<size_t>(pct * static_cast<float>(samples.size())));
  std::nth_element(samples.begin(), samples.begin() + which, samples.end());
  const float k = samples[which];
  if (!(k > 0.0f)) return cap;
  return std::min(params.multiplier / k, cap);
}

// ---------------------------------------------------------------------------------------
// Per-face and per-vertex kernels. Each writes only its own slot and reads inputs that the
// previous phase finished, in adjacency order, so any subset recomputes bit-identically.

FaceNormal faceNormalOf(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
  const glm::vec3 cr = glm::cross(p2 - p1, p0 - p2);
  const float len = glm::length(cr);
  if (!(len > 0.0f) || !std::isfinite(len)) return {};
  const glm::vec3 n = cr / len;
  if (!finite3(n)) return {};
  return {n, len};
}

float sampledFeatureSize(const TriMesh& mesh, const MeshAdjacency& adj, float bounding_radius,
                         const ShapeParams& shape_params, const FeatureSizeParams& params) {
  const size_t nv = mesh.positions.size();
  if (nv == 0 || adj.vertex_count != nv) return computeFeatureSize({}, {}, bounding_radius, params);
  // computeFeatureSize's samples, and the faces within two rings of them.
  const size_t nsamp = featureSampleCount(nv, params);
  std::vector<uint32_t> samples(nsamp);
  for (size_t i = 0; i < nsamp; ++i) samples[i] = static_cast<uint32_t>(featureSample(i, nv, nsamp));
  std::vector<uint32_t> faces;
  for (uint32_t s : samples)
    for (uint32_t f : adj.facesOf(s))
      for (uint32_t u : mesh.faces[f])
        for (uint32_t g : adj.facesOf(u)) faces.push_back(g);
  std::sort(faces.begin(), faces.end());  // increasing order keeps every ring's order
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  TriMesh sub;
  std::unordered_map<uint32_t, uint32_t> index;
  auto local = [&](uint32_t v) {
    auto [it, added] = index.try_emplace(v, static_cast<uint32_t>(sub.positions.size()));
    if (added) sub.positions.push_back(mesh.positions[v]);
    return it->second;
  };
  for (uint32_t s : samples) local(s);  // samples first: sub-vertex i is sample i
  sub.faces.reserve(faces.size());
  for (uint32_t f : faces) sub.faces.push_back({local(mesh.faces[f][0]), local(mesh.faces[f][1]), local(mesh.faces[f][2])});
  ShapeParams p = shape_params;
  p.derivatives = false;
  p.threads = 1;
  ShapeCache cache(p);
  cache.compute(sub);
  // The samples are distinct (i·nv/nsamp grows by at least 1 for nsamp ≤ nv): sub-vertices
  // 0 .. nsamp − 1, in computeFeatureSize's order.
  return computeFeatureSize(cache.k1().subspan(0, nsamp), cache.k2().subspan(0, nsamp), bounding_radius, params);
}

template <int W>
void ShapeCache::storeFaceGeometry(uint32_t f, const float* out, int lane, bool ok) {
  FaceRecord& rec = faces_[f];
  rec.ok = 0;
  rec.corner = {0.0f, 0.0f, 0.0f};
  rec.normal_weight = {0.0f, 0.0f, 0.0f};
  rec.n = glm::vec3(0.0f);
  face_normals_[f] = glm::vec3(0.0f);
  if (!ok) return;
  auto get = [&](int k) { return out[k * W + lane]; };
  auto get3 = [&](int k) { return glm::vec3(get(k), get(k + 1), get(k + 2)); };
  const glm::vec3 n = get3(fit::kGN);
  face_normals_[f] = n;
  rec.corner = {get(fit::kGCorner), get(fit::kGCorner + 1), get(fit::kGCorner + 2)};
  rec.n = n;
  // Weight of this face's unit normal in each corner's vertex normal. Corner j sits between
  // the edges a = e[j-1] and b = −e[j+1], with |a × b| = len.
  const float len = get(fit::kGLen);
  for (int j = 0; j < 3; ++j) {
    const int jp = prevCorner(j), jn = nextCorner(j);
    switch (params_.normal_weighting) {
      case NormalWeighting::kArea:
        rec.normal_weight[j] = len;
        break;
      case NormalWeighting::kAngle:
        rec.normal_weight[j] = std::atan2(len, -get(fit::kGDot + j));
        break;
      case NormalWeighting::kMax:
        rec.normal_weight[j] = len / (get(fit::kGL2 + jp) * get(fit::kGL2 + jn));
        break;
    }
    if (!std::isfinite(rec.normal_weight[j])) rec.normal_weight[j] = 0.0f;
  }
  rec.ok = kGeomOk;
}

void ShapeCache::faceGeometryBlock(const TriMesh& mesh, const uint32_t* faces, uint32_t count) {
  constexpr int W = lanes::kWidth;
  alignas(32) float out[fit::kGeomOut * W];
  const uint8_t* const valid_faces = validFaces();
  const auto valid = [&](uint32_t f) { return valid_faces[f] != 0; };
  runFaceKernel<fit::kGeomIn>(
      faces, count, out, valid,
      [&](uint32_t f, const float** in, int lane) {
        for (int j = 0; j < 3; ++j) in[(fit::kGP + j) * W + lane] = &mesh.positions[mesh.faces[f][j]].x;
      },
      fit::faceGeometryLanes,
      [&](uint32_t f, const float* o, int lane, bool ok) { storeFaceGeometry<W>(f, o, lane, ok && valid(f)); });
}

void ShapeCache::vertexNormal(uint32_t v) {
  const MeshAdjacency& adj = adjacency_;
  glm::vec3 n(0.0f);
  float area = 0.0f;
  for (uint32_t i = adj.vertex_face_begin[v]; i < adj.vertex_face_end[v]; ++i) {
    const FaceRecord& rec = faces_[adj.vertex_faces[i]];
    const int c = adj.vertex_face_corners[i];
    area += rec.corner[c];
    n += rec.normal_weight[c] * rec.n;
  }
  finishNormal(v, n, area);
}

void ShapeCache::finishNormal(uint32_t v, glm::vec3 n, float area) {
  const float len = glm::length(n);
  n = (len > 0.0f && std::isfinite(len)) ? n / len : kFallbackNormal;
  if (!finite3(n)) n = kFallbackNormal;
  normals_[v] = n;
  point_areas_[v] = area;
  VertexFrame& fr = frames_[v];
  fr.n = n;
  frameFromNormal(n, fr.u, fr.w);
}

template <int W>
void ShapeCache::gatherCurvatureFit(const TriMesh& mesh, uint32_t f, const float** src, int lane) const {
  static_assert(sizeof(VertexFrame) == 9 * sizeof(float));
  const auto& t = mesh.faces[f];
  for (int j = 0; j < 3; ++j) {
    src[(fit::kP + j) * W + lane] = &mesh.positions[t[j]].x;
    src[(fit::kFrame + j) * W + lane] = reinterpret_cast<const float*>(&frames_[t[j]]);
  }
  src[fit::kFn * W + lane] = &face_normals_[f].x;
}

template <int W>
void ShapeCache::storeCurvatureFit(uint32_t f, const float* out, int lane, bool ok) {
  FaceRecord& rec = faces_[f];
  rec.ok &= static_cast<uint8_t>(~kCurvOk);
  rec.curv = glm::vec3(0.0f);
  if (!(rec.ok & kGeomOk)) return;
  // Corner relations (vertex frame axes in face coordinates), reused by every later gather.
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) rec.rel[j][i] = out[(fit::kRel + 4 * j + i) * W + lane];
  if (!ok) return;
  for (int i = 0; i < 3; ++i) rec.curv[i] = out[(fit::kCurv + i) * W + lane];
  rec.ok |= kCurvOk;
}

void ShapeCache::curvatureFitBlock(const TriMesh& mesh, const uint32_t* faces, uint32_t count,
                                   float* out) {
  runFaceKernel<fit::kCurvIn>(
      faces, count, out, [&](uint32_t f) { return (faces_[f].ok & kGeomOk) != 0; },
      [&](uint32_t f, const float** in, int lane) { gatherCurvatureFit<lanes::kWidth>(mesh, f, in, lane); },
      fit::curvatureFitLanes,
      [&](uint32_t f, const float* o, int lane, bool ok) { storeCurvatureFit<lanes::kWidth>(f, o, lane, ok); });
}

void ShapeCache::vertexCurvature(uint32_t v) {
  const MeshAdjacency& adj = adjacency_;
  glm::vec3 k(0.0f);
  float wsum = 0.0f;
  for (uint32_t i = adj.vertex_face_begin[v]; i < adj.vertex_face_end[v]; ++i) {
    const uint32_t f = adj.vertex_faces[i];
    const FaceRecord& rec = faces_[f];
    if (!(rec.ok & kCurvOk)) continue;
    const int c = adj.vertex_face_corners[i];
    const float wt = rec.corner[c];
    if (!(wt > 0.0f)) continue;
    const float kf[3] = {rec.curv[0], rec.curv[1], rec.curv[2]};
    float t[3];
    projectCurvature(kf, rec.rel[c][0], rec.rel[c][1], rec.rel[c][2], rec.rel[c][3], t);
    k += wt * glm::vec3(t[0], t[1], t[2]);
    wsum += wt;
  }
  finishCurvature(v, k, wsum);
}

void ShapeCache::finishCurvature(uint32_t v, glm::vec3 k, float wsum) {
  const glm::vec3& u = frames_[v].u;
  const glm::vec3& w = frames_[v].w;
  float k1 = 0.0f, k2 = 0.0f;
  glm::vec2 ab(1.0f, 0.0f);  // pdir1 = a·u + b·w
  if (wsum > 0.0f) {
    k /= wsum;  // weights corner/point area, normalised over the faces that had a fit
    const float ku = k[0], kuv = k[1], kv = k[2];
    // Jacobi rotation diagonalising [[ku, kuv], [kuv, kv]].
    float cs = 1.0f, sn = 0.0f, tt = 0.0f;
    if (kuv != 0.0f) {
      const float h = 0.5f * (kv - ku) / kuv;
      tt = (h < 0.0f) ? 1.0f / (h - std::sqrt(1.0f + h * h)) : 1.0f / (h + std::sqrt(1.0f + h * h));
      cs = 1.0f / std::sqrt(1.0f + tt * tt);
      sn = tt * cs;
    }
    k1 = ku - tt * kuv;
    k2 = kv + tt * kuv;
    if (k1 >= k2) {
      ab = glm::vec2(cs, -sn);
    } else {
      std::swap(k1, k2);
      ab = glm::vec2(sn, cs);
    }
    ab /= std::sqrt(ab.x * ab.x + ab.y * ab.y);
    if (!std::isfinite(k1) || !std::isfinite(k2) || !std::isfinite(ab.x) ||
        !std::isfinite(ab.y)) {
      k1 = k2 = 0.0f;
      ab = glm::vec2(1.0f, 0.0f);
    }
  }
  k1_[v] = k1;
  k2_[v] = k2;
  vertex_kab_[v] = glm::vec4(k1, k2, ab.x, ab.y);
  pdir1_[v] = ab.x * u + ab.y * w;  // unit: (u, w) orthonormal
  pdir2_[v] = ab.x * w - ab.y * u;  // = n × pdir1
}

template <int W>
void ShapeCache::gatherDerivativeFit(const TriMesh& mesh, uint32_t f, const float** src, int lane) const {
  const auto& t = mesh.faces[f];
  for (int j = 0; j < 3; ++j) {
    src[(fit::kDP + j) * W + lane] = &mesh.positions[t[j]].x;
    src[(fit::kDKab + j) * W + lane] = &vertex_kab_[t[j]].x;
  }
  src[fit::kDRel * W + lane] = &faces_[f].rel[0].x;  // the three corners' relations, 12 floats
  src[fit::kDFn * W + lane] = &face_normals_[f].x;
}

template <int W>
void ShapeCache::storeDerivativeFit(uint32_t f, const float* out, int lane, bool ok) {
  FaceRecord& rec = faces_[f];
  rec.ok &= static_cast<uint8_t>(~kDcurvOk);
  rec.dcurv = glm::vec4(0.0f);
  if (!(rec.ok & kGeomOk) || !ok) return;
  for (int i = 0; i < 4; ++i) rec.dcurv[i] = out[(fit::kDcurv + i) * W + lane];
  rec.ok |= kDcurvOk;
}

void ShapeCache::derivativeFitBlock(const TriMesh& mesh, const uint32_t* faces, uint32_t count,
                                    float* out) {
  runFaceKernel<fit::kDerivIn>(
      faces, count, out, [&](uint32_t f) { return (faces_[f].ok & kGeomOk) != 0; },
      [&](uint32_t f, const float** in, int lane) { gatherDerivativeFit<lanes::kWidth>(mesh, f, in, lane); },
      fit::derivativeFitLanes,
      [&](uint32_t f, const float* o, int lane, bool ok) { storeDerivativeFit<lanes::kWidth>(f, o, lane, ok); });
}

void ShapeCache::vertexDerivative(uint32_t v) {
  const MeshAdjacency& adj = adjacency_;
  glm::vec4 c(0.0f);
  float wsum = 0.0f;
  const glm::vec2 ab(vertex_kab_[v][2], vertex_kab_[v][3]);
  for (uint32_t i = adj.vertex_face_begin[v]; i < adj.vertex_face_end[v]; ++i) {
    const uint32_t f = adj.vertex_faces[i];
    const FaceRecord& rec = faces_[f];
    if (!(rec.ok & kDcurvOk)) continue;
    const int corner = adj.vertex_face_corners[i];
    const float wt = rec.corner[corner];
    if (!(wt > 0.0f)) continue;
    const float m[4] = {rec.rel[corner][0], rec.rel[corner][1], rec.rel[corner][2], rec.rel[corner][3]};
    const float cd[4] = {rec.dcurv[0], rec.dcurv[1], rec.dcurv[2], rec.dcurv[3]};
    float q[4], t[4];
    principalInFace(m, ab.x, ab.y, q);
    projectDerivative(cd, q[0], q[1], q[2], q[3], t);
    c += wt * glm::vec4(t[0], t[1], t[2], t[3]);
    wsum += wt;
  }
  finishDerivative(v, c, wsum);
}

void ShapeCache::finishDerivative(uint32_t v, glm::vec4 c, float wsum) {
  if (wsum > 0.0f) c /= wsum;
  if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]) ||
      !std::isfinite(c[3]))
    c = glm::vec4(0.0f);
  dcurv_[v] = c;
}

// The full compute on one thread, by scattering each face's share to its three vertices in
// face order (Rusinkiewicz 2004's own loop order) instead of gathering each vertex's ring.
// A vertex's ring lists its faces in increasing order, so every vertex receives the same
// terms in the same order as its gather adds them, and the results are bit-identical; but
// the face records stream through once per phase and only the small per-vertex sums are
// touched at random — the gathers' random reads of whole face records were most of the time.
void ShapeCache::computeScattered(const TriMesh& mesh, bool eager_derivatives) {
  const uint32_t nv = static_cast<uint32_t>(mesh.positions.size());
  const uint32_t nf = static_cast<uint32_t>(mesh.faces.size());
  const uint8_t* valid = validFaces();
  sum_.assign(nv, glm::vec4(0.0f));
  sum_w_.assign(nv, 0.0f);
  constexpr uint32_t W = lanes::kWidth;
  // The blocks run in face order, so each vertex receives its terms in increasing face order,
  // as a gather over its ring adds them. (Written out rather than through forEachFaceBlock():
  // behind its lambda the scatter loops ran a third slower.)
  uint32_t block[W];
  auto next_block = [&](uint32_t f0) {
    const uint32_t count = std::min<uint32_t>(W, nf - f0);
    for (uint32_t l = 0; l < count; ++l) block[l] = f0 + l;
    return count;
  };
  // Normals and point areas: every face of a ring (a valid face) adds to its corners.
  for (uint32_t f0 = 0; f0 < nf; f0 += W) {
    const uint32_t count = next_block(f0);
    faceGeometryBlock(mesh, block, count);
    for (uint32_t f = f0; f < f0 + count; ++f) {
      if (!valid[f]) continue;
      const FaceRecord& rec = faces_[f];
      for (int j = 0; j < 3; ++j) {
        const uint32_t v = mesh.faces[f][j];
        sum_w_[v] += rec.corner[j];
        sum_[v] += glm::vec4(rec.normal_weight[j] * rec.n, 0.0f);
      }
    }
  }
  for (uint32_t v = 0; v < nv; ++v) finishNormal(v, glm::vec3(sum_[v]), sum_w_[v]);
  // Curvature, then derivatives. The fits run lanes::kWidth faces at a time (fit_lanes.h); then each
  // of those faces with a fit (`ok_bit`) adds its corners' terms, computed with the fit as
  // vertexCurvature() and vertexDerivative() compute them, where the corner weight is positive.
  alignas(32) float out[std::max(fit::kCurvOut, fit::kDerivOut) * W];
  auto scatter = [&](auto fit_block, uint8_t ok_bit, int term_row, int term_size) {
    std::fill(sum_.begin(), sum_.end(), glm::vec4(0.0f));
    std::fill(sum_w_.begin(), sum_w_.end(), 0.0f);
    for (uint32_t f0 = 0; f0 < nf; f0 += W) {
      const uint32_t count = next_block(f0);
      fit_block(block, count, out);
      for (uint32_t l = 0; l < count; ++l) {
        const uint32_t f = f0 + l;
        const FaceRecord& rec = faces_[f];
        if (!valid[f] || !(rec.ok & ok_bit)) continue;
        for (int j = 0; j < 3; ++j) {
          const float wt = rec.corner[j];
          if (!(wt > 0.0f)) continue;
          const uint32_t v = mesh.faces[f][j];
          glm::vec4 term(0.0f);
          for (int i = 0; i < term_size; ++i) term[i] = out[(term_row + term_size * j + i) * W + l];
          sum_[v] += wt * term;
          sum_w_[v] += wt;
        }
      }
    }
  };
  scatter([&](const uint32_t* faces, uint32_t count, float* o) { curvatureFitBlock(mesh, faces, count, o); },
          kCurvOk, fit::kCurvTerm, 3);
  for (uint32_t v = 0; v < nv; ++v) finishCurvature(v, glm::vec3(sum_[v]), sum_w_[v]);
  if (!eager_derivatives) return;
  scatter([&](const uint32_t* faces, uint32_t count, float* o) { derivativeFitBlock(mesh, faces, count, o); },
          kDcurvOk, fit::kDcurvTerm, 4);
  for (uint32_t v = 0; v < nv; ++v) finishDerivative(v, sum_[v], sum_w_[v]);
}

// ---------------------------------------------------------------------------------------

void ShapeCache::resize(uint32_t nv, uint32_t nf) {
  face_normals_.resize(nf);
  faces_.resize(nf);
  normals_.resize(nv);
  frames_.resize(nv);
  point_areas_.resize(nv);
  k1_.resize(nv);
  k2_.resize(nv);
  pdir1_.resize(nv);
  vertex_kab_.resize(nv);
  pdir2_.resize(nv);
  dcurv_.resize(params_.derivatives ? nv : 0);
  vertex_dgen_.resize(params_.lazy_derivatives ? nv : 0, 0);
  face_dgen_.resize(params_.lazy_derivatives ? nf : 0, 0);
  curv_gen_.resize(params_.lazy_derivatives ? nv : 0, 0);
  vertex_stamp_.assign(nv, 0);
  face_stamp_.assign(nf, 0);
  vertex_level_.assign(nv, 0);
  face_level_.assign(nf, 0);
  stamp_ = 0;
}

void ShapeCache::compute(const TriMesh& mesh) {
  const uint32_t nv = static_cast<uint32_t>(mesh.positions.size());
  const uint32_t nf = static_cast<uint32_t>(mesh.faces.size());
  const bool same_faces =
      computed_ && vertex_count_ == nv && faces_copy_.size() == mesh.faces.size() &&
      (nf == 0 || std::memcmp(faces_copy_.data(), mesh.faces.data(),
                              nf * sizeof(mesh.faces[0])) == 0);
  stats_ = ShapeUpdateStats{};
  if (!same_faces) {
    faces_copy_ = mesh.faces;
    vertex_count_ = nv;
    adjacency_current_ = false;
    resize(nv, nf);
    stats_.connectivity_rebuilt = true;
  }
  const bool eager = params_.derivatives && !params_.lazy_derivatives;
  if (params_.threads == 1 && !external_pool_) {
    // Face loops only: the adjacency waits for whoever needs it; until then, which faces
    // are valid is kept on its own.
    if (!adjacency_current_) {
      face_valid_.resize(nf);
      for (uint32_t f = 0; f < nf; ++f) face_valid_[f] = faceIsValid(mesh.faces[f], nv);
    }
    computeScattered(mesh, eager);
  } else {
    ensureAdjacency();  // the threads gather over the vertices' rings
    // Each phase reads only what the previous phases finished and writes only its own face
    // or vertex, so the loops split over threads without changing a bit of the result.
    // The face kernels run lanes::kWidth faces at a time, as on one thread.
    constexpr uint32_t W = lanes::kWidth;
    forEachFaceBlock(nf, [&](const uint32_t* faces, uint32_t count) { faceGeometryBlock(mesh, faces, count); });
    parallelFor(nv, [&](uint32_t v) { vertexNormal(v); });
    forEachFaceBlock(nf, [&](const uint32_t* faces, uint32_t count) {
      alignas(32) float out[fit::kCurvOut * W];
      curvatureFitBlock(mesh, faces, count, out);
    });
    parallelFor(nv, [&](uint32_t v) { vertexCurvature(v); });
    if (eager) {
      forEachFaceBlock(nf, [&](const uint32_t* faces, uint32_t count) {
        alignas(32) float out[fit::kDerivOut * W];
        derivativeFitBlock(mesh, faces, count, out);
      });
      parallelFor(nv, [&](uint32_t v) { vertexDerivative(v); });
    }
  }
  if (!eager && params_.lazy_derivatives) {  // every tensor is stale now
    nextGeneration();
    dfloor_ = dgen_;
  }
  computed_ = true;
  ++version_;
  resetWaiting(mesh);
  stats_.full = true;
  stats_.normal_vertices = stats_.curvature_vertices = nv;
  stats_.derivative_vertices = eager ? nv : 0;
}

void ShapeCache::resetWaiting(const TriMesh& mesh) {
  waiting_.clear();
  if (!(params_.move_tolerance > 0.0f)) return;
  computed_pos_.assign(mesh.positions.begin(), mesh.positions.end());
  seen_pos_.resize(mesh.positions.size());
  waiting_flag_.assign(mesh.positions.size(), 0);
}

const MeshAdjacency& ShapeCache::adjacency() const {
  ensureAdjacency();
  return adjacency_;
}

void ShapeCache::ensureAdjacency() const {
  if (adjacency_current_) return;
  buildAdjacency(faces_copy_, vertex_count_, adjacency_);
  adjacency_current_ = true;
}

void ShapeCache::growFaces(size_t begin, size_t end, uint8_t level) {
  const MeshAdjacency& adj = adjacency_;
  for (size_t k = begin; k < end; ++k) {
    const uint32_t v = inc_verts_[k];
    for (uint32_t i = adj.vertex_face_begin[v]; i < adj.vertex_face_end[v]; ++i) {
      const uint32_t f = adj.vertex_faces[i];
      if (face_stamp_[f] != stamp_) {
        face_stamp_[f] = stamp_;
        face_level_[f] = level;
        inc_faces_.push_back(f);
      }
    }
  }
}

void ShapeCache::growVertices(const TriMesh& mesh, size_t begin, size_t end, uint8_t level) {
  for (size_t k = begin; k < end; ++k) {
    for (uint32_t v : mesh.faces[inc_faces_[k]]) {
      if (vertex_stamp_[v] != stamp_) {
        vertex_stamp_[v] = stamp_;
        vertex_level_[v] = level;
        inc_verts_.push_back(v);
      }
    }
  }
}

template <class Fn>
void ShapeCache::parallelFor(size_t n, Fn&& fn) {
  // Below a few thousand items waking the workers costs more than it saves.
  constexpr size_t kMinChunk = 1024;
  if ((params_.threads == 1 && !external_pool_) || n < 2 * kMinChunk) {
    for (size_t i = 0; i < n; ++i) fn(static_cast<uint32_t>(i));
    return;
  }
  if (!external_pool_ && !pool_) pool_ = std::make_unique<WorkerPool>(params_.threads);
  WorkerPool& pool = external_pool_ ? *external_pool_ : *pool_;
  pool.forRange(n, kMinChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) fn(static_cast<uint32_t>(i));
  });
}

template <class Fn>
void ShapeCache::forEachMarked(bool faces, size_t count, uint8_t max_level, Fn&& fn) {
  const std::vector<uint32_t>& list = faces ? inc_faces_ : inc_verts_;
  const std::vector<uint32_t>& stamps = faces ? face_stamp_ : vertex_stamp_;
  const std::vector<uint8_t>& levels = faces ? face_level_ : vertex_level_;
  if (count * 16 < stamps.size()) {
    parallelFor(count, [&](uint32_t k) { fn(list[k]); });  // few: list order
  } else {
    // Many: memory order, much kinder to the caches than the list's random order. Changes
    // cluster (a view-dependent mesh appends the faces of recent splits, which are also the
    // ones morphing); the pool's chunks are handed out as threads free up, which evens that out.
    parallelFor(stamps.size(), [&](uint32_t i) {
      if (stamps[i] == stamp_ && levels[i] <= max_level) fn(i);
    });
  }
}

template <class Fn>
void ShapeCache::forEachFaceBlock(uint32_t nf, Fn&& block_fn) {
  constexpr uint32_t W = lanes::kWidth;
  parallelFor((nf + W - 1) / W, [&](uint32_t b) {
    uint32_t faces[W];
    const uint32_t count = std::min<uint32_t>(W, nf - b * W);
    for (uint32_t l = 0; l < count; ++l) faces[l] = b * W + l;
    block_fn(faces, count);
  });
}

template <class Fn>
void ShapeCache::forEachBlock(const uint32_t* list, size_t n, Fn&& block_fn) {
  constexpr size_t W = lanes::kWidth;
  parallelFor((n + W - 1) / W, [&](uint32_t b) {
    const size_t first = static_cast<size_t>(b) * W;
    block_fn(list + first, static_cast<uint32_t>(std::min(W, n - first)));
  });
}

template <class Fn>
void ShapeCache::forEachMarkedFaceBlock(size_t count, uint8_t max_level, Fn&& block_fn) {
  if (count * 16 < face_stamp_.size()) return forEachBlock(inc_faces_.data(), count, block_fn);
  // Many: in memory order, as forEachMarked.
  marked_faces_.clear();
  for (uint32_t f = 0; f < face_stamp_.size(); ++f)
    if (face_stamp_[f] == stamp_ && face_level_[f] <= max_level) marked_faces_.push_back(f);
  forEachBlock(marked_faces_.data(), marked_faces_.size(), block_fn);
}

void ShapeCache::update(const TriMesh& mesh, std::span<const uint32_t> changed_vertices) {
  const uint32_t nv = static_cast<uint32_t>(mesh.positions.size());
  const uint32_t nf = static_cast<uint32_t>(mesh.faces.size());
  const uint32_t old_nv = vertex_count_;
  if (!computed_ || nv < old_nv) {  // vertices removed: indices may have moved, start over
    compute(mesh);
    return;
  }
  ensureAdjacency();  // the rings say what depends on what
  const uint32_t old_nf = static_cast<uint32_t>(faces_copy_.size());
  const bool same_faces =
      old_nv == nv && old_nf == nf &&
      (nf == 0 ||
       std::memcmp(faces_copy_.data(), mesh.faces.data(), nf * sizeof(mesh.faces[0])) == 0);
  bool in_place = false;
  if (!same_faces) {
    // Connectivity changed. The face slots whose triple changed, was added or was removed:
    // the adjacency is updated in place around them when they are few (rebuilt otherwise);
    // per-face/per-vertex slots keep their values (a face slot whose triple is unchanged stays
    // valid), new slots start empty.
    const uint32_t common = std::min(old_nf, nf);
    changed_faces_.clear();
    // Sixteen faces (192 bytes) at a time with memcmp, face by face only where they differ:
    // a few percent of the slots change a frame, and the face-by-face loop alone took 0.3 ms
    // on an 81k-face adapted mesh.
    constexpr uint32_t kChunk = 16;
    uint32_t f = 0;
    for (; f + kChunk <= common; f += kChunk) {
      if (std::memcmp(&faces_copy_[f], &mesh.faces[f], kChunk * sizeof(mesh.faces[0])) == 0) continue;
      for (uint32_t g = f; g < f + kChunk; ++g)
        if (faces_copy_[g] != mesh.faces[g]) changed_faces_.push_back(g);
    }
    for (; f < common; ++f)
      if (faces_copy_[f] != mesh.faces[f]) changed_faces_.push_back(f);
    for (uint32_t f = common; f < std::max(old_nf, nf); ++f) changed_faces_.push_back(f);
    in_place = updateAdjacency(mesh, faces_copy_, changed_faces_, adjacency_);
    if (!in_place) buildAdjacency(mesh, adjacency_);
    resize(nv, nf);
  }
  if (++stamp_ == 0) {  // wrapped: clear the marks once every 2³² updates
    std::fill(vertex_stamp_.begin(), vertex_stamp_.end(), 0);
    std::fill(face_stamp_.begin(), face_stamp_.end(), 0);
    stamp_ = 1;
  }
  inc_verts_.clear();
  inc_faces_.clear();
  auto seed = [&](uint32_t v) {
    if (v < nv && vertex_stamp_[v] != stamp_) {
      vertex_stamp_[v] = stamp_;
      vertex_level_[v] = 0;
      inc_verts_.push_back(v);
    }
  };
  const float tol = params_.move_tolerance;
  if (tol > 0.0f) {
    // Small moves wait (ShapeParams::move_tolerance): a vertex is seeded once it is more than
    // tol·√(point area) from where it was last computed, or once it stopped moving.
    computed_pos_.resize(nv);
    seen_pos_.resize(nv);
    waiting_flag_.resize(nv, 0);
    const float tol2 = tol * tol;
    const uint32_t waited = static_cast<uint32_t>(waiting_.size());
    for (uint32_t v : changed_vertices) {
      if (v >= nv) continue;
      if (v >= old_nv) {
        seed(v);
        continue;
      }
      const glm::vec3 d = mesh.positions[v] - computed_pos_[v];
      if (!(glm::dot(d, d) <= tol2 * point_areas_[v])) {  // (a non-finite move is seeded)
        seed(v);
      } else if (!waiting_flag_[v]) {
        waiting_flag_[v] = 1;
        waiting_.push_back(v);
        seen_pos_[v] = mesh.positions[v];
      }
    }
    for (uint32_t k = 0; k < waited; ++k) {  // those that waited before this update
      const uint32_t v = waiting_[k];
      if (v >= nv || !waiting_flag_[v] || vertex_stamp_[v] == stamp_) continue;
      if (std::memcmp(&mesh.positions[v], &seen_pos_[v], sizeof(glm::vec3)) == 0) {
        seed(v);  // stopped
      } else {
        seen_pos_[v] = mesh.positions[v];
      }
    }
  } else {
    for (uint32_t v : changed_vertices) seed(v);
  }
  if (!same_faces) {
    // Every vertex whose ring may have changed: those of changed, added and removed face
    // slots (old and new triples), and new vertices. A slot that became invalid is in no
    // ring, so reset it here (valid ones are redone with F1 below).
    for (uint32_t f : changed_faces_) {
      if (f < old_nf)
        for (uint32_t v : faces_copy_[f]) seed(v);
      if (f < nf) {
        for (uint32_t v : mesh.faces[f]) seed(v);
        if (!adjacency_.face_valid[f]) storeFaceGeometry<1>(f, nullptr, 0, false);
      }
    }
    for (uint32_t v = old_nv; v < nv; ++v) seed(v);
    faces_copy_.resize(nf);  // only the changed slots differ
    for (uint32_t f : changed_faces_)
      if (f < nf) faces_copy_[f] = mesh.faces[f];
    vertex_count_ = nv;
  }
  if (tol > 0.0f) {  // every seed is computed at its current position now
    for (uint32_t v : inc_verts_) {
      computed_pos_[v] = mesh.positions[v];
      waiting_flag_[v] = 0;
    }
    size_t kept = 0;
    for (uint32_t v : waiting_)
      if (v < nv && waiting_flag_[v]) waiting_[kept++] = v;
    waiting_.resize(kept);
  }
  // The nested support sets, as prefixes of inc_faces_ / inc_verts_ (level = ring):
  //   C = changed; F1 = faces of C (geometry, corner areas); V1 = their vertices (normals,
  //   areas, frames); F2 = faces of V1 (curvature fits, corner relations); V2 (curvature);
  //   F3 = faces of V2 (derivative fits); V3 (derivative tensors).
  const size_t m0 = inc_verts_.size();
  const double limit = params_.full_recompute_fraction * nv;
  if (static_cast<double>(m0) > limit) {
    compute(mesh);  // the adjacency is already current: compute() keeps it
    stats_.changed_vertices = static_cast<uint32_t>(m0);
    stats_.connectivity_rebuilt = !same_faces;
    stats_.adjacency_in_place = in_place;
    return;
  }
  growFaces(0, m0, 1);
  const size_t n1 = inc_faces_.size();
  growVertices(mesh, 0, n1, 1);
  const size_t m1 = inc_verts_.size();
  growFaces(m0, m1, 2);
  const size_t n2 = inc_faces_.size();
  growVertices(mesh, n1, n2, 2);
  const size_t m2 = inc_verts_.size();
  size_t n3 = n2, m3 = m2;
  const bool eager = params_.derivatives && !params_.lazy_derivatives;
  if (eager) {
    growFaces(m1, m2, 3);
    n3 = inc_faces_.size();
    growVertices(mesh, n2, n3, 3);
    m3 = inc_verts_.size();
  }
  if (static_cast<double>(m3) > limit) {  // touches most of the mesh: do it all in order
    compute(mesh);
    stats_.changed_vertices = static_cast<uint32_t>(m0);
    stats_.connectivity_rebuilt = !same_faces;
    stats_.adjacency_in_place = in_place;
    return;
  }
  // The face kernels run lanes::kWidth faces at a time (fit_lanes.h), as in compute().
  constexpr int W = lanes::kWidth;
  forEachMarkedFaceBlock(n1, 1, [&](const uint32_t* faces, uint32_t count) { faceGeometryBlock(mesh, faces, count); });
  forEachMarked(false, m1, 1, [&](uint32_t v) { vertexNormal(v); });
  forEachMarkedFaceBlock(n2, 2, [&](const uint32_t* faces, uint32_t count) {
    alignas(32) float out[fit::kCurvOut * W];
    curvatureFitBlock(mesh, faces, count, out);
  });
  forEachMarked(false, m2, 2, [&](uint32_t v) { vertexCurvature(v); });
  if (eager) {
    forEachMarkedFaceBlock(n3, 3, [&](const uint32_t* faces, uint32_t count) {
      alignas(32) float out[fit::kDerivOut * W];
      derivativeFitBlock(mesh, faces, count, out);
    });
    forEachMarked(false, m3, 3, [&](uint32_t v) { vertexDerivative(v); });
  } else if (params_.lazy_derivatives) {  // V2's curvatures are new: what reads them is stale
    nextGeneration();
    for (size_t k = 0; k < m2; ++k) curv_gen_[inc_verts_[k]] = dgen_;
  }
  ++version_;
  stats_ = ShapeUpdateStats{};
  stats_.full = false;
  stats_.connectivity_rebuilt = !same_faces;
  stats_.adjacency_in_place = in_place;
  stats_.changed_vertices = static_cast<uint32_t>(m0);
  stats_.normal_vertices = static_cast<uint32_t>(m1);
  stats_.curvature_vertices = static_cast<uint32_t>(m2);
  stats_.derivative_vertices = static_cast<uint32_t>(eager ? m3 : 0);
  stats_.waiting_vertices = static_cast<uint32_t>(waiting_.size());
}

void ShapeCache::nextGeneration() {
  if (++dgen_ != 0) return;
  // Wrapped (once every 2³² updates): every fit and tensor stale, every curvature older.
  std::fill(vertex_dgen_.begin(), vertex_dgen_.end(), 0);
  std::fill(face_dgen_.begin(), face_dgen_.end(), 0);
  std::fill(curv_gen_.begin(), curv_gen_.end(), 0);
  dgen_ = dfloor_ = 1;
}

bool ShapeCache::fitCurrent(uint32_t f) const {
  const uint32_t g = face_dgen_[f];
  if (g < dfloor_) return false;
  for (uint32_t u : faces_copy_[f])
    if (curv_gen_[u] > g) return false;
  return true;
}

// A tensor reads v's curvature and the fits of the faces around v, and each fit the
// curvatures of its corners (and their positions, normals and rings, which change only with
// those curvatures). So it is current iff computed since the last compute() and neither v's
// curvature nor that of a corner around v has been recomputed since.
bool ShapeCache::tensorCurrent(uint32_t v) const {
  const uint32_t g = vertex_dgen_[v];
  if (g < dfloor_) return false;
  if (!adjacency_current_) return true;  // no update() since compute(): the floor decides
  if (curv_gen_[v] > g) return false;    // (v itself: a vertex left with no faces)
  for (uint32_t i = adjacency_.vertex_face_begin[v]; i < adjacency_.vertex_face_end[v]; ++i)
    for (uint32_t u : faces_copy_[adjacency_.vertex_faces[i]])
      if (curv_gen_[u] > g) return false;
  return true;
}

void ShapeCache::ensureDerivatives(const TriMesh& mesh, std::span<const uint32_t> vertices) {
  last_ensured_ = 0;
  if (!params_.derivatives || !params_.lazy_derivatives || !computed_) return;
  ensureAdjacency();
  const uint32_t nv = vertex_count_;
  ens_verts_.clear();
  ens_faces_.clear();
  // Marked current as they are scheduled (repeats drop out); all are computed below.
  for (uint32_t v : vertices) {
    if (v >= nv || tensorCurrent(v)) continue;
    vertex_dgen_[v] = dgen_;
    ens_verts_.push_back(v);
    for (uint32_t i = adjacency_.vertex_face_begin[v]; i < adjacency_.vertex_face_end[v]; ++i) {
      const uint32_t f = adjacency_.vertex_faces[i];
      if (fitCurrent(f)) continue;
      face_dgen_[f] = dgen_;
      ens_faces_.push_back(f);
    }
  }
  // In memory order: the requests come in edge order, scattered over the arrays. The faces
  // through a bitmap (a few thousand of ~100k: sorting them took 0.1 ms a frame at T = 7 on
  // the 1.1M knot); the vertices usually come sorted (LineDrawing asks in vertex order).
  const uint32_t nf = static_cast<uint32_t>(faces_copy_.size());
  ens_bits_.assign((nf + 63) / 64, 0);
  for (uint32_t f : ens_faces_) ens_bits_[f >> 6] |= uint64_t{1} << (f & 63);
  ens_faces_.clear();
  for (uint32_t w = 0; w < ens_bits_.size(); ++w)
    for (uint64_t bits = ens_bits_[w]; bits; bits &= bits - 1)
      ens_faces_.push_back(w * 64 + static_cast<uint32_t>(std::countr_zero(bits)));
  if (!std::is_sorted(ens_verts_.begin(), ens_verts_.end())) std::sort(ens_verts_.begin(), ens_verts_.end());
  forEachBlock(ens_faces_.data(), ens_faces_.size(), [&](const uint32_t* faces, uint32_t count) {
    alignas(32) float out[fit::kDerivOut * lanes::kWidth];
    derivativeFitBlock(mesh, faces, count, out);
  });
  parallelFor(ens_verts_.size(), [&](uint32_t k) { vertexDerivative(ens_verts_[k]); });
  last_ensured_ = static_cast<uint32_t>(ens_verts_.size());
}

SurfaceFields ShapeCache::fields(const TriMesh& mesh) const {
  SurfaceFields s;
  s.positions = mesh.positions;
  s.normals = normals_;
  s.k1 = k1_;
  s.k2 = k2_;
  s.pdir1 = pdir1_;
  s.pdir2 = pdir2_;
  s.dcurv = dcurv_;
  return s;
}

}  // namespace lodline
