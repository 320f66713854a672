#include "io/generate.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include <glm/geometric.hpp>

namespace lodline {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Adds the quads of a (rows+1) × cols vertex grid wrapped around in the column direction
// (and in the row direction when wrap_rows), vertex (i, j) at index base + i·cols + j.
// `flip` reverses the winding (the caller picks the one whose normals point outward).
void addWrappedQuads(TriMesh& m, uint32_t base, int rows, int cols, bool wrap_rows, bool flip) {
  const int row_count = wrap_rows ? rows + 1 : rows;
  for (int i = 0; i < row_count - (wrap_rows ? 1 : 0); ++i) {
    const int i1 = wrap_rows ? (i + 1) % rows : i + 1;
    for (int j = 0; j < cols; ++j) {
      const int j1 = (j + 1) % cols;
      const uint32_t a = base + i * cols + j, b = base + i * cols + j1;
      const uint32_t c = base + i1 * cols + j1, d = base + i1 * cols + j;
      if (flip) {
        m.faces.push_back({a, c, b});
        m.faces.push_back({a, d, c});
      } else {
        m.faces.push_back({a, b, c});
        m.faces.push_back({a, c, d});
      }
    }
  }
}

}  // namespace

TriMesh makeIcoSphere(float r, int level) {
  const float t = (1.0f + std::sqrt(5.0f)) * 0.5f;
  TriMesh m;
  m.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
             {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (auto& p : m.positions) p = glm::normalize(p);
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      const uint32_t idx = static_cast<uint32_t>(m.positions.size());
      m.positions.push_back(glm::normalize(m.positions[a] + m.positions[b]));
      mid.emplace(key, idx);
      return idx;
    };
    std::vector<std::array<uint32_t, 3>> faces;
    faces.reserve(m.faces.size() * 4);
    for (const auto& f : m.faces) {
      const uint32_t a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      faces.push_back({f[0], a, c});
      faces.push_back({f[1], b, a});
      faces.push_back({f[2], c, b});
      faces.push_back({a, b, c});
    }
    m.faces = std::move(faces);
  }
  for (auto& p : m.positions) p *= r;
  return m;
}

TriMesh makeUvSphere(float r, int slices, int stacks) {
  TriMesh m;
  m.positions.push_back({0, r, 0});
  for (int i = 1; i < stacks; ++i) {
    const float theta = kPi * static_cast<float>(i) / static_cast<float>(stacks);
    for (int j = 0; j < slices; ++j) {
      const float phi = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(slices);
      m.positions.push_back(
          {r * std::sin(theta) * std::sin(phi), r * std::cos(theta), r * std::sin(theta) * std::cos(phi)});
    }
  }
  const uint32_t south = static_cast<uint32_t>(m.positions.size());
  m.positions.push_back({0, -r, 0});
  for (int j = 0; j < slices; ++j) {
    const uint32_t j1 = (j + 1) % slices;
    m.faces.push_back({0, 1 + static_cast<uint32_t>(j), 1 + j1});
  }
  addWrappedQuads(m, 1, stacks - 2, slices, false, true);
  const uint32_t last = 1 + static_cast<uint32_t>((stacks - 2) * slices);
  for (int j = 0; j < slices; ++j) {
    const uint32_t j1 = (j + 1) % slices;
    m.faces.push_back({south, last + j1, last + static_cast<uint32_t>(j)});
  }
  return m;
}

TriMesh makeTorus(float R, float r, int major, int minor) {
  TriMesh m;
  for (int i = 0; i < major; ++i) {
    const float u = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(major);
    for (int j = 0; j < minor; ++j) {
      const float v = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(minor);
      const float w = R + r * std::cos(v);
      m.positions.push_back({w * std::cos(u), r * std::sin(v), -w * std::sin(u)});
    }
  }
  addWrappedQuads(m, 0, major, minor, true, true);
  return m;
}

TriMesh makeCylinder(float r, float h, int slices, int stacks) {
  TriMesh m;
  for (int i = 0; i <= stacks; ++i) {
    const float y = -0.5f * h + h * static_cast<float>(i) / static_cast<float>(stacks);
    for (int j = 0; j < slices; ++j) {
      const float phi = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(slices);
      m.positions.push_back({r * std::sin(phi), y, r * std::cos(phi)});
    }
  }
  addWrappedQuads(m, 0, stacks, slices, false, false);
  return m;
}

TriMesh makeEllipsoid(float a, float b, float c, int level) {
  TriMesh m = makeIcoSphere(1.0f, level);
  for (auto& p : m.positions) p *= glm::vec3(a, b, c);
  return m;
}

TriMesh makeGrid(float size, int n) {
  TriMesh m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      m.positions.push_back({size * (static_cast<float>(j) / n - 0.5f), 0.0f,
                             size * (0.5f - static_cast<float>(i) / n)});
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const uint32_t a = i * (n + 1) + j, b = a + 1, c = a + (n + 1) + 1, d = a + (n + 1);
      m.faces.push_back({a, b, c});
      m.faces.push_back({a, c, d});
    }
  return m;
}

TriMesh makeTerrain(float size, int n) {
  TriMesh m = makeGrid(size, n);
  // Three octaves of crossed sinusoids at unrelated frequencies and phases: hills, ridges
  // across them and small bumps, so contours and suggestive contours appear at every depth.
  const float w = 2.0f * kPi / size;
  for (glm::vec3& p : m.positions) {
    const float x = p.x * w, z = p.z * w;
    p.y = size * (0.06f * std::sin(1.3f * x + 0.4f) * std::cos(0.9f * z) +
                  0.03f * std::sin(3.1f * x + 2.3f * z + 1.1f) +
                  0.015f * std::sin(6.7f * x + 0.7f) * std::sin(7.3f * z + 2.9f) +
                  0.005f * std::cos(13.9f * x - 12.1f * z + 0.3f));
  }
  return m;
}

TriMesh makeTorusKnot(int p, int q, float R, float tube, int segments, int sides, float bumps) {
  auto curve = [&](float s) {
    const float r = R * (0.5f + 0.25f * std::cos(q * s));
    return glm::vec3(r * std::cos(p * s), 0.35f * R * std::sin(q * s), r * std::sin(p * s));
  };
  TriMesh m;
  const float ds = 1e-3f;
  for (int i = 0; i < segments; ++i) {
    const float s = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(segments);
    const glm::vec3 c = curve(s);
    const glm::vec3 t = glm::normalize(curve(s + ds) - curve(s - ds));
    // Frame: project a fixed-ish reference onto the normal plane (smooth for this knot).
    glm::vec3 n = glm::normalize(c - glm::dot(c, t) * t);
    glm::vec3 b = glm::normalize(glm::cross(t, n));
    n = glm::cross(b, t);
    for (int j = 0; j < sides; ++j) {
      const float a = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(sides);
      const float bump = 1.0f + bumps * std::sin(3.0f * a + 7.0f * s) * std::sin(11.0f * s);
      const float rr = tube * bump;
      m.positions.push_back(c + rr * (std::cos(a) * n + std::sin(a) * b));
    }
  }
  // Rows along the knot, columns around the tube; orientation chosen so normals point out.
  for (int i = 0; i < segments; ++i) {
    const int i1 = (i + 1) % segments;
    for (int j = 0; j < sides; ++j) {
      const int j1 = (j + 1) % sides;
      const uint32_t a = i * sides + j, b = i * sides + j1, c = i1 * sides + j1, d = i1 * sides + j;
      m.faces.push_back({a, b, c});
      m.faces.push_back({a, c, d});
    }
  }
  return m;
}

}  // namespace lodline

namespace lodline {

TriMesh makeRoundedBox(glm::vec3 half, float r, int arc_segments, int flat_segments) {
  TriMesh m;
  r = std::clamp(r, 0.0f, std::min({half.x, half.y, half.z}));
  flat_segments = std::max(flat_segments, 1);
  const int arc_half = r > 0.0f ? std::max(arc_segments / 2, 1) : 0;
  // Per axis: coordinates of the grid on the outer cube; those beyond the inner box
  // (|q| > h − r) map onto the arcs at angles spaced evenly (tan spacing), ±h exactly.
  std::array<std::vector<float>, 3> coords;
  for (int a = 0; a < 3; ++a) {
    const float h = half[a], inner = h - r;
    std::vector<float>& c = coords[a];
    c.push_back(-h);
    for (int k = arc_half - 1; k >= 1; --k)
      c.push_back(-inner - r * std::tan(0.25f * kPi * static_cast<float>(k) / arc_half));
    if (arc_half > 0) c.push_back(-inner);
    for (int k = 1; k < flat_segments; ++k)
      c.push_back(-inner + 2.0f * inner * static_cast<float>(k) / flat_segments);
    if (arc_half > 0) c.push_back(inner);
    for (int k = 1; k <= arc_half - 1; ++k)
      c.push_back(inner + r * std::tan(0.25f * kPi * static_cast<float>(k) / arc_half));
    c.push_back(h);
    // With r = 0 or a thin box, ±inner may coincide with neighbours: drop repeats.
    c.erase(std::unique(c.begin(), c.end()), c.end());
  }
  std::map<std::array<float, 3>, uint32_t> index;
  auto vertex = [&](glm::vec3 q) -> uint32_t {
    const glm::vec3 inner = half - glm::vec3(r);
    glm::vec3 c;
    for (int k = 0; k < 3; ++k) c[k] = std::clamp(q[k], -inner[k], inner[k]);
    const glm::vec3 d = q - c;
    const float len = glm::length(d);
    const glm::vec3 p = (r > 0.0f && len > 0.0f) ? c + d * (r / len) : q;
    const std::array<float, 3> key{p.x, p.y, p.z};
    auto [it, inserted] = index.emplace(key, static_cast<uint32_t>(m.positions.size()));
    if (inserted) m.positions.push_back(p);
    return it->second;
  };
  for (int a = 0; a < 3; ++a)
    for (int sign = -1; sign <= 1; sign += 2) {
      // Grid axes b, c with (b × c) = outward normal.
      int b = (a + 1) % 3, c = (a + 2) % 3;
      if (sign < 0) std::swap(b, c);
      const auto& cb = coords[b];
      const auto& cc = coords[c];
      const int nb = static_cast<int>(cb.size()), nc = static_cast<int>(cc.size());
      std::vector<uint32_t> ids(static_cast<size_t>(nb) * nc);
      for (int i = 0; i < nb; ++i)
        for (int j = 0; j < nc; ++j) {
          glm::vec3 q;
          q[a] = static_cast<float>(sign) * half[a];
          q[b] = cb[i];
          q[c] = cc[j];
          ids[static_cast<size_t>(i) * nc + j] = vertex(q);
        }
      for (int i = 0; i + 1 < nb; ++i)
        for (int j = 0; j + 1 < nc; ++j) {
          const uint32_t v00 = ids[static_cast<size_t>(i) * nc + j];
          const uint32_t v10 = ids[static_cast<size_t>(i + 1) * nc + j];
          const uint32_t v11 = ids[static_cast<size_t>(i + 1) * nc + j + 1];
          const uint32_t v01 = ids[static_cast<size_t>(i) * nc + j + 1];
          m.faces.push_back({v00, v10, v11});
          m.faces.push_back({v00, v11, v01});
        }
    }
  return m;
}

}  // namespace lodline
