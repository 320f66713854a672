// DeCarlo et al. 2003 §4 and 2004 §3–4 (zero sets of n·v and kr, num/den test, fading);
// see lines.h.
#include "lines/lines.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include <glm/geometric.hpp>

#include "core/simd_clones.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#define LODLINE_FACE_SCAN_AVX512 1
#endif

namespace lodline {

void LineSet::clear() {
  points.clear();
  alpha.clear();
  point_ids.clear();
  kinds.clear();
  sources.clear();
  counts.fill(0);
}

namespace {

inline float fadeAlpha(float num, float den, float fade) {
  if (!(fade > 0.0f)) return 1.0f;
  const float a = num / (num + fade * den);
  return std::isfinite(a) ? std::clamp(a, 0.0f, 1.0f) : 1.0f;
}

inline bool passes(float num, float den) { return (num > 0.0f && den > 0.0f) || (num < 0.0f && den < 0.0f); }

}  // namespace

namespace {

// What the face pass asks of a corner, per zero set: bit 0 the value is negative, bit 1 the
// test passes, bit 2 the corner is shut (ZeroSetInput::shut: no line in a face with such a
// corner), bit 3 the gate is below its minimum (no line where the gate, interpolated, is: a
// face with every corner below has none, one with some is cut where the gate crosses).
// Zero set k uses bits 4k..4k+3 of a vertex's code.
constexpr uint8_t kNegative = 1, kPasses = 2, kShut = 4, kLow = 8;
constexpr int kCodeBits = 4;

// Per vertex, the code bits of zero set `k`. Branch-free and specialised on what the input
// has, so the compiler vectorises it: the signs are as good as random from one vertex to the
// next, and a mispredicted branch per vertex would cost more than the whole test.
template <bool kTest, bool kDen, bool kGate, int kShift>
[[gnu::always_inline]] inline void vertexCodesOf(const ZeroSetInput& in, size_t begin, size_t end,
                                                 uint8_t* __restrict code) {
  const float* __restrict val = in.value.data();
  const float* __restrict num = in.test_num.data();
  const float* __restrict den = in.test_den.data();
  const float* __restrict gate = in.gate.data();
  const float gate_min = in.gate_min;
  for (size_t v = begin; v < end; ++v) {
    int c = val[v] < 0.0f ? kNegative : 0;
    if constexpr (kTest) {
      const float n = num[v], d = kDen ? den[v] : 1.0f;
      c |= (((n > 0.0f) & (d > 0.0f)) | ((n < 0.0f) & (d < 0.0f))) ? kPasses : 0;
    } else {
      c |= kPasses;
    }
    if constexpr (kGate) c |= gate[v] < gate_min ? kLow : 0;
    if constexpr (kShift == 0) {
      code[v] = static_cast<uint8_t>(c);
    } else {
      code[v] = static_cast<uint8_t>(code[v] | (c << kShift));
    }
  }
}

template <int kShift>
[[gnu::always_inline]] inline void vertexCodesShifted(const ZeroSetInput& in, size_t begin, size_t end,
                                                      uint8_t* code) {
  const size_t nv = in.value.size();
  const bool has_test = in.test_num.size() == nv;
  const bool has_den = has_test && in.test_den.size() == nv;
  const bool has_gate = in.gate.size() == nv;
  if (has_test && has_den && has_gate) return vertexCodesOf<true, true, true, kShift>(in, begin, end, code);
  if (has_test && has_den) return vertexCodesOf<true, true, false, kShift>(in, begin, end, code);
  if (has_test && has_gate) return vertexCodesOf<true, false, true, kShift>(in, begin, end, code);
  if (has_test) return vertexCodesOf<true, false, false, kShift>(in, begin, end, code);
  if (has_gate) return vertexCodesOf<false, false, true, kShift>(in, begin, end, code);
  vertexCodesOf<false, false, false, kShift>(in, begin, end, code);
}

// Compiled for AVX-512F and AVX2 (64 and 32 vertices a step) where the processor has them,
// and for plain x86-64; comparisons only, so all give the same codes.
LODLINE_AVX512_CLONES void vertexCodes(const ZeroSetInput& in, int k, size_t begin, size_t end, uint8_t* code) {
  if (k == 0) vertexCodesShifted<0>(in, begin, end, code);
  else vertexCodesShifted<kCodeBits>(in, begin, end, code);
  if (in.shut.size() == in.value.size()) {
    const uint8_t bit = static_cast<uint8_t>(kShut << (kCodeBits * k));
    for (size_t v = begin; v < end; ++v)
      if (in.shut[v]) code[v] |= bit;
  }
}

// The face pass's test (extractZeroSets, pass 2) on the corner codes c0..c2 of a face: per
// zero set k, bit 4k is set when the sign changes over the face, the test passes at a corner,
// no corner is shut and not every corner's gate is below its minimum.
constexpr int kSignBits = kNegative | (kNegative << kCodeBits), kPassBits = kPasses | (kPasses << kCodeBits),
              kShutBits = kShut | (kShut << kCodeBits), kLowBits = kLow | (kLow << kCodeBits);
inline int liveOf(int c0, int c1, int c2) {
  const int all = c0 & c1 & c2, any = c0 | c1 | c2;
  return (any & ~all & kSignBits) & ((any & kPassBits) >> 1) & (~(any & kShutBits) >> 2) & (~(all & kLowBits) >> 3);
}

// Appends to cand[k] the faces of [begin, end) with a line of zero set k (bit kCodeBits·k of
// liveOf; a face marked invalid has none and reads no code), in increasing order, and to
// codes[k] their corner codes (c0 | c1 << 8 | c2 << 16); n[k] counts them. One list per zero
// set, so the segment pass runs one zero set's faces in a row: whether a face has a contour, a
// suggestive contour or both is as good as random, and a branch on it per face mispredicts.
void liveFacesScalar(const std::array<uint32_t, 3>* tri, const uint8_t* valid, const uint8_t* code, size_t begin,
                     size_t end, uint32_t* const* cand, uint32_t* const* codes, size_t* n) {
  size_t n0 = n[0], n1 = n[1];
  for (size_t f = begin; f < end; ++f) {
    const auto& t = tri[f];
    const bool ok = valid[f];
    const int c0 = ok ? code[t[0]] : 0, c1 = ok ? code[t[1]] : 0, c2 = ok ? code[t[2]] : 0;
    const uint32_t packed = static_cast<uint32_t>(c0 | (c1 << 8) | (c2 << 16));
    const int live = liveOf(c0, c1, c2);
    cand[0][n0] = cand[1][n1] = static_cast<uint32_t>(f);
    codes[0][n0] = codes[1][n1] = packed;
    n0 += live & 1;
    n1 += (live >> kCodeBits) & 1;
  }
  n[0] = n0;
  n[1] = n1;
}

#ifdef LODLINE_FACE_SCAN_AVX512
// The same, sixteen faces a step where the processor has AVX-512: the triples are loaded as
// three vectors and split into corners by permutes, the codes gathered (only for valid faces,
// whose indices are in range; `code` has 3 readable bytes past its last vertex, as a 32-bit
// gather at a byte offset reads 4), and the faces with a line compressed into `cand`. Integer
// operations only: the same list as liveFacesScalar().
// (GCC 12's AVX-512 headers set off -Wmaybe-uninitialized inside their own intrinsics.)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
[[gnu::target("avx512f")]] void liveFacesAvx512(const std::array<uint32_t, 3>* tri, const uint8_t* valid,
                                                const uint8_t* code, size_t begin, size_t end, uint32_t* const* cand,
                                                uint32_t* const* codes, size_t* n) {
  // Corner j of the faces 0..15 of a block lies at 3·i + j of its 48 indices: lanes from the
  // first two vectors (indices 0..31), then the rest from the third (index − 32).
  const __m512i take0 = _mm512_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 30, 0, 0, 0, 0, 0);
  const __m512i rest0 = _mm512_setr_epi32(0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 4, 7, 10, 13);
  const __m512i take1 = _mm512_setr_epi32(1, 4, 7, 10, 13, 16, 19, 22, 25, 28, 31, 0, 0, 0, 0, 0);
  const __m512i rest1 = _mm512_setr_epi32(0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 5, 8, 11, 14);
  const __m512i take2 = _mm512_setr_epi32(2, 5, 8, 11, 14, 17, 20, 23, 26, 29, 0, 0, 0, 0, 0, 0);
  const __m512i rest2 = _mm512_setr_epi32(0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 3, 6, 9, 12, 15);  // lane 10: 0
  const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m512i byte = _mm512_set1_epi32(0xff);
  const __m512i sign = _mm512_set1_epi32(kSignBits), pass = _mm512_set1_epi32(kPassBits),
                shut = _mm512_set1_epi32(kShutBits), low = _mm512_set1_epi32(kLowBits);
  const __m512i zero = _mm512_setzero_si512();
  const __m512i bit0 = _mm512_set1_epi32(1), bit1 = _mm512_set1_epi32(1 << kCodeBits);
  size_t n0 = n[0], n1 = n[1], f = begin;
  for (; f + 16 <= end; f += 16) {
    const uint32_t* t = tri[f].data();
    const __m512i a = _mm512_loadu_si512(t), b = _mm512_loadu_si512(t + 16), c = _mm512_loadu_si512(t + 32);
    const __m512i x0 = _mm512_mask_permutexvar_epi32(_mm512_permutex2var_epi32(a, take0, b), 0xF800, rest0, c);
    const __m512i x1 = _mm512_mask_permutexvar_epi32(_mm512_permutex2var_epi32(a, take1, b), 0xF800, rest1, c);
    const __m512i x2 = _mm512_mask_permutexvar_epi32(_mm512_permutex2var_epi32(a, take2, b), 0xFC00, rest2, c);
    const __mmask16 ok =
        _mm512_test_epi32_mask(_mm512_cvtepu8_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(valid + f))),
                               byte);
    const __m512i c0 = _mm512_and_si512(_mm512_mask_i32gather_epi32(zero, ok, x0, code, 1), byte);
    const __m512i c1 = _mm512_and_si512(_mm512_mask_i32gather_epi32(zero, ok, x1, code, 1), byte);
    const __m512i c2 = _mm512_and_si512(_mm512_mask_i32gather_epi32(zero, ok, x2, code, 1), byte);
    const __m512i all = _mm512_and_si512(_mm512_and_si512(c0, c1), c2);
    const __m512i any = _mm512_or_si512(_mm512_or_si512(c0, c1), c2);
    // (any & ~all & sign) & ((any & pass) >> 1) & (~(any & shut) >> 2) & (~(all & low) >> 3);
    // bits 0 and 4 count.
    __m512i live = _mm512_andnot_si512(all, _mm512_and_si512(any, sign));
    live = _mm512_and_si512(live, _mm512_srli_epi32(_mm512_and_si512(any, pass), 1));
    live = _mm512_andnot_si512(_mm512_srli_epi32(_mm512_and_si512(any, shut), 2), live);
    live = _mm512_andnot_si512(_mm512_srli_epi32(_mm512_and_si512(all, low), 3), live);
    const __mmask16 has0 = _mm512_test_epi32_mask(live, bit0), has1 = _mm512_test_epi32_mask(live, bit1);
    const __m512i faces = _mm512_add_epi32(lane, _mm512_set1_epi32(static_cast<int>(f)));
    const __m512i packed = _mm512_or_si512(c0, _mm512_or_si512(_mm512_slli_epi32(c1, 8), _mm512_slli_epi32(c2, 16)));
    _mm512_mask_compressstoreu_epi32(cand[0] + n0, has0, faces);
    _mm512_mask_compressstoreu_epi32(codes[0] + n0, has0, packed);
    _mm512_mask_compressstoreu_epi32(cand[1] + n1, has1, faces);
    _mm512_mask_compressstoreu_epi32(codes[1] + n1, has1, packed);
    n0 += static_cast<size_t>(__builtin_popcount(has0));
    n1 += static_cast<size_t>(__builtin_popcount(has1));
  }
  n[0] = n0;
  n[1] = n1;
  liveFacesScalar(tri, valid, code, f, end, cand, codes, n);
}
#pragma GCC diagnostic pop
#endif

// Appends to `dst` the segments of zero set `in` in face f, whose corners are `corner` with
// the codes c[3] (this zero set's bits), ids inside the face from `interior_id` up.
void faceSegments(std::span<const glm::vec3> positions, const std::array<uint32_t, 3>& corner,
                  const std::array<uint32_t, 3>& face_edges, uint32_t f, const uint8_t (&c)[3],
                  const ZeroSetInput& in, bool has_test, bool has_den, bool has_gain, LineKind type, LineSet& dst,
                  uint32_t edge_count, uint32_t& interior_id) {
  // The crossing on the edge (a, b), always interpolated from its lower vertex index to its
  // higher, so the two faces of an edge compute bit-identical points (and share the edge's
  // id: exact chaining).
  // The point itself is formed only once a piece of the face passes the test (point()).
  struct Crossing {
    uint32_t a, b;
    float s, t, num, den, gain, gate;
  };
  // Some corner's gate is below its minimum (not all: liveOf()): the pieces where the gate,
  // interpolated like the test, is below go.
  const bool clip = (c[0] | c[1] | c[2]) & kLow;
  auto crossingOf = [&](uint32_t a, uint32_t b) {
    if (b < a) std::swap(a, b);  // as MeshAdjacency::edges stores it
    const float va = in.value[a], vb = in.value[b];
    float t = va / (va - vb);
    if (!(t >= 0.0f && t <= 1.0f)) t = 0.5f;  // NaN input
    const float s = 1.0f - t;
    Crossing x{a, b, s, t, 1.0f, 1.0f, 1.0f, 0.0f};
    if (has_test) {
      x.num = s * in.test_num[a] + t * in.test_num[b];
      x.den = has_den ? s * in.test_den[a] + t * in.test_den[b] : 1.0f;
    }
    if (has_gain) x.gain = s * in.gain[a] + t * in.gain[b];
    // (Each corner's margin first: both above the minimum, or both below, keep their sign
    // however it rounds, so a face whose edge lies wholly above cuts nothing on it, as the
    // face beside it, which does not clip, does not.)
    if (clip) x.gate = s * (in.gate[a] - in.gate_min) + t * (in.gate[b] - in.gate_min);
    return x;
  };
  // The lone corner i has the other sign; its two sides i and i-1 cross.
  const bool s0 = c[0] & kNegative, s1 = c[1] & kNegative, s2 = c[2] & kNegative;
  const int i = (s0 == s1) ? 2 : (s0 == s2 ? 1 : 0);
  const int i2 = (i + 2) % 3;
  const Crossing x1 = crossingOf(corner[i], corner[(i + 1) % 3]), x2 = crossingOf(corner[i2], corner[i]);
  // A crossing exactly at a vertex (its value is 0: t is 0 or 1, the point is the vertex's
  // position) is one point for every face around it: the vertex's id.
  auto idOf = [&](const Crossing& x, uint32_t edge) {
    return in.value[x.a] == 0.0f ? edge_count + x.a : in.value[x.b] == 0.0f ? edge_count + x.b : edge;
  };
  const uint32_t e1 = idOf(x1, face_edges[i]);    // joins corners i and i + 1
  const uint32_t e2 = idOf(x2, face_edges[i2]);   // joins corners i + 2 and i
  // Both at the lone corner (nothing but a point), or joining two vertices where the caller
  // draws the edges itself.
  if (e1 == e2 || (in.skip_vertex_pairs && e1 >= edge_count && e2 >= edge_count)) return;
  auto point = [&](const Crossing& x) { return x.s * positions[x.a] + x.t * positions[x.b]; };
  if (!has_test && !clip) {
    pushSegment(dst, type, f, point(x1), e1, 1.0f, point(x2), e2, 1.0f);
    return;
  }
  const float n1 = x1.num, n2 = x2.num;
  const float d1 = x1.den, d2 = x2.den;
  const float q1 = x1.gate, q2 = x2.gate;
  // Breakpoints where num, den or the gate change sign along p1→p2 (linear interpolation).
  float z[5] = {0.0f, 0.0f, 0.0f, 0.0f, 1.0f};
  int nz = 1;
  if ((n1 >= 0.0f) != (n2 >= 0.0f)) z[nz++] = n1 / (n1 - n2);
  if ((d1 >= 0.0f) != (d2 >= 0.0f)) z[nz++] = d1 / (d1 - d2);
  if (clip && (q1 >= 0.0f) != (q2 >= 0.0f)) z[nz++] = q1 / (q1 - q2);
  z[nz++] = 1.0f;
  for (int a = 2; a + 1 < nz; ++a)  // the (at most three) breakpoints in order
    for (int b = a; b > 1 && z[b] < z[b - 1]; --b) std::swap(z[b], z[b - 1]);
  glm::vec3 p1, p2;
  bool have_points = false;
  for (int k = 0; k + 1 < nz; ++k) {
    const float za = z[k], zb = z[k + 1];
    if (!(zb > za)) continue;
    const float zm = 0.5f * (za + zb);
    const float nm = (1.0f - zm) * n1 + zm * n2, dm = (1.0f - zm) * d1 + zm * d2;
    if (!passes(nm, dm)) continue;
    if (clip && !((1.0f - zm) * q1 + zm * q2 >= 0.0f)) continue;
    const float na = (1.0f - za) * n1 + za * n2, da = (1.0f - za) * d1 + za * d2;
    const float nb = (1.0f - zb) * n1 + zb * n2, db = (1.0f - zb) * d1 + zb * d2;
    if (!have_points) {
      p1 = point(x1);
      p2 = point(x2);
      have_points = true;
    }
    const glm::vec3 pa = k == 0 ? p1 : (1.0f - za) * p1 + za * p2;
    const glm::vec3 pb = k + 2 == nz ? p2 : (1.0f - zb) * p1 + zb * p2;
    const uint32_t ida = k == 0 ? e1 : interior_id++;
    const uint32_t idb = k + 2 == nz ? e2 : interior_id++;
    float ga = 1.0f, gb = 1.0f;
    if (has_gain) {
      const float g1 = x1.gain, g2 = x2.gain;
      ga = std::clamp((1.0f - za) * g1 + za * g2, 0.0f, 1.0f);
      gb = std::clamp((1.0f - zb) * g1 + zb * g2, 0.0f, 1.0f);
    }
    const float fa = has_test ? fadeAlpha(na, da, in.fade) : 1.0f, fb = has_test ? fadeAlpha(nb, db, in.fade) : 1.0f;
    pushSegment(dst, type, f, pa, ida, ga * fa, pb, idb, gb * fb);
  }
}

}  // namespace

void extractZeroSets(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
                     const MeshAdjacency& adj, std::span<const ZeroSetInput> inputs, std::span<const LineKind> types,
                     LineScratch& scratch, LineSet& out) {
  const size_t ne = adj.edges.size();
  const size_t nv = positions.size();
  const size_t nf = faces.size();
  if (adj.vertex_count != nv || adj.face_count != nf || types.size() != inputs.size()) return;
  // Two zero sets a pass (their codes share a byte); the ones whose value is missing drop out.
  std::array<const ZeroSetInput*, 2> in{};
  std::array<LineKind, 2> type{};
  size_t count = 0;
  for (size_t k = 0; k < inputs.size(); ++k) {
    if (inputs[k].value.size() != nv) continue;
    if (count == 2) {  // flush the first two, then go on with the rest
      extractZeroSets(positions, faces, adj, std::span(inputs.data(), k), std::span(types.data(), k), scratch, out);
      extractZeroSets(positions, faces, adj, inputs.subspan(k), types.subspan(k), scratch, out);
      return;
    }
    in[count] = &inputs[k];
    type[count++] = types[k];
  }
  if (count == 0) return;
  bool has_test[2], has_den[2], has_gain[2];
  for (size_t k = 0; k < count; ++k) {
    has_test[k] = in[k]->test_num.size() == nv;
    has_den[k] = has_test[k] && in[k]->test_den.size() == nv;
    has_gain[k] = has_test[k] && in[k]->gain.size() == nv;
  }

  // Pass 1, per vertex: a byte of what the face pass asks of each corner (signs, tests,
  // gates), so the face pass reads three bytes of a small array instead of up to five floats
  // per corner and zero set, scattered over the mesh.
  // (3 bytes past the last vertex: the face pass gathers 32 bits at a vertex's byte.)
  scratch.vertex_code.resize(nv + 3);
  uint8_t* code = scratch.vertex_code.data();
  code[nv] = code[nv + 1] = code[nv + 2] = 0;
  auto codes = [&](size_t begin, size_t end) {
    for (size_t k = 0; k < count; ++k) vertexCodes(*in[k], static_cast<int>(k), begin, end, code);
  };
  if (scratch.pool && nv >= 16384) {
    scratch.pool->forRange(nv, 8192, codes);
  } else {
    codes(0, nv);
  }

  // Pass 2, per face: join the two crossings, keeping the pieces that pass the test; each
  // (part of the faces, zero set) into its own set with ids inside faces from ne + nv up, appended
  // below in zero-set order, then face order, with the ids shifted: the same output as one
  // pass per zero set over all faces.
  const uint8_t* valid = adj.face_valid.data();
  const std::array<uint32_t, 3>* tri = faces.data();
  // The faces with a line, per zero set, and their corners' codes (liveFacesScalar).
  void (*live_faces)(const std::array<uint32_t, 3>*, const uint8_t*, const uint8_t*, size_t, size_t,
                     uint32_t* const*, uint32_t* const*, size_t*) = liveFacesScalar;
#ifdef LODLINE_FACE_SCAN_AVX512
  if (scratch.wide_face_scan && __builtin_cpu_supports("avx512f")) live_faces = liveFacesAvx512;
#endif
  auto faces_pass = [&](size_t begin, size_t end, LineSet* const* dst, uint32_t* interior) {
    // In chunks: first the faces with a line (few, one well-predicted branch for the rest),
    // then those, one zero set after the other, each one's edge record fetched a few faces
    // ahead — the candidates are far apart, so each would otherwise wait for its own cache
    // miss. Each zero set's segments go to its own set, in face order, as before.
    constexpr size_t kChunk = 512, kAhead = 8;
    uint32_t cand0[kChunk], cand1[kChunk], codes0[kChunk], codes1[kChunk];
    uint32_t* const cand[2] = {cand0, cand1};
    uint32_t* const cand_codes[2] = {codes0, codes1};
    for (size_t base = begin; base < end; base += kChunk) {
      const size_t stop = std::min(end, base + kChunk);
      size_t n[2] = {0, 0};
      live_faces(tri, valid, code, base, stop, cand, cand_codes, n);
      for (size_t k = 0; k < count; ++k) {
        const int shift = kCodeBits * static_cast<int>(k);
        const uint32_t* ck_faces = cand[k];
        const uint32_t* ck_codes = cand_codes[k];
        for (size_t j = 0; j < n[k]; ++j) {
          if (j + kAhead < n[k]) __builtin_prefetch(&adj.face_edges[ck_faces[j + kAhead]]);
          const uint32_t f = ck_faces[j];
          const uint32_t cc = ck_codes[j];
          const uint8_t ck[3] = {static_cast<uint8_t>((cc & 0xff) >> shift),
                                 static_cast<uint8_t>(((cc >> 8) & 0xff) >> shift),
                                 static_cast<uint8_t>((cc >> 16) >> shift)};
          faceSegments(positions, tri[f], adj.face_edges[f], f, ck, *in[k], has_test[k], has_den[k], has_gain[k],
                       type[k], *dst[k], static_cast<uint32_t>(ne), interior[k]);
        }
      }
    }
  };
  const uint32_t base = static_cast<uint32_t>(ne + nv);  // the first id inside a face
  const size_t parts = (!scratch.pool || nf < 16384) ? 1 : 4 * scratch.pool->threadCount();
  scratch.part_sets.resize(parts * count);
  scratch.part_interior.assign(parts * count, 0);
  // With one part, the first zero set's segments go straight into `out` with their final ids,
  // instead of into a part set that would then be copied there.
  const bool direct = parts == 1;
  const uint32_t first_id = std::max(scratch.next_interior_id, base);
  auto run_part = [&](size_t c) {
    LineSet* dst[2] = {&scratch.part_sets[c * count], count > 1 ? &scratch.part_sets[c * count + 1] : nullptr};
    uint32_t ids[2] = {base, base};
    for (size_t k = 0; k < count; ++k) dst[k]->clear();
    if (direct) {
      dst[0] = &out;
      ids[0] = first_id;
    }
    faces_pass(nf * c / parts, nf * (c + 1) / parts, dst, ids);
    for (size_t k = 0; k < count; ++k)
      scratch.part_interior[c * count + k] = ids[k] - (direct && k == 0 ? first_id : base);
  };
  if (parts == 1) {
    run_part(0);
  } else {
    scratch.pool->forRange(parts, 1, [&](size_t begin, size_t end) {
      for (size_t c = begin; c < end; ++c) run_part(c);
    });
  }
  uint32_t interior_id = first_id;
  for (size_t k = 0; k < count; ++k) {
    for (size_t c = 0; c < parts; ++c) {
      if (direct && k == 0) {  // already in `out`
        interior_id += scratch.part_interior[0];
        continue;
      }
      const LineSet& part = scratch.part_sets[c * count + k];
      const uint32_t shift = interior_id - base;
      out.points.insert(out.points.end(), part.points.begin(), part.points.end());
      out.alpha.insert(out.alpha.end(), part.alpha.begin(), part.alpha.end());
      for (uint32_t id : part.point_ids) out.point_ids.push_back(id >= base ? id + shift : id);
      out.kinds.insert(out.kinds.end(), part.kinds.begin(), part.kinds.end());
      out.sources.insert(out.sources.end(), part.sources.begin(), part.sources.end());
      for (int j = 0; j < kLineKindCount; ++j) out.counts[j] += part.counts[j];
      interior_id += scratch.part_interior[c * count + k];
    }
  }
  scratch.next_interior_id = interior_id;
}

void extractZeroSet(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
                    const MeshAdjacency& adj, const ZeroSetInput& in, LineKind type, LineScratch& scratch,
                    LineSet& out) {
  extractZeroSets(positions, faces, adj, std::span(&in, 1), std::span(&type, 1), scratch, out);
}

namespace {

// Calls f(i) for each i with bytes[i] != 0, in order, eight zero bytes skipped at a time
// (the marked edges are a few hundred of ~100k).
template <class F>
void forEachNonZero(std::span<const uint8_t> bytes, F&& f) {
  const size_t n = bytes.size();
  size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    uint64_t word;
    std::memcpy(&word, bytes.data() + i, sizeof(word));
    if (word == 0) continue;
    for (size_t k = i; k < i + 8; ++k)
      if (bytes[k]) f(static_cast<uint32_t>(k));
  }
  for (; i < n; ++i)
    if (bytes[i]) f(static_cast<uint32_t>(i));
}

// Marks edges in scratch.edge_mark: 1 crease (when `want_creases`), 2 boundary (when
// `want_boundaries`), 0 otherwise, and lists the marked ones in edge order in
// scratch.marked_edges: a mesh has few, and the passes after this one read the list, not
// every edge. With `crease_vertices` (an adapted mesh, whose creases join vertices on the
// full-detail creases) only the edges at those vertices and at boundary vertices are tested,
// from their lower end, and edge_mark is valid at the listed edges only (0 elsewhere for
// edges it held before); without, every edge is marked. False when the inputs do not fit the
// mesh.
bool classifyEdges(const TriMesh& mesh, const MeshAdjacency& adj, std::span<const glm::vec3> face_normals,
                   const LineParams& params, bool want_creases, bool want_boundaries, LineScratch& scratch,
                   std::span<const uint8_t> crease_vertices) {
  const bool masked = crease_vertices.size() == mesh.positions.size();
  const size_t ne = adj.edges.size();
  auto& mark = scratch.edge_mark;
  for (const uint32_t e : scratch.marked_edges)  // the last call's marks, so the rest stays 0
    if (e < mark.size()) mark[e] = 0;
  scratch.marked_edges.clear();
  if (adj.vertex_count != mesh.positions.size() || face_normals.size() != adj.face_count) return false;
  const float cos_limit =
      std::cos(params.crease_angle_deg * std::numbers::pi_v<float> / 180.0f);
  const bool marked_lines = want_creases && params.marked_edges;
  mark.resize(ne, 0);
  auto markOf = [&](size_t e) -> uint8_t {
    const uint32_t count = adj.edge_face_count[e];
    if (count == 1) return want_boundaries ? 2 : 0;
    if (count == 2) {
      if (!want_creases || (masked && (!crease_vertices[adj.edges[e][0]] || !crease_vertices[adj.edges[e][1]])))
        return 0;
      const glm::vec3& n1 = face_normals[adj.edge_faces[e][0]];
      const glm::vec3& n2 = face_normals[adj.edge_faces[e][1]];
      return glm::dot(n1, n1) != 0.0f && glm::dot(n2, n2) != 0.0f && glm::dot(n1, n2) < cos_limit ? 1 : 0;
    }
    return count > 2 && marked_lines ? 1 : 0;
  };
  auto& list = scratch.marked_edges;
  if (masked) {
    // An edge that can be marked has both ends on a full-detail crease (a crease) or on a
    // boundary (a boundary or non-manifold edge). Those vertices, eight others skipped at a
    // time, then the edges of their rings that start at them.
    const size_t nv = mesh.positions.size();
    const uint8_t* crease = crease_vertices.data();
    const uint8_t* open = adj.vertex_on_boundary.size() == nv ? adj.vertex_on_boundary.data() : nullptr;
    const bool want_open = open && (want_boundaries || marked_lines);
    auto visit = [&](uint32_t v) {
      if (!(want_creases && crease[v]) && !(want_open && open[v])) return;
      const uint32_t begin = adj.vertex_face_begin[v], end = adj.vertex_face_end[v];
      for (uint32_t i = begin; i < end; ++i) {
        const auto& fe = adj.face_edges[adj.vertex_faces[i]];
        const uint8_t c = adj.vertex_face_corners[i];
        for (const uint32_t e : {fe[c], fe[c == 0 ? 2 : c - 1]}) {  // the two sides at corner c
          if (e == kNoIndex || adj.edges[e][0] != v || mark[e]) continue;
          if ((mark[e] = markOf(e))) list.push_back(e);
        }
      }
    };
    uint32_t v = 0;
    for (; v + 8 <= nv; v += 8) {
      uint64_t a = 0, b = 0;
      if (want_creases) std::memcpy(&a, crease + v, sizeof(a));
      if (want_open) std::memcpy(&b, open + v, sizeof(b));
      if ((a | b) == 0) continue;
      for (uint32_t u = v; u < v + 8; ++u) visit(u);
    }
    for (; v < nv; ++v) visit(v);
  } else {
    auto classify = [&](size_t begin, size_t end) {  // each edge writes only its own mark
      for (size_t e = begin; e < end; ++e) mark[e] = markOf(e);
    };
    if (scratch.pool) {
      scratch.pool->forRange(ne, 8192, classify);
    } else {
      classify(0, ne);
    }
  }
  // Marked edges are creases whatever their angle; on a boundary they stay boundaries when
  // those are drawn.
  if (marked_lines) {
    for (const EdgeKey& k : mesh.marked_edges) {
      const uint32_t e = adj.findEdge(k[0], k[1]);
      if (e == kNoIndex) continue;
      if (masked && !mark[e]) list.push_back(e);
      mark[e] = adj.edge_face_count[e] == 1 && want_boundaries ? 2 : 1;
    }
  }
  if (masked) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());  // (a marked edge listed twice)
    return true;
  }
  forEachNonZero(mark, [&](uint32_t e) { list.push_back(e); });
  return true;
}

// Appends the edges scratch.edge_mark marks (listed in scratch.marked_edges): creases if
// params.creases, boundaries if params.boundaries.
void pushEdgeLines(const TriMesh& mesh, const MeshAdjacency& adj, const LineParams& params, const LineScratch& scratch,
                   LineSet& out) {
  for (const uint32_t e : scratch.marked_edges) {
    const uint8_t m = scratch.edge_mark[e];
    if ((m == 1 && !params.creases) || (m == 2 && !params.boundaries)) continue;
    const uint32_t a = adj.edges[e][0], b = adj.edges[e][1];
    pushSegment(out, m == 2 ? LineKind::kBoundary : LineKind::kCrease, e, mesh.positions[a], a, 1.0f,
                mesh.positions[b], b, 1.0f);
  }
}

// Facing of face f from `view`: the sign of n·(eye − p) at its first corner (perspective), or
// of n·toward_viewer (orthographic); 0 for a degenerate face.
int faceFacing(const TriMesh& mesh, std::span<const glm::vec3> face_normals, const ViewSpec& view, uint32_t f) {
  const glm::vec3& n = face_normals[f];
  if (glm::dot(n, n) == 0.0f) return 0;
  const glm::vec3 to_eye = view.orthographic ? view.toward_viewer : view.eye - mesh.positions[mesh.faces[f][0]];
  return glm::dot(n, to_eye) > 0.0f ? 1 : -1;
}

// The contour's value with the vertices of silhouette creases (crease edges whose faces face
// opposite ways, in scratch.edge_mark; listed in scratch.silhouette_creases) at 0
// (LineParams::contours_follow_creases); `ndotv` itself when there is none.
std::span<const float> contourValue(const TriMesh& mesh, const MeshAdjacency& adj,
                                    std::span<const glm::vec3> face_normals, const ViewQuantities& view,
                                    LineScratch& scratch) {
  bool copied = false;
  scratch.silhouette_creases.clear();
  for (const uint32_t e : scratch.marked_edges) {
    if (scratch.edge_mark[e] != 1 || adj.edge_face_count[e] != 2) continue;
    const int a = faceFacing(mesh, face_normals, view.view, adj.edge_faces[e][0]);
    const int b = faceFacing(mesh, face_normals, view.view, adj.edge_faces[e][1]);
    if (a == 0 || b == 0 || a == b) continue;
    scratch.silhouette_creases.push_back(e);
    if (!copied) {
      scratch.contour_value.assign(view.ndotv.begin(), view.ndotv.end());
      copied = true;
    }
    scratch.contour_value[adj.edges[e][0]] = 0.0f;
    scratch.contour_value[adj.edges[e][1]] = 0.0f;
  }
  return copied ? std::span<const float>(scratch.contour_value) : std::span<const float>(view.ndotv);
}

// Where the smooth contour meets a silhouette crease, the faces' own facing (which decides
// the crease) and the interpolated n·v (which decides the smooth contour) may disagree by a
// face: the crease then runs an edge or two past the meeting point, a spur with a free end
// beside a vertex where three contour ends meet. Such spurs are dropped from
// scratch.silhouette_creases, so the contour stays one line through the meeting point.
void pruneCreaseSpurs(const MeshAdjacency& adj, const LineSet& out, LineScratch& scratch) {
  const uint32_t ne = static_cast<uint32_t>(adj.edges.size()), nv = adj.vertex_count;
  auto& ends = scratch.vertex_ends;
  ends.assign(nv, 0);
  auto count = [&](uint32_t id) {
    if (id >= ne && id - ne < nv && ends[id - ne] < 255) ++ends[id - ne];
  };
  for (size_t k = 0; k < out.kinds.size(); ++k)
    if (out.kinds[k] == LineKind::kContour) {
      count(out.point_ids[2 * k]);
      count(out.point_ids[2 * k + 1]);
    }
  auto& list = scratch.silhouette_creases;
  for (uint32_t e : list) {
    count(ne + adj.edges[e][0]);
    count(ne + adj.edges[e][1]);
  }
  for (int round = 0; round < 4; ++round) {  // a spur is an edge or two long
    bool changed = false;
    for (uint32_t& e : list) {
      if (e == kNoIndex) continue;
      const uint32_t a = adj.edges[e][0], b = adj.edges[e][1];
      if ((ends[a] == 1 && ends[b] >= 3) || (ends[b] == 1 && ends[a] >= 3)) {
        --ends[a];
        --ends[b];
        e = kNoIndex;
        changed = true;
      }
    }
    if (!changed) break;
  }
  list.erase(std::remove(list.begin(), list.end(), kNoIndex), list.end());
}

}  // namespace

void extractEdgeLines(const TriMesh& mesh, const MeshAdjacency& adj,
                      std::span<const glm::vec3> face_normals, const LineParams& params,
                      LineScratch& scratch, LineSet& out, std::span<const uint8_t> crease_vertices) {
  if (!params.creases && !params.boundaries) return;
  if (classifyEdges(mesh, adj, face_normals, params, params.creases, params.boundaries, scratch, crease_vertices))
    pushEdgeLines(mesh, adj, params, scratch, out);
}

void extractMeshSilhouette(const TriMesh& mesh, const MeshAdjacency& adj, std::span<const glm::vec3> face_normals,
                           const ViewSpec& view, LineScratch& scratch, LineSet& out) {
  out.clear();
  // Each face's facing once, in face order; then each edge reads two bytes and marks itself
  // (both passes on the pool's threads); then the marked edges, in edge order.
  auto& facing = scratch.face_facing;
  facing.resize(mesh.faces.size());
  auto faces = [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; ++f)
      facing[f] = static_cast<int8_t>(faceFacing(mesh, face_normals, view, static_cast<uint32_t>(f)));
  };
  const size_t ne = adj.edges.size();
  auto& mark = scratch.silhouette_edge;
  mark.resize(ne);
  auto edges = [&](size_t begin, size_t end) {
    for (size_t e = begin; e < end; ++e) {
      const int a = facing[adj.edge_faces[e][0] == kNoIndex ? 0 : adj.edge_faces[e][0]];
      const int b = facing[adj.edge_faces[e][1] == kNoIndex ? 0 : adj.edge_faces[e][1]];
      mark[e] = adj.edge_face_count[e] == 2 && a != 0 && b != 0 && a != b;
    }
  };
  if (scratch.pool) {
    scratch.pool->forRange(mesh.faces.size(), 8192, faces);
    scratch.pool->forRange(ne, 8192, edges);
  } else {
    faces(0, mesh.faces.size());
    edges(0, ne);
  }
  auto push = [&](size_t e) {
    const uint32_t v0 = adj.edges[e][0], v1 = adj.edges[e][1];
    pushSegment(out, LineKind::kContour, static_cast<uint32_t>(e), mesh.positions[v0], v0, 1.0f, mesh.positions[v1],
                v1, 1.0f);
  };
  forEachNonZero(mark, push);
}

void extractLines(const TriMesh& mesh, const MeshAdjacency& adj,
                  std::span<const glm::vec3> face_normals, const ViewQuantities& view,
                  const LineParams& params, float feature_size, LineScratch& scratch,
                  LineSet& out, std::span<const uint8_t> crease_vertices,
                  std::span<const float> suggestive_gain) {
  out.clear();
  scratch.next_interior_id = 0;
  const float fs = feature_size > 0.0f && std::isfinite(feature_size) ? feature_size : 1.0f;
  ZeroSetInput in[6];
  LineKind types[6];
  size_t n = 0;
  // Edges first: the contour follows the creases that are silhouettes.
  const bool follow = params.contours && params.contours_follow_creases && view.ndotv.size() == mesh.positions.size();
  const bool off_creases = params.suggestive_off_creases && (params.suggestive || params.suggestive_highlights);
  const bool classified = (follow || params.creases || params.boundaries || off_creases) &&
                          classifyEdges(mesh, adj, face_normals, params, params.creases || follow || off_creases,
                                        params.boundaries, scratch, crease_vertices);
  // The vertices on crease edges, where the suggestive kinds are not drawn.
  std::span<const uint8_t> crease_shut;
  if (off_creases && classified) {
    scratch.crease_vertex.assign(mesh.positions.size(), 0);
    for (const uint32_t e : scratch.marked_edges)
      if (scratch.edge_mark[e] == 1) scratch.crease_vertex[adj.edges[e][0]] = scratch.crease_vertex[adj.edges[e][1]] = 1;
    crease_shut = scratch.crease_vertex;
  }
  const bool on_creases = follow && classified;
  if (params.contours) {
    in[n].value = on_creases ? contourValue(mesh, adj, face_normals, view, scratch) : view.ndotv;
    in[n].skip_vertex_pairs = on_creases;
    if (params.contours_require_positive_kr) in[n].test_num = view.kr;
    types[n++] = LineKind::kContour;
  }
  // Both suggestive kinds: kr = 0, tested by num/cosθ, gated and faded alike.
  const size_t nv = mesh.positions.size();
  auto kr_zero = [&](std::span<const float> test_num, LineKind type, std::span<const float> gain) {
    in[n].value = view.kr;
    in[n].test_num = test_num;
    in[n].test_den = view.ndotv;
    in[n].gate = view.ndotv;
    in[n].gate_min = params.suggestive_min_ndotv;
    in[n].fade = params.suggestive_fade / (fs * fs);
    in[n].gain = gain;
    in[n].shut = crease_shut;
    types[n++] = type;
  };
  if (params.suggestive && view.sc_num.size() == nv) kr_zero(view.sc_num, LineKind::kSuggestive, suggestive_gain);
  if (params.suggestive_highlights && view.sh_num.size() == nv)
    kr_zero(view.sh_num, LineKind::kSuggestiveHighlight, {});
  // The level-set kinds (lines/level_lines.h), where their quantities were computed.
  if (params.isophotes && view.isophote.size() == nv && view.isophote_test.size() == nv) {
    in[n].value = view.isophote;
    in[n].test_num = view.isophote_test;
    types[n++] = LineKind::kIsophote;
  }
  if (params.topo && view.topo.size() == nv) {
    in[n].value = view.topo;
    types[n++] = LineKind::kTopo;
  }
  if (params.parabolic && view.parabolic.size() == nv && view.parabolic_test.size() == nv) {
    in[n].value = view.parabolic;
    in[n].test_num = view.parabolic_test;
    types[n++] = LineKind::kParabolic;
  }
  extractZeroSets(mesh.positions, mesh.faces, adj, std::span(in, n), std::span(types, n), scratch, out);
  // The contour along silhouette creases, with the ids of points at vertices (edgeCount +
  // vertex) that the zero set's crossings at those vertices use too.
  const uint32_t ne = static_cast<uint32_t>(adj.edges.size());
  if (on_creases && !scratch.silhouette_creases.empty()) pruneCreaseSpurs(adj, out, scratch);
  if (on_creases)
    for (uint32_t e : scratch.silhouette_creases) {
      const uint32_t a = adj.edges[e][0], b = adj.edges[e][1];
      const uint32_t f0 = adj.edge_faces[e][0], f1 = adj.edge_faces[e][1];
      const uint32_t front = faceFacing(mesh, face_normals, view.view, f0) > 0 ? f0 : f1;
      pushSegment(out, LineKind::kContour, front, mesh.positions[a], ne + a, 1.0f, mesh.positions[b], ne + b, 1.0f);
    }
  if (classified) pushEdgeLines(mesh, adj, params, scratch, out);
  if (params.materials) extractMaterialLines(mesh, adj, out);
}

void extractMaterialLines(const TriMesh& mesh, const MeshAdjacency& adj, LineSet& out) {
  const auto& mat = mesh.face_materials;
  if (mat.size() != mesh.faces.size() || adj.face_count != mesh.faces.size() ||
      adj.vertex_count != mesh.positions.size())
    return;
  for (size_t e = 0; e < adj.edges.size(); ++e) {
    if (adj.edge_face_count[e] != 2) continue;
    if (mat[adj.edge_faces[e][0]] == mat[adj.edge_faces[e][1]]) continue;
    const uint32_t a = adj.edges[e][0], b = adj.edges[e][1];
    pushSegment(out, LineKind::kMaterial, static_cast<uint32_t>(e), mesh.positions[a], a, 1.0f, mesh.positions[b], b,
                1.0f);
  }
}

void LineExtractor::extract(const TriMesh& mesh, const ShapeCache& shape, const ViewSpec& view,
                            const LineParams& params, float feature_size, LineSet& out) {
  extract(mesh, shape, shape.fields(mesh), view, params, feature_size, out);
}

void LineExtractor::extract(const TriMesh& mesh, const ShapeCache& shape,
                            const SurfaceFields& fields, const ViewSpec& view,
                            const LineParams& params, float feature_size, LineSet& out) {
  const float fs = feature_size > 0.0f && std::isfinite(feature_size) ? feature_size : 1.0f;
  SurfaceFields f = fields;
  if (!params.suggestive && !params.suggestive_highlights) f.dcurv = {};
  computeViewQuantities(f, view, params.suggestive_threshold / (fs * fs), view_);
  if (params.suggestive_highlights) suggestiveHighlightTest(params.suggestive_threshold / (fs * fs), view_);
  extractLines(mesh, shape.adjacency(), shape.faceNormals(), view_, params, fs, scratch_, out);
}

}  // namespace lodline
