// Helpers shared by the shape and lines tests: orientation fixes and analytic surfaces.
#pragma once

#include <cmath>
#include <cstring>
#include <functional>
#include <span>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/mesh.h"

namespace lodline::test {

/// True when both arrays hold the same bytes (bit-identical floats, NaNs included).
template <class T>
bool sameBits(std::span<const T> a, std::span<const T> b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size_bytes()) == 0);
}

/// Signed volume enclosed by a closed mesh (> 0 when faces are counter-clockwise seen from
/// outside).
inline double signedVolume(const TriMesh& m) {
  double v = 0.0;
  for (const auto& f : m.faces) {
    const glm::dvec3 a(m.positions[f[0]]), b(m.positions[f[1]]), c(m.positions[f[2]]);
    v += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return v;
}

/// Number of faces whose normal points against `outward(centroid)`.
inline size_t countInwardFaces(const TriMesh& m, const std::function<glm::vec3(glm::vec3)>& outward) {
  size_t n = 0;
  for (const auto& f : m.faces) {
    const glm::vec3 a = m.positions[f[0]], b = m.positions[f[1]], c = m.positions[f[2]];
    if (glm::dot(glm::cross(b - a, c - a), outward((a + b + c) / 3.0f)) < 0.0f) ++n;
  }
  return n;
}

/// Flips every face whose normal points against `outward(centroid)`.
inline void orientFaces(TriMesh& m, const std::function<glm::vec3(glm::vec3)>& outward) {
  for (auto& f : m.faces) {
    const glm::vec3 a = m.positions[f[0]], b = m.positions[f[1]], c = m.positions[f[2]];
    if (glm::dot(glm::cross(b - a, c - a), outward((a + b + c) / 3.0f)) < 0.0f)
      std::swap(f[1], f[2]);
  }
}

/// Outward direction of a sphere centred at the origin.
inline glm::vec3 sphereOutward(glm::vec3 p) { return p; }

/// Torus of io/generate.h: P(u,v) = ((R + r cos v) cos u, r sin v, −(R + r cos v) sin u).
struct AnalyticTorus {
  double R, r;
  /// Outward unit normal at (or nearest to) p.
  glm::dvec3 normal(glm::dvec3 p) const {
    const double rho = std::hypot(p.x, p.z);
    const glm::dvec3 ring(R * p.x / rho, 0.0, R * p.z / rho);
    return glm::normalize(p - ring);
  }
  double tubeAngle(glm::dvec3 p) const {  // v
    const double rho = std::hypot(p.x, p.z);
    return std::atan2(p.y, rho - R);
  }
  double ringAngle(glm::dvec3 p) const { return std::atan2(-p.z, p.x); }  // u
  glm::dvec3 point(double u, double v) const {
    const double w = R + r * std::cos(v);
    return {w * std::cos(u), r * std::sin(v), -w * std::sin(u)};
  }
  /// Unit tangent along the ring (direction of the principal curvature cos v/(R + r cos v)).
  glm::dvec3 ringDir(double u) const { return {-std::sin(u), 0.0, -std::cos(u)}; }
  /// Unit tangent around the tube (principal curvature 1/r).
  glm::dvec3 tubeDir(double u, double v) const {
    return {-std::sin(v) * std::cos(u), std::cos(v), std::sin(v) * std::sin(u)};
  }
  double ringCurvature(double v) const { return std::cos(v) / (R + r * std::cos(v)); }
  double tubeCurvature() const { return 1.0 / r; }
  /// C(e_ring, e_ring, e_tube): the only non-zero component of the derivative tensor.
  double cRingRingTube(double v) const {
    const double w = R + r * std::cos(v);
    return -R * std::sin(v) / (r * w * w);
  }
  /// Radial curvature for the view point `eye` (perspective) at (u, v).
  double radialCurvature(double u, double v, glm::dvec3 eye) const {
    const glm::dvec3 p = point(u, v);
    const glm::dvec3 view = glm::normalize(eye - p);
    const double a = glm::dot(view, ringDir(u)), b = glm::dot(view, tubeDir(u, v));
    return (ringCurvature(v) * a * a + tubeCurvature() * b * b) / (a * a + b * b);
  }
};

/// Torus outward direction for io/generate.h's makeTorus(R, ...).
inline std::function<glm::vec3(glm::vec3)> torusOutward(float R) {
  return [R](glm::vec3 p) {
    const float rho = std::hypot(p.x, p.z);
    return p - glm::vec3(R * p.x / rho, 0.0f, R * p.z / rho);
  };
}

}  // namespace lodline::test
