// LODLINE_AVX2_CLONES: compile a vectorisable hot loop twice, for AVX2 and for the baseline
// x86-64 (SSE2) the build targets, and pick one when the program loads (GCC's target_clones,
// an ifunc). The release build keeps the baseline so that one binary runs on any x86-64; the
// loops so marked run eight floats a step where the processor allows.
//
// Only for loops whose results do not depend on the clone: the AVX2 clone enables no FMA, the
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
#else
#define LODLINE_AVX2_CLONES
#endif
