// Test meshes for the pm and lod tests: generated surfaces plus a tiny OFF reader for the
// CGAL demo meshes in data/meshes (tests skip when they are missing).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/mesh.h"
#include "io/generate.h"

namespace lodline::test {

/// Reads a triangle/polygon OFF file (polygons fan-triangulated); false on any problem.
inline bool readOff(const std::filesystem::path& path, TriMesh& out) {
  std::ifstream in(path);
  std::string tok;
  if (!(in >> tok) || tok != "OFF") return false;
  size_t nv = 0, nf = 0, ne = 0;
  if (!(in >> nv >> nf >> ne)) return false;
  out = TriMesh{};
  out.positions.resize(nv);
  for (auto& p : out.positions)
    if (!(in >> p.x >> p.y >> p.z)) return false;
  for (size_t f = 0; f < nf; ++f) {
    size_t k = 0;
    if (!(in >> k) || k < 3) return false;
    std::vector<uint32_t> idx(k);
    for (auto& i : idx)
      if (!(in >> i) || i >= nv) return false;
    std::string rest;
    std::getline(in, rest);
    for (size_t j = 1; j + 1 < k; ++j) out.faces.push_back({idx[0], idx[j], idx[j + 1]});
  }
  return true;
}

/// Moves every vertex along its position direction by up to ±`amount` (deterministic).
inline void perturbRadially(TriMesh& m, float amount, uint32_t seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(-amount, amount);
  for (auto& p : m.positions) {
    const float len = glm::length(p);
    if (len > 0.0f) p *= 1.0f + d(rng) / len;
  }
}

/// Canonical rotation of a face (smallest index first), for order-free comparisons.
inline std::array<uint32_t, 3> canonicalFace(std::array<uint32_t, 3> f) {
  while (f[0] > f[1] || f[0] > f[2]) f = {f[1], f[2], f[0]};
  return f;
}

inline std::vector<std::array<uint32_t, 3>> sortedFaces(std::vector<std::array<uint32_t, 3>> fs) {
  for (auto& f : fs) f = canonicalFace(f);
  std::sort(fs.begin(), fs.end());
  return fs;
}

}  // namespace lodline::test
