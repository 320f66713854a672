// Jeong et al. 2005 §3.1 (the image areas the criterion averages); see face_areas.h.
#include "lod/face_areas.h"

#include <algorithm>
#include <cmath>

#include "core/simd_clones.h"

namespace lodline {
namespace {

template <bool kOrtho>
[[gnu::always_inline]] inline void faceAreasIn(const FaceAreaView& a, size_t begin, size_t end,
                                               float* __restrict area, uint8_t* __restrict visible) {
  // Blocks of corner positions gathered into plain per-component arrays (a short last block
  // padded), then the arithmetic over whole blocks: a fixed trip count over memory nothing
  // else aliases is what the vectoriser needs (as the view quantities do, lines/).
  constexpr size_t kBlock = 64;
  alignas(64) float x0[kBlock], y0[kBlock], z0[kBlock], x1[kBlock], y1[kBlock], z1[kBlock];
  alignas(64) float x2[kBlock], y2[kBlock], z2[kBlock], o_area[kBlock];
  alignas(64) uint8_t o_vis[kBlock];
  const float ex = a.eye.x, ey = a.eye.y, ez = a.eye.z;
  const float fx = a.forward.x, fy = a.forward.y, fz = a.forward.z;
  const float kk = a.k, near2 = a.near2;
  float pl[kFrustumPlanes][4];
  for (int i = 0; i < kFrustumPlanes; ++i)
    for (int j = 0; j < 4; ++j) pl[i][j] = a.planes[i][j];
  for (size_t b = begin; b < end; b += kBlock) {
    const size_t n = std::min(kBlock, end - b);
    for (size_t j = 0; j < n; ++j) {
      const auto& c = a.faces[b + j];
      const glm::vec3 &p0 = a.pos[c[0]], &p1 = a.pos[c[1]], &p2 = a.pos[c[2]];
      x0[j] = p0.x, y0[j] = p0.y, z0[j] = p0.z;
      x1[j] = p1.x, y1[j] = p1.y, z1[j] = p1.z;
      x2[j] = p2.x, y2[j] = p2.y, z2[j] = p2.z;
    }
    for (size_t j = n; j < kBlock; ++j) x0[j] = y0[j] = z0[j] = x1[j] = y1[j] = z1[j] = x2[j] = y2[j] = z2[j] = 0.0f;
    for (size_t j = 0; j < kBlock; ++j) {
      // glm's cross, length, dot and centre, spelled out in the same order of operations.
      const float ux = x1[j] - x0[j], uy = y1[j] - y0[j], uz = z1[j] - z0[j];
      const float vx = x2[j] - x0[j], vy = y2[j] - y0[j], vz = z2[j] - z0[j];
      const float nx = uy * vz - vy * uz, ny = uz * vx - vz * ux, nz = ux * vy - vx * uy;
      const float face_area = 0.5f * std::sqrt(nx * nx + ny * ny + nz * nz);
      const float cx = (x0[j] + x1[j] + x2[j]) * (1.0f / 3.0f), cy = (y0[j] + y1[j] + y2[j]) * (1.0f / 3.0f),
                  cz = (z0[j] + z1[j] + z2[j]) * (1.0f / 3.0f);
      const float mx = cx - ex, my = cy - ey, mz = cz - ez;
      o_area[j] = kOrtho ? kk * face_area : kk * face_area / std::max(mx * mx + my * my + mz * mz, near2);
      const float dx = kOrtho ? fx : mx, dy = kOrtho ? fy : my, dz = kOrtho ? fz : mz;
      bool in = nx * dx + ny * dy + nz * dz < 0.0f;
      for (int i = 0; i < kFrustumPlanes; ++i) in &= pl[i][0] * cx + pl[i][1] * cy + pl[i][2] * cz + pl[i][3] >= 0.0f;
      o_vis[j] = in;
    }
    std::copy_n(o_area, n, area + b);
    std::copy_n(o_vis, n, visible + b);
  }
}

}  // namespace

// Compiled for AVX-512F and AVX2 where the processor has them, and for plain x86-64; no FMA in
// any clone, and square roots and divisions are exact, so every clone gives the same bits
// (docs/design.md §6, item 17).
LODLINE_AVX512_CLONES void faceImageAreas(const FaceAreaView& a, size_t begin, size_t end, float* area,
                                          uint8_t* visible) {
  if (a.ortho) faceAreasIn<true>(a, begin, end, area, visible);
  else faceAreasIn<false>(a, begin, end, area, visible);
}

}  // namespace lodline
