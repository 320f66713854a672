// The geometric rules by which AdaptiveMesh tells a fold from a coarse face that merely
// points away from its full-detail face (docs/detail-control.md §7-§9). Hoppe 1997 §4 keeps
// the mesh free of fold-overs by refusing operations; a coarse face of a mixed-resolution
// mesh can, however, point more than 90° from its full-detail face without folding anything,
// and refusing those held whole regions coarse.
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace lodline {

/// Whether triangle (a, b, c) faces within 90° of `ref` (strictly); a zero `ref` (no
/// recorded normal) always passes.
inline bool facesAlong(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& ref) {
  if (ref.x == 0.0f && ref.y == 0.0f && ref.z == 0.0f) return true;
  return glm::dot(glm::cross(b - a, c - a), ref) > 0.0f;
}

/// Whether triangle (a, b, c) is turned over against `before` (its normal before an operation,
/// any length): 90° or more from it. A zero `before` (a face of no area) has no normal to turn
/// from, and nothing is turned over.
inline bool turnedOverFrom(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& before) {
  return glm::dot(before, before) > 0.0f && !(glm::dot(glm::cross(b - a, c - a), before) > 0.0f);
}

/// Whether a face that a vertex split creates, (a, b, c), is turned over against the two
/// faces it opens between, whose normals before the split are `side0` and `side1` (any
/// length): its normal is 90° or more from the sum of their unit normals. Where the sides
/// point almost opposite ways (a knife edge: unit normals within about 0.6° of opposite), or
/// have no area, their sum has no reliable direction and nothing is turned over.
inline bool turnedOverBetween(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& side0,
                              const glm::vec3& side1) {
  auto unit = [](const glm::vec3& n) {
    const float len = glm::length(n);
    return len > 0.0f ? n / len : glm::vec3(0.0f);
  };
  const glm::vec3 sum = unit(side0) + unit(side1);
  return glm::dot(sum, sum) >= 1e-4f && turnedOverFrom(a, b, c, sum);
}

}  // namespace lodline
