#include "core/mesh.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lodline {

float Bounds::diagonal() const { return glm::length(max - min); }

Bounds computeBounds(std::span<const glm::vec3> positions) {
  Bounds b;
  if (positions.empty()) return b;
  b.min = b.max = positions[0];
  for (const glm::vec3& p : positions) {
    b.min = glm::min(b.min, p);
    b.max = glm::max(b.max, p);
  }
  b.center = 0.5f * (b.min + b.max);
  float r2 = 0.0f;
  for (const glm::vec3& p : positions) {
    const glm::vec3 d = p - b.center;
    r2 = std::max(r2, glm::dot(d, d));
  }
  b.radius = std::sqrt(r2);
  return b;
}

void computeFaceNormals(const TriMesh& mesh, std::vector<glm::vec3>& out) {
  out.resize(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    const glm::vec3 n = glm::cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                                   mesh.positions[t[2]] - mesh.positions[t[0]]);
    const float len = glm::length(n);
    out[f] = len > 0.0f ? n / len : glm::vec3(0.0f);
  }
}

float medianEdgeLength(const TriMesh& mesh, std::vector<float>& lengths) {
  const size_t nf = mesh.faces.size(), nv = mesh.positions.size();
  lengths.clear();
  if (nf == 0) return 0.0f;
  const size_t samples = std::min<size_t>(nf, 4096);
  for (size_t k = 0; k < samples; ++k) {
    const auto& f = mesh.faces[k * nf / samples];
    for (int j = 0; j < 3; ++j) {
      const uint32_t a = f[j], b = f[(j + 1) % 3];
      if (a < nv && b < nv) lengths.push_back(glm::length(mesh.positions[a] - mesh.positions[b]));
    }
  }
  if (lengths.empty()) return 0.0f;
  auto mid = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), mid, lengths.end());
  return std::isfinite(*mid) ? *mid : 0.0f;
}

}  // namespace lodline
