// LODLINE_AVX2_CLONES: compile a vectorisable hot loop twice, for AVX2 and for the baseline
// x86-64 (SSE2) the build targets, and pick one when the program loads (GCC's target_clones,
// an ifunc). The release build keeps the baseline so that one binary runs on any x86-64; the
// loops so marked run eight floats a step where the processor allows.
// LODLINE_AVX512_CLONES adds an AVX-512F clone for loops whose arithmetic is plain enough
// for the vectoriser to widen (sixteen floats a step where GCC chooses 512-bit vectors, as in
// the line stage's per-vertex loops; eight where it keeps to 256 bits, as in lod/face_areas).
//
// Only for loops whose results do not depend on the clone: the clones enable no FMA, the
// build fuses no multiply-adds (-ffp-contract=off, CMakeLists.txt), and IEEE division and
// square root are exact, so each lane computes the bits the scalar code does. The test
// (tests/lines/lines_test.cpp, ViewQuantities.VectorPassEqualsThePerVertexPathBitForBit)
// checks the clone the test machine picks against the per-vertex code.
// Elsewhere (other architectures, other compilers, C libraries without ifuncs) it expands to
// nothing.
#pragma once

#include <cstddef>  // defines __GLIBC__ where the C library is glibc

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__linux__) && defined(__GLIBC__)
#define LODLINE_AVX2_CLONES [[gnu::target_clones("avx2", "default")]]
#define LODLINE_AVX512_CLONES [[gnu::target_clones("avx512f", "avx2", "default")]]
#else
#define LODLINE_AVX2_CLONES
#define LODLINE_AVX512_CLONES
#endif
