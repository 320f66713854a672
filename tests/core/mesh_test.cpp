#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "core/mesh.h"
#include "io/generate.h"

namespace lodline {
namespace {

TEST(Bounds, SphereRadius) {
  const TriMesh m = makeIcoSphere(2.0f, 2);
  const Bounds b = computeBounds(m.positions);
  EXPECT_NEAR(b.radius, 2.0f, 1e-4f);
  EXPECT_NEAR(glm::length(b.center), 0.0f, 1e-5f);
}

}  // namespace
}  // namespace lodline
