// LineDrawing with lazily evaluated derivative tensors (what level of detail uses) draws
// exactly the lines of the eager evaluation when temporal smoothing is off, frame after
// frame while the mesh deforms.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "core/mesh_order.h"
#include "frame/line_drawing.h"
#include "io/generate.h"
#include "test_util.h"

namespace lodline {
namespace {

TEST(LineDrawing, LazyDerivativesDrawTheSameLines) {
  const TriMesh mesh = makeTorusKnot(2, 3, 1.0f, 0.2f, 300, 24, 0.18f);
  ShapeParams eager_params, lazy_params;
  lazy_params.lazy_derivatives = true;
  LineDrawing eager(mesh, {}, eager_params), lazy(mesh, {}, lazy_params);
  std::array<bool, kLineKindCount> enabled{};
  enabled.fill(true);
  TriMesh moving = mesh;
  std::vector<uint32_t> changed;
  size_t suggestive = 0;
  for (int k = 0; k < 12; ++k) {
    // A travelling bump moves a band of vertices each frame.
    changed.clear();
    for (uint32_t v = 0; v < moving.vertexCount(); ++v) {
      if ((v / 24) % 300 < static_cast<uint32_t>(20 * k) || (v / 24) % 300 >= static_cast<uint32_t>(20 * k + 20)) continue;
      moving.positions[v] = mesh.positions[v] * (1.0f + 0.02f * std::sin(0.5f * static_cast<float>(v + k)));
      changed.push_back(v);
    }
    eager.updateMesh(moving.positions, moving.faces, changed);
    lazy.updateMesh(moving.positions, moving.faces, changed);
    const Camera cam = orbitCamera(eager.bounds(), {15.0f * k, 25.0f, 0.0f}, 35.0f, 16.0f / 9.0f);
    eager.update(cam, enabled);
    lazy.update(cam, enabled);
    const LineSet& a = eager.segments();
    const LineSet& b = lazy.segments();
    ASSERT_EQ(a.counts, b.counts) << "frame " << k;
    ASSERT_EQ(a.points, b.points) << "frame " << k;
    ASSERT_EQ(a.alpha, b.alpha) << "frame " << k;
    suggestive += a.counts[static_cast<int>(LineKind::kSuggestive)];
    // The lazy cache computed far fewer tensors than there are vertices.
    uint32_t valid = 0;
    for (uint32_t v = 0; v < moving.vertexCount(); ++v) valid += lazy.shape().derivativeValid(v);
    EXPECT_LT(valid, moving.vertexCount()) << "frame " << k;
  }
  EXPECT_GT(suggestive, 100u);  // the comparison covered suggestive contours
}

// The order a full-detail mesh is drawn in (core/mesh_order.h) changes its indices, not its
// lines: per kind the same segments up to the rounding of sums taken in another order (the
// feature size samples the same vertices, through stored_to_drawn).
TEST(LineDrawing, MeshOrderDrawsTheSameLines) {
  const TriMesh mesh = test::shuffledMesh(makeTorusKnot(2, 3, 1.0f, 0.2f, 300, 24, 0.18f), 11);
  TriMesh ordered = mesh;
  std::vector<uint32_t> stored_to_drawn;
  ASSERT_TRUE(orderForLocality(ordered, &stored_to_drawn));
  LineDrawing a(mesh), b(ordered, {}, {}, nullptr, FullMesh::kDrawn, stored_to_drawn);
  // The same vertices sampled: the same feature size up to rounding.
  EXPECT_NEAR(b.featureSize(), a.featureSize(), 1e-5f * a.featureSize());
  std::array<bool, kLineKindCount> enabled{};
  enabled.fill(true);
  auto length = [](const LineSet& s, int kind) {
    double sum = 0.0;
    for (size_t i = 0; i < s.kinds.size(); ++i)
      if (static_cast<int>(s.kinds[i]) == kind) sum += glm::length(s.points[2 * i + 1] - s.points[2 * i]);
    return sum;
  };
  size_t compared = 0;
  for (int k = 0; k < 4; ++k) {
    const Camera cam = orbitCamera(a.bounds(), {35.0f + 40.0f * k, 20.0f, 0.0f}, 35.0f, 16.0f / 9.0f);
    a.update(cam, enabled);
    b.update(cam, enabled);
    for (int kind = 0; kind < kLineKindCount; ++kind) {
      const double na = a.segments().counts[kind], nb = b.segments().counts[kind];
      EXPECT_NEAR(nb, na, std::max(2.0, 0.002 * na)) << "view " << k << ", kind " << kind;
      const double la = length(a.segments(), kind), lb = length(b.segments(), kind);
      EXPECT_NEAR(lb, la, 0.002 * la + 1e-6) << "view " << k << ", kind " << kind;
      compared += a.segments().counts[kind];
    }
  }
  EXPECT_GT(compared, 1000u);
}

TEST(LineDrawing, FittedRidgesAreSmoothedInASequence) {
  const TriMesh mesh = makeTorusKnot(2, 3, 1.0f, 0.2f, 200, 16, 0.18f);
  LineParams params;
  params.ridges = params.valleys = true;
  params.ridge_estimator = RidgeEstimator::kFit;
  std::array<bool, kLineKindCount> enabled{};
  enabled[static_cast<int>(LineKind::kRidge)] = enabled[static_cast<int>(LineKind::kValley)] = true;
  LineDrawing sequence(mesh, params), still(mesh, params);
  const Camera cam = orbitCamera(sequence.bounds(), {30.0f, 25.0f, 0.0f}, 35.0f, 16.0f / 9.0f);
  sequence.update(cam, enabled, 0.5f);  // the first frame of a sequence: nothing to blend yet
  still.update(cam, enabled);
  ASSERT_GT(still.segments().counts[static_cast<int>(LineKind::kRidge)], 50u);
  EXPECT_EQ(sequence.segments().points, still.segments().points);
  // The surface ripples a little: the still follows at once, the sequence blends.
  TriMesh moved = mesh;
  std::vector<uint32_t> changed;
  for (uint32_t v = 0; v < moved.vertexCount(); ++v) {
    moved.positions[v] *= 1.0f + 0.01f * std::sin(0.7f * static_cast<float>(v));
    changed.push_back(v);
  }
  for (LineDrawing* d : {&sequence, &still}) d->updateMesh(moved.positions, moved.faces, changed);
  sequence.update(cam, enabled, 0.5f);
  still.update(cam, enabled);
  EXPECT_NE(sequence.segments().points, still.segments().points);
  // The fitted derivatives themselves carry history (not only the normals they are fitted in).
  EXPECT_TRUE(sequence.smoother().channelOn(TemporalSmoother::kC111));
  EXPECT_TRUE(sequence.smoother().channelOn(TemporalSmoother::kC222));
  EXPECT_FALSE(still.smoother().channelOn(TemporalSmoother::kC111));
}

}  // namespace
}  // namespace lodline
