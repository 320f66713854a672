// Lane types for the per-face kernels of shape_cache.cpp (face geometry, curvature fit,
// derivative fit): kWidth faces at once, with GCC vector extensions (floats, doubles and
// their comparison masks; clang accepts them too). Every operation is an IEEE operation
// applied lane by lane, in the order written, and the build fuses no multiply-adds
// (-ffp-contract=off, CMakeLists.txt), so a face's results do not depend on its lane, on the
// other faces of its block or on the clone (AVX2 or baseline) the machine picks: the full
// compute (every face, in order) and the incremental updates (the changed faces, in any
// grouping) agree bit for bit. Branches become selects: both sides are computed and the mask
// picks one.
#pragma once

#include <cstdint>

// Values of these types only pass between inline functions, never across a call boundary
// that another translation unit sees, so the ABI note GCC gives for them does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace lodline::lanes {

/// Four lanes: four doubles fill an AVX2 register (the fits solve in double), and no type is
/// wider than the hardware's, which GCC would otherwise lower element by element.
inline constexpr int kWidth = 4;
using FL = float __attribute__((vector_size(4 * kWidth)));
using DL = double __attribute__((vector_size(8 * kWidth)));
using MFL = int32_t __attribute__((vector_size(4 * kWidth)));  // mask of a float comparison
using MDL = int64_t __attribute__((vector_size(8 * kWidth)));  // mask of a double comparison

inline DL toDouble(FL x) { return __builtin_convertvector(x, DL); }
inline FL toFloat(DL x) { return __builtin_convertvector(x, FL); }
inline MFL toFloatMask(MDL m) { return __builtin_convertvector(m, MFL); }

inline MFL both(MFL a, MFL b) { return a & b; }
inline MDL both(MDL a, MDL b) { return a & b; }

/// m ? a : b, lane by lane.
inline FL select(MFL m, FL a, FL b) { return m ? a : b; }
inline DL select(MDL m, DL a, DL b) { return m ? a : b; }

/// Square root, lane by lane (exact IEEE, as std::sqrt).
inline FL sqrtLanes(FL x) {
  FL r;
  for (int i = 0; i < kWidth; ++i) r[i] = __builtin_sqrtf(x[i]);
  return r;
}

/// x is neither infinite nor NaN (x − x is 0 exactly then, NaN otherwise).
template <class T>
inline auto finite(T x) {
  return x - x == T{};
}

/// |x| for the maxima below (−0 and NaN pass through; only comparisons read the result).
template <class T>
inline T absValue(T x) {
  return select(x < T{}, -x, x);
}

/// A vector of three lanes-wide coordinates.
template <class T>
struct Vec3L {
  T x, y, z;
};
template <class T>
inline Vec3L<T> operator-(const Vec3L<T>& a, const Vec3L<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
inline Vec3L<T> operator+(const Vec3L<T>& a, const Vec3L<T>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
inline Vec3L<T> operator*(T s, const Vec3L<T>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
/// As glm::dot: the three products, summed left to right.
template <class T>
inline T dot(const Vec3L<T>& a, const Vec3L<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}


/// Float k of each lane's source, src[lane][k], as one vector. Built from scalar loads:
/// staging the lanes through memory and loading them as one vector would stall on store
/// forwarding.
inline FL gather(const float* const* src, int k) {
  static_assert(kWidth == 4);
  return FL{src[0][k], src[1][k], src[2][k], src[3][k]};
}

inline void store(float* p, FL v) { __builtin_memcpy(p, &v, sizeof v); }
inline void storeMask(int32_t* p, MFL m) { __builtin_memcpy(p, &m, sizeof m); }

}  // namespace lodline::lanes
