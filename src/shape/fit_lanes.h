// Lane types for the per-face fits of shape_cache.cpp: the same source computes one face
// (float, double, bool masks) or eight faces at once (GCC vector extensions: eight floats,
// eight doubles, and their comparison masks). Every operation is an IEEE operation applied
// lane by lane, in the order written, and the build fuses no multiply-adds
// (-ffp-contract=off, CMakeLists.txt), so each lane of the eight-face form computes the bits
// the one-face form computes for that face: the full compute (eight at a time) and the
// incremental updates (one face at a time) agree bit for bit (docs/design.md, convention 18).
// Branches become selects: both sides are computed and the mask picks one.
#pragma once

#include <cstdint>

// Values of these types only pass between inline functions, never across a call boundary
// that another translation unit sees, so the ABI note GCC gives for them does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace lodline::lanes {

using F8 = float __attribute__((vector_size(32)));
using D8 = double __attribute__((vector_size(64)));
using MF8 = int32_t __attribute__((vector_size(32)));   // mask of a float comparison
using MD8 = int64_t __attribute__((vector_size(64)));   // mask of a double comparison
inline constexpr int kWidth = 8;

inline double toDouble(float x) { return static_cast<double>(x); }
inline D8 toDouble(F8 x) { return __builtin_convertvector(x, D8); }
inline float toFloat(double x) { return static_cast<float>(x); }
inline F8 toFloat(D8 x) { return __builtin_convertvector(x, F8); }
inline bool toDoubleMask(bool m) { return m; }
inline MD8 toDoubleMask(MF8 m) { return __builtin_convertvector(m, MD8); }
inline bool toFloatMask(bool m) { return m; }
inline MF8 toFloatMask(MD8 m) { return __builtin_convertvector(m, MF8); }

inline bool both(bool a, bool b) { return a && b; }
inline MF8 both(MF8 a, MF8 b) { return a & b; }
inline MD8 both(MD8 a, MD8 b) { return a & b; }

/// m ? a : b, lane by lane.
inline float select(bool m, float a, float b) { return m ? a : b; }
inline double select(bool m, double a, double b) { return m ? a : b; }
inline F8 select(MF8 m, F8 a, F8 b) { return m ? a : b; }
inline D8 select(MD8 m, D8 a, D8 b) { return m ? a : b; }

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

}  // namespace lodline::lanes

namespace lodline::lanes {

/// W consecutive floats from p as one value of F (W = 1 for float, 8 for F8).
template <class F>
inline F load(const float* p);
template <>
inline float load<float>(const float* p) {
  return *p;
}
template <>
inline F8 load<F8>(const float* p) {
  F8 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
inline void store(float* p, float v) { *p = v; }
inline void store(float* p, F8 v) { __builtin_memcpy(p, &v, sizeof v); }
inline void storeMask(int32_t* p, bool m) { *p = m ? -1 : 0; }
inline void storeMask(int32_t* p, MF8 m) { __builtin_memcpy(p, &m, sizeof m); }

}  // namespace lodline::lanes
