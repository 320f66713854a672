// LODLINE_AVX2_CLONES: compile a vectorisable hot loop twice, for AVX2 and for the baseline
// x86-64 (SSE2) the build targets, and pick one when the program loads (GCC's target_clones,
// an ifunc). The release build keeps the baseline so that one binary runs on any x86-64; the
// loops so marked run eight floats a step where the processor allows.
//
// Only for loops whose results do not depend on the clone: no FMA is enabled (AVX2 alone), the
// build contracts no multiply-adds (-std=c++20, not gnu++20), and IEEE division and square root
// are exact, so each lane computes the same bits as the scalar code
// (tests/lines/lines_test.cpp, ViewQuantities.VectorPassEqualsThePerVertexPathBitForBit).
// Elsewhere (other architectures, other compilers) it expands to nothing.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define LODLINE_AVX2_CLONES [[gnu::target_clones("avx2", "default")]]
#else
#define LODLINE_AVX2_CLONES
#endif
