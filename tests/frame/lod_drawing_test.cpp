// LodDrawing keeps the shape stage, the crease mask and the drawn faces in step with the
// adaptive mesh incrementally (only what a frame's change list names); after every frame
// all of it must equal what a from-scratch computation on the current mesh gives (the shape
// stage away from morphing vertices whose small moves wait, and everywhere once they stop).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <memory>

#include "core/mesh_order.h"
#include "frame/lod_drawing.h"
#include "io/generate.h"
#include "lines/view_quantities.h"
#include "shape/shape_test_util.h"
#include "test_util.h"

namespace lodline {
namespace {

// The vertices within `rings` rings of those whose small moves wait in `shape` (their own
// quantities and those that read their positions may lag: ShapeParams::move_tolerance).
std::vector<uint8_t> nearWaiting(const ShapeCache& shape, const TriMesh& mesh, int rings) {
  std::vector<uint8_t> near(mesh.vertexCount(), 0);
  std::vector<uint32_t> frontier(shape.waitingVertices().begin(), shape.waitingVertices().end()), next;
  for (uint32_t v : frontier) near[v] = 1;
  const MeshAdjacency& adj = shape.adjacency();
  for (int r = 0; r < rings; ++r) {
    next.clear();
    for (uint32_t v : frontier)
      for (uint32_t i = adj.vertex_face_begin[v]; i < adj.vertex_face_end[v]; ++i)
        for (uint32_t c : mesh.faces[adj.vertex_faces[i]])
          if (!near[c]) {
            near[c] = 1;
            next.push_back(c);
          }
    frontier.swap(next);
  }
  return near;
}

// Equal bits at every vertex not marked in `skip`.
template <class T>
bool sameBitsExcept(std::span<const T> a, std::span<const T> b, const std::vector<uint8_t>& skip) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (!skip[i] && std::memcmp(&a[i], &b[i], sizeof(T)) != 0) return false;
  return true;
}

TEST(LodDrawing, IncrementalStateEqualsAFreshComputeEveryFrame) {
  // A sharp box made of many small faces: crease vertices along its 12 edges.
  const TriMesh mesh = makeRoundedBox({1.0f, 0.7f, 0.5f}, 0.0f, 2, 14);
  auto pm = buildProgressiveMesh(mesh);
  ASSERT_TRUE(pm.ok()) << pm.error().message;
  LodDrawing lod(mesh, std::make_shared<const ProgressiveMesh>(std::move(pm.value())));
  std::array<bool, kLineKindCount> enabled{};
  enabled.fill(true);
  DetailParams detail;
  detail.target_area = 24.0f;
  auto camera_at = [&](int k) {  // orbit while zooming in from 8 to 2 radii and out again
    const float phase = static_cast<float>(k) / 89.0f;
    const float dist = 2.0f + 6.0f * std::abs(2.0f * phase - 1.0f);
    return orbitCamera(lod.bounds(), {25.0f + 2.0f * k, 25.0f, dist}, 35.0f, 16.0f / 9.0f);
  };
  ASSERT_TRUE(lod.converge(camera_at(0), 640, 360, detail, 1.0f / 30.0f, 300, enabled).ok());
  {  // A still is drawn at rest: no small move left waiting, the shape that of a fresh compute.
    ASSERT_TRUE(lod.drawing().shape().waitingVertices().empty());
    ShapeCache fresh(lod.drawing().shape().params());
    fresh.compute(lod.drawing().mesh());
    ASSERT_TRUE(test::sameBits(lod.drawing().shape().normals(), fresh.normals()));
    ASSERT_TRUE(test::sameBits(lod.drawing().shape().k1(), fresh.k1()));
  }
  const auto full_creases = lod.drawing().fullDetailCreaseVertices();
  int changed_frames = 0, crease_slots = 0, valid_tensors = 0, waiting_frames = 0;
  size_t compared = 0, vertices = 0;
  // An orbit, then frames at its last view until every morph has ended and every waiting
  // vertex has been recomputed: from then on, no vertex is left out of the comparison.
  int still_frames = 0;
  for (int k = 0; k < 90 + still_frames; ++k) {
    ASSERT_TRUE(lod.frame(camera_at(std::min(k, 89)), 640, 360, detail, 1.0f / 30.0f, enabled).ok());
    const bool at_rest = k >= 89 && lod.lod()->stats().morphing == 0 &&
                         lod.lod()->stats().pending_collapses == 0 &&
                         lod.drawing().shape().waitingVertices().empty();
    if (k >= 89 && !at_rest && still_frames < 120) ++still_frames;
    const AdaptiveMesh& am = *lod.lod();
    ASSERT_EQ(am.checkInvariants(), "") << "frame " << k;
    changed_frames += am.stats().splits + am.stats().collapses > 0;
    // Drawn faces: exactly the active faces.
    const TriMesh& drawn = lod.drawing().mesh();
    std::vector<std::array<uint32_t, 3>> faces;
    am.exportFaces(faces);
    ASSERT_EQ(drawn.faces.size(), am.activeFaceCount());
    ASSERT_TRUE(drawn.faces == faces) << "frame " << k;
    // Crease mask: per used slot, whether its vertex lies on a full-detail crease.
    const auto mask = lod.drawing().creaseMask();
    const auto nodes = am.slotVertices();
    ASSERT_GE(mask.size(), nodes.size());
    for (size_t s = 0; s < nodes.size(); ++s) {
      if (nodes[s] == kPmNone) continue;
      const uint8_t expected = full_creases[am.pm().origin[nodes[s]]];
      ASSERT_EQ(mask[s], expected) << "frame " << k << ", slot " << s;
      crease_slots += expected;
    }
    // Shape quantities: bit for bit those of a fresh compute on the drawn mesh, except within
    // three rings (what derivative tensors read) of a morphing vertex whose small moves wait.
    const ShapeCache& inc = lod.drawing().shape();
    ASSERT_GT(inc.params().move_tolerance, 0.0f);
    ShapeCache fresh(inc.params());
    fresh.compute(drawn);
    const std::vector<uint8_t> skip = nearWaiting(inc, drawn, 3);
    waiting_frames += !inc.waitingVertices().empty();
    vertices += skip.size();
    compared += static_cast<size_t>(std::count(skip.begin(), skip.end(), uint8_t{0}));
    if (at_rest) {
      ASSERT_EQ(std::count(skip.begin(), skip.end(), uint8_t{1}), 0);
    }
    ASSERT_TRUE(sameBitsExcept(inc.normals(), fresh.normals(), skip)) << "frame " << k;
    ASSERT_TRUE(sameBitsExcept(inc.k1(), fresh.k1(), skip)) << "frame " << k;
    ASSERT_TRUE(sameBitsExcept(inc.k2(), fresh.k2(), skip)) << "frame " << k;
    ASSERT_TRUE(sameBitsExcept(inc.pdir1(), fresh.pdir1(), skip)) << "frame " << k;
    // Derivative tensors are lazy here: current wherever the frame asked for them (next to
    // every kr zero crossing), and those equal the eager ones bit for bit.
    ASSERT_TRUE(inc.params().lazy_derivatives);
    ShapeParams eager_params = inc.params();
    eager_params.lazy_derivatives = false;
    ShapeCache eager(eager_params);
    eager.compute(drawn);
    for (uint32_t v = 0; v < drawn.vertexCount(); ++v) {
      if (!inc.derivativeValid(v) || skip[v]) continue;
      ++valid_tensors;
      ASSERT_EQ(std::memcmp(&inc.dcurv()[v], &eager.dcurv()[v], sizeof(glm::vec4)), 0)
          << "frame " << k << ", vertex " << v;
    }
    // ... and every corner of a face crossed by the kr zero set with a corner facing the viewer
    // (past the gate: the suggestive contour is cut where n·v crosses it) has one.
    ViewQuantities vq;
    computeViewQuantities(inc.fields(drawn), ViewSpec::fromCamera(camera_at(k)), 0.0f, vq);
    const float gate = lod.drawing().params().suggestive_min_ndotv;
    for (const auto& t : drawn.faces) {
      const bool s0 = vq.kr[t[0]] < 0.0f, s1 = vq.kr[t[1]] < 0.0f, s2 = vq.kr[t[2]] < 0.0f;
      if ((s0 == s1 && s1 == s2) || (vq.ndotv[t[0]] < gate && vq.ndotv[t[1]] < gate && vq.ndotv[t[2]] < gate))
        continue;
      for (uint32_t v : t) ASSERT_TRUE(inc.derivativeValid(v)) << "frame " << k << ", vertex " << v;
    }
  }
  EXPECT_LT(still_frames, 120);   // it came to rest, and was compared whole at rest
  EXPECT_GT(waiting_frames, 10);  // small moves did wait
  EXPECT_GT(compared, vertices / 2);  // and most vertices were compared all the same
  EXPECT_GT(changed_frames, 30);  // the test did exercise splits and collapses
  EXPECT_GT(crease_slots, 0);     // and crease vertices
  EXPECT_GT(valid_tensors, 0);
}

// A full-detail drawing renumbers a mesh stored in a scattered order (core/mesh_order.h), and
// its feature size and median edge length sample the same vertices and faces as in the stored
// order (as detail control's do), so they do not depend on the numbering.
TEST(LodDrawing, FullDetailIsDrawnInLocalityOrderWithTheStoredSamples) {
  const TriMesh stored = test::shuffledMesh(makeTorusKnot(2, 3, 1.0f, 0.2f, 300, 24, 0.18f), 5);
  LodDrawing full(stored);
  const LineDrawing as_stored(stored);
  EXPECT_LT(medianCornerSpread(full.drawing().mesh()), medianCornerSpread(stored) / 20);
  EXPECT_EQ(full.drawing().mesh().faceCount(), stored.faceCount());
  EXPECT_NEAR(full.drawing().featureSize(), as_stored.featureSize(), 1e-5f * as_stored.featureSize());
  std::vector<float> scratch;
  EXPECT_EQ(full.medianEdgeLength(scratch), medianEdgeLength(stored, scratch));
}

// At a fixed view the adapted mesh settles: converging ends with a step that changes
// nothing, and further frames change nothing either. On this knot and view a visible
// vertex's split used to force back-facing neighbours' splits first; those coarsened again
// the next frame and the vertex wanted its split again, a cycle that never ended
// (docs/temporal-coherence.md, "Limit cycles at a fixed view").
TEST(LodDrawing, ConvergedDetailStaysPutAtAFixedView) {
  const TriMesh mesh = makeTorusKnot(2, 3, 1.0f, 0.16f, 1200, 80, 0.18f);
  auto pm = buildProgressiveMesh(mesh);
  ASSERT_TRUE(pm.ok()) << pm.error().message;
  LodDrawing lod(mesh, std::make_shared<const ProgressiveMesh>(std::move(pm.value())));
  std::array<bool, kLineKindCount> enabled{};
  enabled[static_cast<int>(LineKind::kContour)] = true;
  DetailParams detail;
  detail.target_area = 32.0f;
  const Camera cam = orbitCamera(lod.bounds(), {200.0f, -30.0f, 2.5f}, 35.0f, 16.0f / 9.0f);
  auto steps = lod.converge(cam, 1280, 720, detail, 1.0f, 60, enabled);
  ASSERT_TRUE(steps.ok());
  const LodStats& last = lod.lod()->stats();
  EXPECT_EQ(last.splits + last.collapses, 0u) << "converging stopped with changes still going on";
  EXPECT_LT(*steps, 10);
  // Frames at the same view: vertices whose split was refused are retried 8 frames later
  // (their neighbourhood may have changed), and those retries may split; after them nothing
  // may change.
  uint32_t late_changes = 0;
  for (int k = 0; k < 40; ++k) {
    ASSERT_TRUE(lod.frame(cam, 1280, 720, detail, 1.0f / 30.0f, enabled).ok());
    const LodStats& st = lod.lod()->stats();
    if (k >= 20) late_changes += st.splits + st.collapses;
  }
  EXPECT_EQ(late_changes, 0u);
}

// The strokes' whole length on screen, as LineDrawing::dropShortStrokes measures it.
std::vector<float> strokeLengthsPx(const StrokeSet& strokes, const Camera& cam, int w, int h) {
  const PixelProjector proj(cam, w, h);
  std::vector<float> out;
  measureStrokeLengths(
      strokes,
      [&](glm::vec3 p) {
        glm::vec2 px(0.0f);
        float z = 0.0f;
        proj.project(p, px, z);
        return px;
      },
      out);
  return out;
}

// Under detail control, suggestive contours shorter on screen than min_suggestive_length·√T
// are left out, and nothing else: the other strokes and the longer suggestive ones stay.
TEST(LodDrawing, SuggestiveContoursBelowTheScaleAreLeftOut) {
  const TriMesh mesh = makeTorusKnot(2, 3, 1.0f, 0.2f, 900, 60, 0.25f);
  auto pm = buildProgressiveMesh(mesh);
  ASSERT_TRUE(pm.ok()) << pm.error().message;
  const auto shared = std::make_shared<const ProgressiveMesh>(std::move(pm.value()));
  std::array<bool, kLineKindCount> enabled{};
  enabled[static_cast<int>(LineKind::kContour)] = true;
  enabled[static_cast<int>(LineKind::kSuggestive)] = true;
  const int w = 1280, h = 720;
  DetailParams detail;
  detail.target_area = 16.0f;
  const float min_px = detail.min_suggestive_length * 4.0f;  // √16
  ASSERT_GT(min_px, 0.0f) << "the default leaves every suggestive contour in";
  LodDrawing all(mesh, shared), kept(mesh, shared);
  const Camera cam = orbitCamera(all.bounds(), {30.0f, 20.0f, 1.6f}, 35.0f, 16.0f / 9.0f);
  DetailParams every = detail;
  every.min_suggestive_length = 0.0f;
  ASSERT_TRUE(all.converge(cam, w, h, every, 1.0f, 60, enabled).ok());
  ASSERT_TRUE(kept.converge(cam, w, h, detail, 1.0f, 60, enabled).ok());
  ASSERT_EQ(all.lod()->activeFaceCount(), kept.lod()->activeFaceCount());

  const StrokeSet& a = all.drawing().strokes();
  const StrokeSet& k = kept.drawing().strokes();
  const std::vector<float> la = strokeLengthsPx(a, cam, w, h), lk = strokeLengthsPx(k, cam, w, h);
  size_t short_suggestive = 0, long_suggestive = 0, others = 0;
  for (size_t s = 0; s < a.strokeCount(); ++s) {
    if (a.kinds[s] != LineKind::kSuggestive) ++others;
    else if (la[s] < min_px) ++short_suggestive;
    else ++long_suggestive;
  }
  ASSERT_GT(short_suggestive, 0u) << "the view must have suggestive contours below the scale";
  ASSERT_GT(long_suggestive, 0u);
  size_t k_suggestive = 0, k_others = 0;
  for (size_t s = 0; s < k.strokeCount(); ++s) {
    if (k.kinds[s] == LineKind::kSuggestive) {
      ++k_suggestive;
      EXPECT_GE(lk[s], min_px) << "stroke " << s;
    } else {
      ++k_others;
    }
  }
  EXPECT_EQ(k_suggestive, long_suggestive);
  EXPECT_EQ(k_others, others);
  EXPECT_EQ(k.offsets.size(), k.strokeCount() + 1);
  EXPECT_EQ(k.points.size(), k.offsets.back());
  EXPECT_EQ(k.alpha.size(), k.points.size());

  // Full detail draws them all, whatever the setting.
  LodDrawing full_every(mesh), full_long(mesh);
  DetailParams longest = detail;
  longest.min_suggestive_length = 8.0f;
  ASSERT_TRUE(full_every.converge(cam, w, h, every, 1.0f, 60, enabled).ok());
  ASSERT_TRUE(full_long.converge(cam, w, h, longest, 1.0f, 60, enabled).ok());
  EXPECT_GT(full_every.drawing().strokes().strokeCount(), 0u);
  EXPECT_EQ(full_long.drawing().strokes().points, full_every.drawing().strokes().points);
}

// Back faces may be culled for closed models at full detail and on progressive-mesh levels,
// never for open models or clustering (whose cells can flip faces).
TEST(LodDrawing, BackFacesHiddenOnlyForClosedModelsWithoutClustering) {
  const TriMesh sphere = makeIcoSphere(1.0f, 3);
  EXPECT_TRUE(LodDrawing(sphere).backFacesHidden());
  auto pm = buildProgressiveMesh(sphere);
  ASSERT_TRUE(pm.ok());
  EXPECT_TRUE(LodDrawing(sphere, std::make_shared<const ProgressiveMesh>(std::move(pm.value()))).backFacesHidden());
  EXPECT_FALSE(LodDrawing(sphere, ClusterParams{}).backFacesHidden());
  EXPECT_FALSE(LodDrawing(makeGrid(2.0f, 16)).backFacesHidden());
}

}  // namespace
}  // namespace lodline
