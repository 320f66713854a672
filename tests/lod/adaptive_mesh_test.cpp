// Selective refinement: exact full refinement/coarsening, validity along random camera paths,
// convergence without oscillation, the image-area band, detail modifiers, geomorphs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <map>
#include <memory>
#include <random>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/mesh_order.h"
#include "lod/adaptive_mesh.h"
#include "lod/fold_rules.h"
#include "pm/pm_file.h"
#include "pm/pm_test_meshes.h"
#include "pm/progressive_mesh.h"
#include "test_util.h"

namespace lodline {
namespace {

constexpr int kW = 1280, kH = 720;

struct Model {
  TriMesh mesh;
  ProgressiveMesh pm;
  Bounds bounds;
};

/// Builds (once per name) the progressive mesh of a named test model.
const Model& model(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Model>> cache;
  auto& slot = cache[name];
  if (slot) return *slot;
  slot = std::make_unique<Model>();
  Model& m = *slot;
  if (name == "sphere") m.mesh = makeIcoSphere(1.0f, 4);
  else if (name == "noisy") { m.mesh = makeIcoSphere(1.0f, 4); test::perturbRadially(m.mesh, 0.02f); }
  else if (name == "fine_sphere") m.mesh = makeIcoSphere(1.0f, 6);
  else if (name == "torus") m.mesh = makeTorus(1.0f, 0.35f, 96, 48);
  else if (name == "fine_torus") m.mesh = makeTorus(1.0f, 0.35f, 320, 128);
  else if (name == "grid") m.mesh = makeGrid(2.0f, 40);
  else if (name == "cylinder") m.mesh = makeCylinder(0.5f, 2.0f, 48, 24);
  else if (name == "knot") m.mesh = makeTorusKnot(2, 3, 1.0f, 0.25f, 256, 24, 0.1f);
  else {
    const auto path = test::dataMesh(name);
    if (path.empty() || !test::readOff(path, m.mesh)) m.mesh = TriMesh{};
  }
  if (m.mesh.faces.empty()) return m;
  auto pm = buildProgressiveMesh(m.mesh);
  EXPECT_TRUE(pm.ok()) << name << ": " << (pm.ok() ? "" : pm.error().message);
  if (pm.ok()) m.pm = std::move(pm).value();
  m.bounds = computeBounds(m.mesh.positions);
  return m;
}

Camera cameraAt(const Bounds& b, float az, float el, float dist_radii) {
  OrbitView v;
  v.azimuth_deg = az;
  v.elevation_deg = el;
  v.distance = dist_radii;
  Camera cam = orbitCamera(b, v, 35.0f, static_cast<float>(kW) / kH);
  cam.near_plane = 0.01f * b.radius;
  cam.far_plane = 100.0f * b.radius;
  return cam;
}

/// One frame (1/30 s) of `lod` seen from `cam`.
::testing::AssertionResult stepTo(AdaptiveMesh& lod, const Camera& cam, const DetailParams& d) {
  if (!lod.setView(cam, kW, kH, d).ok()) return ::testing::AssertionFailure() << "setView failed";
  lod.adapt(1.0f / 30.0f);
  return ::testing::AssertionSuccess();
}

void expectRefinesToInput(const Model& m) {
  AdaptiveMesh lod(m.pm);
  ASSERT_EQ(lod.checkInvariants(), "");
  lod.fullyRefine();
  ASSERT_EQ(lod.checkInvariants(), "");
  TriMesh out;
  std::vector<uint32_t> ids;
  lod.exportCompact(out, ids);
  ASSERT_EQ(out.faceCount(), m.mesh.faceCount());
  std::vector<std::array<uint32_t, 3>> faces = out.faces;
  for (auto& f : faces)
    for (auto& v : f) {
      ASSERT_TRUE(m.pm.isLeaf(ids[v]));
      v = ids[v];
    }
  EXPECT_EQ(test::sortedFaces(faces), test::sortedFaces(m.mesh.faces));
  for (size_t i = 0; i < ids.size(); ++i) EXPECT_EQ(out.positions[i], m.mesh.positions[ids[i]]);

  lod.fullyCoarsen();
  ASSERT_EQ(lod.checkInvariants(), "");
  std::vector<uint32_t> got(lod.activeFaceIds().begin(), lod.activeFaceIds().end());
  std::vector<uint32_t> want = m.pm.base_faces;
  std::sort(got.begin(), got.end());
  std::sort(want.begin(), want.end());
  EXPECT_EQ(got, want);
  EXPECT_EQ(lod.activeVertexCount(), m.pm.roots.size());
  lod.exportCompact(out, ids);
  std::vector<std::array<uint32_t, 3>> base = out.faces;
  for (auto& f : base)
    for (auto& v : f) v = ids[v];
  EXPECT_EQ(test::sortedFaces(base), test::sortedFaces(m.pm.base_corners));
  // And back up again.
  lod.fullyRefine();
  EXPECT_EQ(lod.activeFaceCount(), m.mesh.faceCount());
  EXPECT_EQ(lod.checkInvariants(), "");
}

TEST(AdaptiveMesh, FullyRefineReproducesInputAndCoarsenGivesBase) {
  for (const char* name : {"sphere", "noisy", "torus", "grid", "cylinder", "knot"}) {
    SCOPED_TRACE(name);
    expectRefinesToInput(model(name));
  }
}

TEST(AdaptiveMesh, FullyRefineCgalMeshes) {
  bool any = false;
  for (const char* name : {"bunny00.off", "armadillo.off"}) {
    const Model& m = model(name);
    if (m.mesh.faces.empty()) continue;
    any = true;
    SCOPED_TRACE(name);
    expectRefinesToInput(m);
  }
  if (!any) GTEST_SKIP() << "CGAL meshes not found";
}

TEST(AdaptiveMesh, NonManifoldInputRefinesExactly) {
  Model m;
  TriMesh a = makeIcoSphere(1.0f, 2);
  m.mesh = a;
  const uint32_t off = static_cast<uint32_t>(a.positions.size());
  for (auto p : a.positions) m.mesh.positions.push_back(p + glm::vec3(2.0f, 0.0f, 0.0f));
  for (auto f : a.faces) {
    for (auto& v : f) v = (v == 0 ? 0u : v + off);
    m.mesh.faces.push_back(f);
  }
  m.mesh.positions.push_back({9.0f, 9.0f, 9.0f});  // isolated
  auto pm = buildProgressiveMesh(m.mesh);
  ASSERT_TRUE(pm.ok());
  m.pm = std::move(pm).value();
  expectRefinesToInput(m);
  AdaptiveMesh lod(m.pm);
  m.bounds = computeBounds(m.mesh.positions);
  DetailParams d;
  for (int i = 0; i < 100; ++i) {
    ASSERT_TRUE(stepTo(lod, cameraAt(m.bounds, 10.0f * i, 10.0f, 1.0f + 0.05f * i), d));
  }
  EXPECT_EQ(lod.checkInvariants(), "");
}

/// Random camera path: orbit, zoom, jumps, T changes, ortho phases, geomorphs on/off.
void randomPath(const Model& m, int frames, uint32_t seed, int check_every) {
  AdaptiveMesh lod(m.pm);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  float az = 0.0f, el = 10.0f, dist = 3.0f;
  DetailParams d;
  d.target_area = 8.0f;
  for (int frame = 0; frame < frames; ++frame) {
    az += 3.0f;
    el = 40.0f * std::sin(0.01f * frame);
    dist *= std::exp(0.05f * (u01(rng) - 0.5f));
    if (u01(rng) < 0.02f) dist = 0.6f + 6.0f * u01(rng);  // jump (zoom in/out at once)
    if (u01(rng) < 0.02f) az += 180.0f * u01(rng);
    if (u01(rng) < 0.01f) d.target_area = 2.0f + 60.0f * u01(rng);
    if (u01(rng) < 0.01f) d.geomorphs = !d.geomorphs;
    dist = std::clamp(dist, 0.4f, 10.0f);
    Camera cam = cameraAt(m.bounds, az, el, dist);
    if ((frame / 300) % 4 == 3) {
      cam.orthographic = true;
      cam.ortho_height = dist * m.bounds.radius;
    }
    ASSERT_TRUE(lod.setView(cam, kW, kH, d).ok());
    lod.adapt(u01(rng) < 0.05f ? 0.5f : 1.0f / 30.0f);
    if (frame % check_every == 0 || frame == frames - 1) {
      const std::string err = lod.checkInvariants();
      ASSERT_EQ(err, "") << "frame " << frame;
    }
    // The change list only names valid slots, each once.
    const auto& ch = lod.changes();
    std::vector<uint32_t> dirty = ch.dirty;
    std::sort(dirty.begin(), dirty.end());
    ASSERT_TRUE(std::adjacent_find(dirty.begin(), dirty.end()) == dirty.end());
    for (uint32_t s : dirty) ASSERT_LT(s, lod.slotCount());
  }
}

TEST(AdaptiveMesh, RandomCameraPathsKeepTheMeshValid) {
  randomPath(model("noisy"), 3000, 1, 7);
  randomPath(model("torus"), 2000, 2, 11);
  randomPath(model("grid"), 1000, 3, 5);
  randomPath(model("knot"), 1500, 4, 13);
}

TEST(AdaptiveMesh, RandomCameraPathsCgal) {
  const Model& m = model("bunny00.off");
  if (m.mesh.faces.empty()) GTEST_SKIP() << "bunny00.off not found";
  randomPath(m, 1500, 5, 50);
}

TEST(AdaptiveMesh, StaticCameraConvergesWithoutOscillation) {
  for (const char* name : {"fine_sphere", "torus", "knot"}) {
    SCOPED_TRACE(name);
    const Model& m = model(name);
    AdaptiveMesh lod(m.pm);
    DetailParams d;
    d.geomorphs = false;
    ASSERT_TRUE(lod.setView(cameraAt(m.bounds, 30.0f, 20.0f, 2.5f), kW, kH, d).ok());
    // Converged: 20 frames in a row without a split or collapse (refused splits are retried
    // every few frames, and a retry must not change the mesh).
    int frame = 0, quiet = 0;
    for (; frame < 400 && quiet < 20; ++frame) {
      lod.adapt(1.0f / 30);
      quiet = (lod.stats().splits == 0 && lod.stats().collapses == 0) ? quiet + 1 : 0;
    }
    EXPECT_LT(frame, 400) << "did not converge";
    EXPECT_GT(lod.activeFaceCount(), m.pm.base_faces.size());
    const uint32_t faces = lod.activeFaceCount();
    for (int i = 0; i < 100; ++i) {
      lod.adapt(1.0f / 30);
      ASSERT_EQ(lod.stats().splits + lod.stats().collapses, 0u) << "oscillation at frame " << i;
    }
    EXPECT_EQ(lod.activeFaceCount(), faces);
    EXPECT_EQ(lod.checkInvariants(), "");
  }
}

float convergedBand(const Model& m, float dist, float target, uint32_t* visible = nullptr) {
  AdaptiveMesh lod(m.pm);
  DetailParams d;
  d.geomorphs = false;
  d.target_area = target;
  EXPECT_TRUE(lod.setView(cameraAt(m.bounds, 30.0f, 20.0f, dist), kW, kH, d).ok());
  for (int i = 0; i < 300; ++i) {
    lod.adapt(1.0f / 30);
    if (lod.stats().splits == 0 && lod.stats().collapses == 0) break;
  }
  float band = 0.0f;
  uint32_t vis = 0;
  lod.measureBand(band, vis);
  if (visible) *visible = vis;
  return band;
}

TEST(AdaptiveMesh, BandFractionAfterConvergence) {
  for (const char* name : {"fine_sphere", "fine_torus"}) {
    SCOPED_TRACE(name);
    uint32_t visible = 0;
    // At 6 radii the full-detail faces are ~8 px² (finer than T), so the band is reachable.
    const float band = convergedBand(model(name), 6.0f, 16.0f, &visible);
    EXPECT_GE(band, 0.9f) << "visible faces " << visible;
    EXPECT_GT(visible, 1000u);
  }
}

TEST(AdaptiveMesh, VisibleFacesTrackImageAreaOverT) {
  const Model& m = model("fine_sphere");
  uint32_t near_vis = 0, far_vis = 0;
  convergedBand(m, 6.0f, 16.0f, &near_vis);
  convergedBand(m, 12.0f, 16.0f, &far_vis);
  // Twice the distance: a quarter of the image area, about a quarter of the faces.
  const float ratio = static_cast<float>(near_vis) / static_cast<float>(far_vis);
  EXPECT_GT(ratio, 2.5f);
  EXPECT_LT(ratio, 6.0f);
}

uint32_t convergedFaces(const Model& m, const DetailParams& d0, const Camera& cam) {
  AdaptiveMesh lod(m.pm);
  DetailParams d = d0;
  d.geomorphs = false;
  EXPECT_TRUE(lod.setView(cam, kW, kH, d).ok());
  for (int i = 0; i < 300; ++i) {
    lod.adapt(1.0f / 30);
    if (lod.stats().splits == 0 && lod.stats().collapses == 0) break;
  }
  EXPECT_EQ(lod.checkInvariants(), "");
  return lod.activeFaceCount();
}

TEST(AdaptiveMesh, DetailModifiers) {
  const Model& m = model("fine_sphere");
  const Camera cam = cameraAt(m.bounds, 30.0f, 20.0f, 6.0f);
  DetailParams d;
  const uint32_t base = convergedFaces(m, d, cam);
  d.object_factor = 4.0f;
  const uint32_t object = convergedFaces(m, d, cam);
  EXPECT_LT(object, base / 2);
  d.object_factor = 1.0f;
  auto map = std::make_shared<DetailMap>();
  map->width = 8;
  map->height = 4;
  map->values.assign(32, 4.0f);
  d.detail_map = map;
  const uint32_t mapped = convergedFaces(m, d, cam);
  EXPECT_LT(mapped, base / 2);
  d.detail_map = nullptr;
  d.depth_falloff = 2.0f;
  const uint32_t falloff = convergedFaces(m, d, cam);
  EXPECT_NE(falloff, base);
  d.depth_falloff = 0.0f;
  d.foveation = 1.0f;
  d.focus_px = {0.0f, 0.0f};  // gaze at the corner: the model gets coarser
  const uint32_t fov = convergedFaces(m, d, cam);
  EXPECT_LT(fov, base);
}

TEST(AdaptiveMesh, DetailMapScalesLocally) {
  const Model& m = model("fine_sphere");
  AdaptiveMesh lod(m.pm);
  auto map = std::make_shared<DetailMap>();
  map->width = 2;
  map->height = 1;
  map->values = {1.0f, 8.0f};  // right half: 8× larger triangles
  DetailParams d;
  d.geomorphs = false;
  d.detail_map = map;
  const Camera cam = cameraAt(m.bounds, 0.0f, 0.0f, 3.0f);
  ASSERT_TRUE(lod.setView(cam, kW, kH, d).ok());
  for (int i = 0; i < 200; ++i) lod.adapt(1.0f / 30);
  TriMesh out;
  std::vector<uint32_t> ids;
  lod.exportCompact(out, ids);
  int left = 0, right = 0;
  for (const auto& f : out.faces) {
    const glm::vec3 c = (out.positions[f[0]] + out.positions[f[1]] + out.positions[f[2]]) / 3.0f;
    const glm::vec2 px = projectToPixels(cam, c, kW, kH);
    if (px.x < 0.4f * kW) ++left;
    if (px.x > 0.6f * kW) ++right;
  }
  EXPECT_GT(left, 3 * right);
}

TEST(AdaptiveMesh, BadParametersAreErrors) {
  const Model& m = model("sphere");
  AdaptiveMesh lod(m.pm);
  const Camera cam = cameraAt(m.bounds, 0.0f, 0.0f, 3.0f);
  DetailParams d;
  EXPECT_FALSE(lod.setView(cam, 0, kH, d).ok());
  d.t_c = 0.8f;  // 2·t_c > t_s: would oscillate
  EXPECT_FALSE(lod.setView(cam, kW, kH, d).ok());
  d = DetailParams{};
  d.target_area = -1.0f;
  EXPECT_FALSE(lod.setView(cam, kW, kH, d).ok());
  d = DetailParams{};
  auto map = std::make_shared<DetailMap>();
  map->width = 4;
  map->height = 4;
  map->values.assign(15, 1.0f);
  d.detail_map = map;
  auto st = lod.setView(cam, kW, kH, d);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message.find("detail map"), std::string::npos);
}

TEST(AdaptiveMesh, OffScreenAndBackFacingCoarsen) {
  const Model& m = model("fine_sphere");
  AdaptiveMesh lod(m.pm);
  DetailParams d;
  d.geomorphs = false;
  Camera cam = cameraAt(m.bounds, 0.0f, 0.0f, 3.0f);
  ASSERT_TRUE(lod.setView(cam, kW, kH, d).ok());
  for (int i = 0; i < 100; ++i) lod.adapt(1.0f / 30);
  const uint32_t seen = lod.activeFaceCount();
  // Front half refined more than the back half: count faces by facing direction.
  TriMesh out;
  std::vector<uint32_t> ids;
  lod.exportCompact(out, ids);
  int front = 0, back = 0;
  for (const auto& f : out.faces) {
    const glm::vec3 c = (out.positions[f[0]] + out.positions[f[1]] + out.positions[f[2]]) / 3.0f;
    (glm::dot(c, cam.eye) > 0.0f ? front : back) += 1;
  }
  EXPECT_GT(front, 4 * back);
  // Look away: coarsens to (nearly) the base mesh at once, without geomorphs too.
  cam.target = cam.eye + (cam.eye - m.bounds.center);
  d.geomorphs = true;
  ASSERT_TRUE(lod.setView(cam, kW, kH, d).ok());
  for (int i = 0; i < 5; ++i) lod.adapt(1.0f / 30);
  EXPECT_LT(lod.activeFaceCount(), seen / 20);
  EXPECT_EQ(lod.checkInvariants(), "");
}

TEST(AdaptiveMesh, GeomorphsMorphOutAndCollapseAfterMorphing) {
  const Model& m = model("fine_sphere");
  AdaptiveMesh lod(m.pm);
  DetailParams d;
  d.morph_time = 0.5f;
  const Camera cam = cameraAt(m.bounds, 0.0f, 0.0f, 3.0f);
  ASSERT_TRUE(lod.setView(cam, kW, kH, d).ok());
  lod.adapt(0.0f);
  ASSERT_GT(lod.stats().splits, 0u);
  // New children start at the parent position and are morphing.
  EXPECT_GT(lod.stats().morphing, 0u);
  bool displaced = false;
  auto pos = lod.positions();
  auto nodes = lod.slotVertices();
  for (uint32_t s = 0; s < lod.slotCount(); ++s)
    if (nodes[s] != kPmNone && pos[s] != m.pm.nodePosition(nodes[s])) displaced = true;
  EXPECT_TRUE(displaced);
  EXPECT_FALSE(lod.changes().moved.empty());
  for (int i = 0; i < 200; ++i) lod.adapt(1.0f / 30);
  for (int i = 0; i < 60 && lod.stats().morphing; ++i) lod.adapt(1.0f / 30);
  EXPECT_EQ(lod.stats().morphing, 0u);
  pos = lod.positions();
  nodes = lod.slotVertices();
  for (uint32_t s = 0; s < lod.slotCount(); ++s) {
    if (nodes[s] != kPmNone) {
      ASSERT_EQ(pos[s], m.pm.nodePosition(nodes[s]));
    }
  }
  // Zoom out over 2 s: collapses are first pending (morphing), executed later. (A jump of the
  // camera within one frame executes them at once: their faces leave the band before any
  // morph could end.)
  uint32_t pending = 0;
  for (int f = 1; f <= 60; ++f) {
    ASSERT_TRUE(stepTo(lod, cameraAt(m.bounds, 0.0f, 0.0f, 3.0f * std::pow(2.0f, f / 60.0f)), d));
    pending = std::max(pending, lod.stats().pending_collapses);
  }
  EXPECT_GT(pending, 0u);
  EXPECT_EQ(lod.checkInvariants(), "");
}

/// Frames (at 30 fps) until the face count after a 4× zoom-out comes within 10% of what the
/// same zoom-out reaches without geomorphs (the coarsening lag the geomorphs add).
int coarseningLagFrames(const Model& m, const DetailParams& d, uint32_t* final_faces = nullptr) {
  const Camera near_cam = cameraAt(m.bounds, 0.0f, 0.0f, 3.0f);
  const Camera far_cam = cameraAt(m.bounds, 0.0f, 0.0f, 12.0f);
  DetailParams instant = d;
  instant.geomorphs = false;
  AdaptiveMesh ref(m.pm);
  EXPECT_TRUE(ref.setView(near_cam, kW, kH, instant).ok());
  for (int i = 0; i < 200; ++i) ref.adapt(1.0f / 30);
  EXPECT_TRUE(ref.setView(far_cam, kW, kH, instant).ok());
  for (int i = 0; i < 200; ++i) ref.adapt(1.0f / 30);
  const uint32_t want = ref.activeFaceCount();
  AdaptiveMesh lod(m.pm);
  EXPECT_TRUE(lod.setView(near_cam, kW, kH, d).ok());
  for (int i = 0; i < 200; ++i) lod.adapt(1.0f / 30);
  EXPECT_TRUE(lod.setView(far_cam, kW, kH, d).ok());
  int lag = 300;
  for (int frame = 1; frame <= 300; ++frame) {
    lod.adapt(1.0f / 30);
    if (lod.activeFaceCount() <= 1.1f * want) { lag = frame; break; }
  }
  for (int i = 0; i < 100; ++i) lod.adapt(1.0f / 30);
  if (final_faces) *final_faces = lod.activeFaceCount();
  EXPECT_EQ(lod.checkInvariants(), "");
  return lag;
}

TEST(AdaptiveMesh, CoarseningLagAfterZoomOutIsBounded) {
  const Model& m = model("fine_sphere");
  DetailParams d;
  uint32_t faces = 0;
  const int lag = coarseningLagFrames(m, d, &faces);
  std::printf("coarsening lag after a 4x zoom-out: %d frames at 30 fps (%u faces after)\n", lag,
              faces);
  EXPECT_LE(lag, 20) << "more than 2/3 s to coarsen after a 4x zoom-out";
}

TEST(AdaptiveMesh, OperationBudgetSpreadsWorkOverFrames) {
  const Model& m = model("fine_sphere");
  AdaptiveMesh lod(m.pm);
  DetailParams d;
  d.geomorphs = false;
  d.max_operations = 200;
  ASSERT_TRUE(lod.setView(cameraAt(m.bounds, 0.0f, 0.0f, 6.0f), kW, kH, d).ok());
  int frames = 0, quiet = 0;
  for (; frames < 500 && quiet < 20; ++frames) {
    lod.adapt(1.0f / 30);
    const uint32_t ops = lod.stats().splits + lod.stats().collapses;
    EXPECT_LE(ops, 200u + 64u);  // a forced chain may overshoot a little
    quiet = ops == 0 ? quiet + 1 : 0;
  }
  EXPECT_GT(frames, 10);  // the budget did spread the work
  EXPECT_LT(frames, 500);
  d.max_operations = 0;
  EXPECT_NEAR(static_cast<double>(lod.activeFaceCount()),
              static_cast<double>(convergedFaces(m, d, cameraAt(m.bounds, 0.0f, 0.0f, 6.0f))),
              0.1 * lod.activeFaceCount());
  EXPECT_EQ(lod.checkInvariants(), "");
}

// A time budget that is always spent: each frame still evaluates an eighth of the vertices,
// resuming where the last one stopped, so the mesh reaches the unbudgeted detail anyway (if
// every frame started from the first vertex, the rest would never be visited).
TEST(AdaptiveMesh, TimeBudgetResumesWhereItStopped) {
  const Model& m = model("fine_sphere");
  AdaptiveMesh lod(m.pm);
  DetailParams d;
  d.geomorphs = false;
  d.max_adapt_ms = 1e-9f;
  const Camera cam = cameraAt(m.bounds, 0.0f, 0.0f, 6.0f);
  ASSERT_TRUE(lod.setView(cam, kW, kH, d).ok());
  int frames = 0, quiet = 0;
  for (; frames < 400 && quiet < 20; ++frames) {
    lod.adapt(1.0f / 30);
    quiet = lod.stats().splits + lod.stats().collapses == 0 ? quiet + 1 : 0;
  }
  EXPECT_GT(frames, 20);  // the budget did cut the work
  EXPECT_LT(frames, 400);
  d.max_adapt_ms = 0.0f;
  EXPECT_NEAR(static_cast<double>(lod.activeFaceCount()), static_cast<double>(convergedFaces(m, d, cam)),
              0.05 * lod.activeFaceCount());
  EXPECT_EQ(lod.checkInvariants(), "");
}

TEST(AdaptiveMesh, WorksOnALoadedCacheFile) {
  const Model& m = model("knot");
  test::TempDir dir;
  auto loaded = loadOrBuildPm(m.mesh, meshContentHash(m.mesh), dir.path());
  ASSERT_TRUE(loaded.ok());
  auto again = loadOrBuildPm(m.mesh, meshContentHash(m.mesh), dir.path());  // from the file
  ASSERT_TRUE(again.ok());
  Model copy;
  copy.mesh = m.mesh;
  copy.pm = std::move(again).value();
  copy.bounds = m.bounds;
  expectRefinesToInput(copy);
}

TEST(AdaptiveMesh, ChangeListAndExports) {
  const Model& m = model("sphere");
  AdaptiveMesh lod(m.pm);
  DetailParams d;
  d.geomorphs = false;
  ASSERT_TRUE(stepTo(lod, cameraAt(m.bounds, 0.0f, 0.0f, 2.0f), d));
  const auto& ch = lod.changes();
  ASSERT_FALSE(ch.split.empty());
  EXPECT_EQ(ch.split.size(), lod.stats().splits);
  // Every active vertex created this frame is dirty.
  std::vector<uint8_t> dirty(lod.slotCount(), 0);
  for (uint32_t s : ch.dirty) dirty[s] = 1;
  for (uint32_t s = 0; s < lod.slotCount(); ++s) {
    const uint32_t v = lod.slotVertices()[s];
    if (v == kPmNone || m.pm.parent[v] == kPmNone) continue;
    if (std::find(ch.split.begin(), ch.split.end(), m.pm.parent[v]) != ch.split.end()) {
      EXPECT_TRUE(dirty[s]) << "slot " << s;
    }
  }
  std::vector<std::array<uint32_t, 3>> faces;
  lod.exportFaces(faces);
  EXPECT_EQ(faces.size(), lod.activeFaceCount());
  for (const auto& f : faces)
    for (uint32_t s : f) {
      ASSERT_LT(s, lod.slotCount());
      ASSERT_NE(lod.slotVertices()[s], kPmNone);
    }
  EXPECT_EQ(lod.stats().active_faces, lod.activeFaceCount());
  EXPECT_EQ(lod.stats().active_vertices, lod.activeVertexCount());
}

}  // namespace
}  // namespace lodline

namespace lodline {
namespace {

/// One frame (1/30 s) of two meshes that must adapt alike: the same view for both, then the
/// same splits and collapses.
::testing::AssertionResult adaptAlike(AdaptiveMesh& a, AdaptiveMesh& b, const Camera& cam, const DetailParams& d) {
  if (auto r = stepTo(a, cam, d); !r) return r;
  if (auto r = stepTo(b, cam, d); !r) return r;
  if (a.stats().splits != b.stats().splits || a.stats().collapses != b.stats().collapses)
    return ::testing::AssertionFailure() << "splits " << a.stats().splits << " / " << b.stats().splits
                                         << ", collapses " << a.stats().collapses << " / " << b.stats().collapses;
  return ::testing::AssertionSuccess();
}

// The per-face pass split over worker threads leaves every decision unchanged: two meshes,
// one adapting on three threads and one on the caller's, stay identical through a zooming
// orbit with geomorphs.
TEST(AdaptiveMesh, WorkerThreadsDoNotChangeTheResult) {
  const Model& m = model("fine_torus");
  ASSERT_FALSE(m.mesh.faces.empty());
  AdaptiveMesh serial(m.pm), threaded(m.pm);
  WorkerPool pool(3);
  threaded.setWorkerPool(&pool);
  DetailParams detail;
  std::vector<std::array<uint32_t, 3>> a, b;
  uint32_t ops = 0;
  for (int k = 0; k < 120; ++k) {
    const Camera cam = cameraAt(m.bounds, 3.0f * k, 30.0f, 2.0f + 4.0f * std::abs(std::sin(0.05f * k)));
    ASSERT_TRUE(adaptAlike(serial, threaded, cam, detail)) << k;
    ASSERT_EQ(serial.stats().visible_faces, threaded.stats().visible_faces) << k;
    ASSERT_EQ(serial.stats().band_fraction, threaded.stats().band_fraction) << k;
    serial.exportFaces(a);
    threaded.exportFaces(b);
    ASSERT_EQ(a, b) << k;
    ops += serial.stats().splits + serial.stats().collapses;
  }
  EXPECT_GT(ops, 1000u);
  EXPECT_GT(threaded.activeFaceCount(), 2u * 4096u);  // long enough to be split over threads
  EXPECT_EQ(threaded.checkInvariants(), "");
}

/// The `zoom-out` camera path run in 2 s (16× farther, exponential, 60 frames at 30 fps) from
/// converged detail at the default framing, then 10 frames at rest: the lowest band fraction
/// of the drawn frames (the mesh after each adapt()) while the camera moves, and the band
/// fraction 10 frames after it stops; each also with faces at the hierarchy's ends counted in
/// (LodStats::band_or_limit_fraction).
struct ZoomBand {
  float lowest = 1.0f, after = 0.0f;
  float lowest_or_limit = 1.0f, after_or_limit = 0.0f;
};
/// Camera distance of the default framing, in bounding radii.
const float kDefaultFramingRadii = 1.08f / std::sin(glm::radians(17.5f));
/// Distance at frame f of that zoom (f = 0: the default framing; from frame 60 on, 16×).
float zoomOutRadii(int f) {
  return kDefaultFramingRadii * std::pow(16.0f, static_cast<float>(std::min(f, 60)) / 60.0f);
}
ZoomBand fastZoomOutBand(const Model& m) {
  AdaptiveMesh lod(m.pm);
  DetailParams d;
  EXPECT_TRUE(lod.setView(cameraAt(m.bounds, 35.0f, 20.0f, zoomOutRadii(0)), kW, kH, d).ok());
  for (int i = 0, quiet = 0; i < 300 && quiet < 10; ++i) {
    lod.adapt(1.0f);
    quiet = lod.stats().splits + lod.stats().collapses + lod.stats().morphing == 0 ? quiet + 1 : 0;
  }
  ZoomBand z;
  float band = 0.0f, or_limit = 0.0f;
  uint32_t visible = 0;
  for (int f = 1; f <= 70; ++f) {
    EXPECT_TRUE(lod.setView(cameraAt(m.bounds, 35.0f, 20.0f, zoomOutRadii(f)), kW, kH, d).ok());
    lod.adapt(1.0f / 30);
    lod.measureBand(band, visible, &or_limit);
    if (f <= 60) {
      z.lowest = std::min(z.lowest, band);
      z.lowest_or_limit = std::min(z.lowest_or_limit, or_limit);
    }
  }
  z.after = band;
  z.after_or_limit = or_limit;
  EXPECT_EQ(lod.checkInvariants(), "");
  return z;
}
/// Converges `lod` for a still at `cam` as `render` converges it: no geomorphs, steps of 1/30 s
/// until one makes no split or collapse, at most 300. Returns the steps taken, or -1 when the
/// view is refused.
int convergeStill(AdaptiveMesh& lod, const Camera& cam) {
  DetailParams d;
  d.geomorphs = false;
  if (!lod.setView(cam, kW, kH, d).ok()) return -1;
  int steps = 0;
  while (steps < 300) {
    lod.adapt(1.0f / 30);
    ++steps;
    if (lod.stats().splits == 0 && lod.stats().collapses == 0) break;
  }
  return steps;
}
/// The targets for that zoom: ≥ 0.8 in every frame, ≥ 0.9 ten frames after the stop.
void expectFastZoomKeepsTheBand(const char* name) {
  const ZoomBand z = fastZoomOutBand(model(name));
  std::printf("%s: band lowest while zooming %.3f, 10 frames after %.3f\n", name, z.lowest, z.after);
  EXPECT_GE(z.lowest, 0.8f);
  EXPECT_GE(z.after, 0.9f);
}

// Faces outside the band only because the hierarchy ends there count in band_or_limit: a T
// far below the full-detail faces' areas refines everything to full detail (faces too large,
// all corners leaves), one far above coarsens to the base mesh (too small, all corners roots).
TEST(AdaptiveMesh, BandOrLimitCountsFacesAtTheHierarchysEnds) {
  const Model& m = model("torus");
  ASSERT_FALSE(m.mesh.faces.empty());
  for (const float t : {1e-3f, 1e7f}) {
    SCOPED_TRACE(t);
    AdaptiveMesh lod(m.pm);
    DetailParams d;
    d.target_area = t;
    for (int i = 0; i < 60; ++i) ASSERT_TRUE(stepTo(lod, cameraAt(m.bounds, 35.0f, 20.0f, 3.0f), d));
    float band = 0.0f, or_limit = 0.0f;
    uint32_t visible = 0;
    lod.measureBand(band, visible, &or_limit);
    ASSERT_GT(visible, 0u);
    EXPECT_LT(band, 0.05f);
    EXPECT_GT(or_limit, 0.99f);
    // adapt()'s own figure, measured on the mesh that entered the last step, agrees.
    EXPECT_GT(lod.stats().band_or_limit_fraction, 0.99f);
  }
  // Where the mesh can follow T (the 82k torus at the default T; the 9k one's full-detail
  // faces are larger than the band there), most faces are in the band proper.
  const Model& fine = model("fine_torus");
  AdaptiveMesh lod(fine.pm);
  DetailParams d;
  for (int i = 0; i < 60; ++i) ASSERT_TRUE(stepTo(lod, cameraAt(fine.bounds, 35.0f, 20.0f, 3.0f), d));
  float band = 0.0f, or_limit = 0.0f;
  uint32_t visible = 0;
  lod.measureBand(band, visible, &or_limit);
  EXPECT_GT(band, 0.85f);
  EXPECT_GE(or_limit, band);
}

TEST(AdaptiveMesh, DueCollapsesAreUnblockedAfterAZoomOut) {
  // A zoom-out to 16x the framing distance in 20 frames, without geomorphs, then 20 frames
  // at rest. Collapses that are due but illegal (Hoppe's dependencies on finer neighbours)
  // used to wait for collapses that never became due themselves, and the mesh stayed several
  // times finer than a fresh convergence at that view. Measured when written, band fraction
  // at rest with / without unblockCollapse(): torus 0.745 / 0.438, armadillo 0.976 / 0.289
  // (88 against 322 faces; about 60 from a fresh convergence); the knot, 0.849 / 0.855, is
  // there for the criterion and the morph speed.
  const std::pair<const char*, float> cases[] = {{"knot", 0.8f}, {"torus", 0.7f}, {"armadillo.off", 0.9f}};
  for (const auto& [name, want] : cases) {
    SCOPED_TRACE(name);
    const Model& m = model(name);
    if (m.mesh.faces.empty()) continue;  // CGAL data meshes not installed
    DetailParams d;
    d.geomorphs = false;
    const float start = kDefaultFramingRadii;
    AdaptiveMesh lod(m.pm);
    ASSERT_TRUE(lod.setView(cameraAt(m.bounds, 35.0f, 20.0f, start), kW, kH, d).ok());
    for (int i = 0; i < 100; ++i) lod.adapt(1.0f);
    for (int f = 1; f <= 40; ++f) {
      const float s = std::pow(16.0f, static_cast<float>(std::min(f, 20)) / 20.0f);
      ASSERT_TRUE(stepTo(lod, cameraAt(m.bounds, 35.0f, 20.0f, start * s), d));
    }
    float band = 0.0f;
    uint32_t visible = 0;
    lod.measureBand(band, visible);
    std::printf("%s: band %.3f at rest, %u faces\n", name, band, lod.activeFaceCount());
    EXPECT_GE(band, want) << lod.activeFaceCount() << " faces";
    EXPECT_EQ(lod.checkInvariants(), "");
  }
}

// A split is refused only where it turns a face over, not where it leaves a coarse face more
// than 90° from the normal of its full-detail face (splitFacingAllowed()). The refined
// elephant's progressive mesh has coarse faces around its legs and trunk that point far from
// their full-detail faces; refusing every split that left one past 90° held it at about 1,100
// faces and a band fraction of 0.77, however many frames it had. Here: 120 frames at the
// default framing, every one allowed to retry, and the faces so left are listed as folds.
TEST(AdaptiveMesh, SplitsThatTurnNoFaceOverRefineASubdividedModel) {
  const Model& m = model("refined_elephant.off");
  if (m.mesh.faces.empty()) GTEST_SKIP() << "refined_elephant.off not found";
  AdaptiveMesh lod(m.pm);
  DetailParams d;
  d.geomorphs = false;
  ASSERT_TRUE(lod.setView(cameraAt(m.bounds, 35.0f, 20.0f, kDefaultFramingRadii), kW, kH, d).ok());
  uint32_t listed = 0;  // frames that end with a face listed as folded
  for (int i = 0; i < 120; ++i) {
    lod.adapt(1.0f / 30);
    ASSERT_EQ(lod.checkInvariants(), "") << "frame " << i;
    listed += lod.stats().folded_faces > 0;
  }
  float band = 0.0f;
  uint32_t visible = 0;
  lod.measureBand(band, visible);
  EXPECT_GE(band, 0.9f) << "active faces " << lod.activeFaceCount() << ", frames with folds listed " << listed;
  EXPECT_GT(visible, 8000u);
}

// A still converges to the band on the organic CGAL demo meshes, as `render` does it (steps
// of 1/30 s without geomorphs until one changes nothing): band fraction, counting the faces at
// the hierarchy's ends, at least 0.9 at the default framing, and at rest 300 frames later. The refined elephant read 0.773 here for two days before anyone looked
// (splits refused for a coarse face's reference normal, docs/detail-control.md §8); when
// written the seven read 0.911-0.999. The femur is here for the rest: a face that a split
// left against its full-detail normal, whose repair was refused at two corners, had the third
// corner split by the repair and collapsed by the criterion every frame (120 operations in
// frames 300-360) until such a repair was undone (repairFolds()).
TEST(AdaptiveMesh, StillsOfCgalMeshesReachTheBand) {
  bool any = false;
  for (const char* name : {"armadillo.off", "bunny00.off", "refined_elephant.off", "camel.off", "man.off",
                           "diplodocus.off", "bear.off", "femur.off"}) {
    SCOPED_TRACE(name);
    const Model& m = model(name);
    if (m.mesh.faces.empty()) continue;
    any = true;
    AdaptiveMesh lod(m.pm);
    const int steps = convergeStill(lod, cameraAt(m.bounds, 35.0f, 20.0f, kDefaultFramingRadii));
    ASSERT_GE(steps, 0);
    ASSERT_EQ(lod.checkInvariants(), "");
    float band = 0.0f, band_or_limit = 0.0f;
    uint32_t visible = 0;
    lod.measureBand(band, visible, &band_or_limit);
    EXPECT_GE(band_or_limit, 0.9f) << lod.activeFaceCount() << " faces after " << steps << " steps, band " << band;
    // And it comes to rest: the repair of faces that splits leave against their full-detail
    // normal must not trade splits and collapses with the criterion at a fixed view. (Splits
    // refused earlier are retried for a while, 8 to 64 frames apart; after 300 frames nothing
    // is left to do.)
    for (int i = 0; i < 300; ++i) lod.adapt(1.0f / 30);
    uint32_t ops = 0;
    for (int i = 0; i < 60; ++i) {
      lod.adapt(1.0f / 30);
      ops += lod.stats().splits + lod.stats().collapses;
    }
    EXPECT_EQ(ops, 0u) << "operations in frames 300-360 at the converged view";
    EXPECT_EQ(lod.checkInvariants(), "");
  }
  if (!any) GTEST_SKIP() << "CGAL meshes not found";
}

// The rule for a split's new faces (lod/fold_rules.h): a new face is turned over only against
// the two faces it opens between, not against a reference that a coarse face may point far
// from. Two sides sharing the edge x = 0 of the plane z = 0, both facing +z.
TEST(FoldRules, ANewFaceIsTurnedOverOnlyAgainstTheFacesItOpensBetween) {
  const glm::vec3 up(0.0f, 0.0f, 1.0f);
  const glm::vec3 a(0.0f, 0.0f, 0.0f), b(1.0f, 0.0f, 0.0f);
  // Tilted 100° from +z but still within 90° of the sides' sum: not turned over, though
  // against a full-detail normal of +z.
  const float t = glm::radians(100.0f);
  const glm::vec3 c_tilted(0.0f, std::cos(t), std::sin(t));  // normal of (a, b, c) ∝ (0, -sin t, cos t)
  const glm::vec3 n_tilted = glm::cross(b - a, c_tilted - a);
  const glm::vec3 side_tilted = n_tilted + 0.2f * up;  // sides leaning the face's way
  EXPECT_FALSE(facesAlong(a, b, c_tilted, up));
  EXPECT_FALSE(turnedOverBetween(a, b, c_tilted, side_tilted, side_tilted));
  // The same face between two sides facing +z: turned over (a fold).
  EXPECT_TRUE(turnedOverBetween(a, b, c_tilted, up, 2.0f * up));
  // Exactly 90° counts as turned over; the winding decides.
  EXPECT_TRUE(turnedOverBetween(a, b, glm::vec3(0.0f, 0.0f, 1.0f), up, up));
  EXPECT_FALSE(turnedOverBetween(a, b, glm::vec3(0.0f, 1.0f, 0.0f), up, up));
  EXPECT_TRUE(turnedOverBetween(b, a, glm::vec3(0.0f, 1.0f, 0.0f), up, up));
  // A knife edge (sides facing opposite ways) or sides without area give no reference.
  EXPECT_FALSE(turnedOverBetween(b, a, glm::vec3(0.0f, 1.0f, 0.0f), up, -up));
  EXPECT_FALSE(turnedOverBetween(b, a, glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0.0f), glm::vec3(0.0f)));
  // One side without area: the other decides.
  EXPECT_TRUE(turnedOverBetween(b, a, glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0.0f), up));
}

// A face a split creates may end against its full-detail normal, as long as it is not
// turned over against the two faces it opens between (splitNewFaceAllowed()). Held to its
// full-detail normal, as before 2026-12-07, it refused for good the splits of about 120
// vertices behind the bunny's ears: the still stopped at 10,338 faces, band 0.910, with the far
// ear collapsed into the head and the back of the neck one large triangle; its fast zoom-out
// dipped to 0.788. When written: 17.7k faces, band 0.958; the zoom 0.858 / 0.925.
TEST(AdaptiveMesh, SplitsWhoseNewFacesDoNotFoldRefineTheBunnysEars) {
  const Model& m = model("bunny00.off");
  if (m.mesh.faces.empty()) GTEST_SKIP() << "bunny00.off not found";
  AdaptiveMesh lod(m.pm);
  const int steps = convergeStill(lod, cameraAt(m.bounds, 35.0f, 20.0f, kDefaultFramingRadii));
  ASSERT_GE(steps, 0);
  ASSERT_LT(steps, 300) << "did not converge";
  ASSERT_EQ(lod.checkInvariants(), "");
  float band = 0.0f;
  uint32_t visible = 0;
  lod.measureBand(band, visible);
  std::printf("bunny00: %u faces, band %.3f after %d steps\n", lod.activeFaceCount(), band, steps);
  EXPECT_GE(band, 0.94f) << lod.activeFaceCount() << " faces";
  expectFastZoomKeepsTheBand("bunny00.off");
}

// Stills from all round, close up and framed: 8 azimuths, 2 elevations (20°, -30°), at the
// default framing and at 1.6 radii, converged as `render` converges; band fraction counting
// the faces at the hierarchy's ends at least 0.9 in each of the 32 views. Scanned on
// 2026-12-07 over fourteen CGAL meshes, the lowest view of each read 0.906-0.995; with the new
// faces of a split held to their full-detail normals (before detail-control.md §9) four of the
// bunny's close views read 0.865-0.895.
TEST(AdaptiveMesh, StillsReachTheBandFromAllRound) {
  bool any = false;
  for (const char* name : {"bunny00.off", "armadillo.off", "refined_elephant.off", "lion-head.off", "femur.off"}) {
    const Model& m = model(name);
    if (m.mesh.faces.empty()) continue;
    any = true;
    for (const float dist : {kDefaultFramingRadii, 1.6f})
      for (float az = 0.0f; az < 360.0f; az += 45.0f)
        for (const float el : {20.0f, -30.0f}) {
          SCOPED_TRACE(::testing::Message() << name << " distance " << dist << " azimuth " << az << " elevation " << el);
          AdaptiveMesh lod(m.pm);
          const int steps = convergeStill(lod, cameraAt(m.bounds, az, el, dist));
          ASSERT_GE(steps, 0);
          float band = 0.0f, band_or_limit = 0.0f;
          uint32_t visible = 0;
          lod.measureBand(band, visible, &band_or_limit);
          EXPECT_GE(band_or_limit, 0.9f) << lod.activeFaceCount() << " faces after " << steps << " steps";
        }
  }
  if (!any) GTEST_SKIP() << "CGAL meshes not found";
}

TEST(AdaptiveMesh, FastZoomOutKeepsTheBand) {
  // Measured when written: 0.863 while zooming, 0.989 ten frames after. Without the morph
  // speed that follows the zoom (collapseSpeedup) the lowest frame is 0.576, without the
  // unblocking of due collapses 0.784; with the old criterion (the mean after the collapse
  // below t_c·T) it was 0.180. Other meshes, where the result is less even, are in
  // docs/detail-control.md.
  expectFastZoomKeepsTheBand("fine_sphere");
}

// The 82k torus after the same zoom ended at 0.835 (292 faces against 168 for a fresh
// convergence) while a collapse that would fold a sub-pixel sliver over was refused and the
// due collapses behind it waited for good (docs/detail-control.md §7). Such folds are now
// allowed and listed; one that the camera brings closer before a split has undone it is
// refined back (repairFolds()).
TEST(AdaptiveMesh, SubPixelFoldsFreeTheTorusAndAreRepairedWhenTheyGrow) {
  expectFastZoomKeepsTheBand("fine_torus");

  // The same zoom, stopped at the first frame that leaves a fold of a collapse listed; then
  // the camera jumps back in, where the fold would be seen: every listed fold must be gone,
  // and somewhere repaired. Whether a fold is left listed at the end of a frame, and whether
  // the splits of the way back remove it before the repair has to, depends on the order of
  // operations (since splits may leave a face against its full-detail normal, 2026-12-07, the
  // azimuth of 35° used before leaves none): several azimuths, and the repair must happen in
  // one of them.
  const Model& m = model("fine_torus");
  DetailParams d;
  uint32_t folds_seen = 0, repairs = 0;
  for (const float az : {35.0f, 30.0f, 60.0f, 90.0f, 150.0f, 240.0f, 270.0f}) {
    SCOPED_TRACE(az);
    AdaptiveMesh lod(m.pm);
    ASSERT_TRUE(lod.setView(cameraAt(m.bounds, az, 20.0f, kDefaultFramingRadii), kW, kH, d).ok());
    for (int i = 0; i < 300; ++i) lod.adapt(1.0f);
    uint32_t folds = 0;  // the collapses that folded a face (a split may list one too)
    for (int f = 1; f <= 60 && !(folds > 0 && lod.stats().folded_faces > 0); ++f) {
      ASSERT_TRUE(lod.setView(cameraAt(m.bounds, az, 20.0f, zoomOutRadii(f)), kW, kH, d).ok());
      lod.adapt(1.0f / 30);
      folds += lod.stats().folds;
      ASSERT_EQ(lod.checkInvariants(), "") << "frame " << f;
    }
    if (!(folds > 0 && lod.stats().folded_faces > 0)) continue;
    folds_seen += folds;
    for (const float s : {8.0f, 4.0f, 2.0f, 1.0f, 0.5f}) {
      ASSERT_TRUE(lod.setView(cameraAt(m.bounds, az, 20.0f, kDefaultFramingRadii * s), kW, kH, d).ok());
      lod.adapt(1.0f / 30);
      repairs += lod.stats().fold_repairs;
      ASSERT_EQ(lod.checkInvariants(), "") << "distance " << s;
    }
    EXPECT_EQ(lod.stats().folded_faces, 0u);
    if (repairs > 0) break;
  }
  EXPECT_GT(folds_seen, 0u);
  EXPECT_GT(repairs, 0u);
}

}  // namespace
}  // namespace lodline

namespace lodline {
namespace {

// What a renumbering must keep: each active node's displayed position, the faces as node
// triples (corners in order), the morphs in flight.
struct NodeView {
  std::map<uint32_t, glm::vec3> positions;
  std::vector<std::array<uint32_t, 3>> faces;  // rotated to start at the smallest node, sorted
};
NodeView nodeView(const AdaptiveMesh& lod) {
  NodeView v;
  const auto nodes = lod.slotVertices();
  for (uint32_t s = 0; s < lod.slotCount(); ++s)
    if (nodes[s] != kPmNone) v.positions[nodes[s]] = lod.positions()[s];
  std::vector<std::array<uint32_t, 3>> faces;
  lod.exportFaces(faces);
  for (auto f : faces) {
    for (uint32_t& c : f) c = nodes[c];
    while (f[0] > f[1] || f[0] > f[2]) f = {f[1], f[2], f[0]};
    v.faces.push_back(f);
  }
  std::sort(v.faces.begin(), v.faces.end());
  return v;
}

uint32_t medianSpread(const AdaptiveMesh& lod) {
  TriMesh t;
  t.positions.assign(lod.positions().begin(), lod.positions().end());
  lod.exportFaces(t.faces);
  return medianCornerSpread(t);
}

// orderForLocality() changes the numbering only: the same nodes at the same displayed
// positions, the same faces, the morphs still running; slots without gaps, faces sorted by
// their lowest corner, every slot in the change list, and a far smaller corner spread.
TEST(AdaptiveMesh, OrderingSlotsKeepsTheMesh) {
  const Model& m = model("fine_torus");
  ASSERT_FALSE(m.mesh.faces.empty());
  AdaptiveMesh lod(m.pm);
  DetailParams d;
  d.target_area = 6.0f;
  // A zoom from far to close: slots are taken in the order of the splits.
  for (int k = 0; k < 40; ++k) {
    ASSERT_TRUE(stepTo(lod, cameraAt(m.bounds, 2.0f * k, 30.0f, 8.0f - 0.15f * k), d));
  }
  ASSERT_GT(lod.stats().morphing, 0u);
  ASSERT_GT(lod.activeVertexCount(), 4096u);
  const NodeView before = nodeView(lod);
  const uint32_t spread_before = medianSpread(lod);
  const uint32_t morphing = lod.stats().morphing;
  lod.orderForLocality();
  ASSERT_EQ(lod.checkInvariants(), "");
  const NodeView after = nodeView(lod);
  EXPECT_EQ(after.positions, before.positions);
  EXPECT_EQ(after.faces, before.faces);
  EXPECT_EQ(lod.slotCount(), lod.activeVertexCount());
  std::vector<uint32_t> dirty = lod.changes().dirty;
  std::sort(dirty.begin(), dirty.end());
  ASSERT_EQ(dirty.size(), lod.slotCount());
  for (uint32_t s = 0; s < dirty.size(); ++s) ASSERT_EQ(dirty[s], s);
  std::vector<std::array<uint32_t, 3>> faces;
  lod.exportFaces(faces);
  for (size_t k = 1; k < faces.size(); ++k)
    ASSERT_LE(*std::min_element(faces[k - 1].begin(), faces[k - 1].end()),
              *std::min_element(faces[k].begin(), faces[k].end()));
  // (adapt() ordered the slots already during the zoom, so the spread before is small too.)
  const uint32_t spread_after = medianSpread(lod);
  EXPECT_LE(spread_after, spread_before);
  EXPECT_LT(spread_after * 100, lod.slotCount()) << spread_after << " of " << lod.slotCount();

  // The morphs go on from where they were and end; the mesh stays valid.
  for (int k = 0; k < 30; ++k) {
    ASSERT_TRUE(stepTo(lod, cameraAt(m.bounds, 80.0f, 30.0f, 2.0f), d));
    if (k == 0) {
      EXPECT_GT(lod.stats().morphing, 0u) << "of " << morphing << " morphing before";
    }
  }
  EXPECT_EQ(lod.checkInvariants(), "");
}

// Renumbering changes no decision: a mesh whose slots are renumbered after every frame adapts
// exactly as one renumbered only when adapt() decides to, through a zoom-out and an orbit
// with geomorphs (the order of evaluation keeps each vertex's place).
TEST(AdaptiveMesh, RenumberingChangesNoDecision) {
  const Model& m = model("fine_torus");
  ASSERT_FALSE(m.mesh.faces.empty());
  AdaptiveMesh plain(m.pm), renumbered(m.pm);
  DetailParams d;
  d.max_adapt_ms = 0.0f;
  uint32_t ops = 0;
  for (int k = 0; k < 120; ++k) {
    const float dist = k < 60 ? 2.0f * std::pow(8.0f, k / 60.0f) : 2.0f;  // a zoom-out, then close
    const Camera cam = cameraAt(m.bounds, 4.0f * k, 30.0f, dist);
    ASSERT_TRUE(adaptAlike(plain, renumbered, cam, d)) << k;
    ASSERT_EQ(plain.stats().morphing, renumbered.stats().morphing) << k;
    const NodeView a = nodeView(plain), b = nodeView(renumbered);
    ASSERT_EQ(a.positions, b.positions) << k;
    ASSERT_EQ(a.faces, b.faces) << k;
    ops += plain.stats().splits + plain.stats().collapses;
    renumbered.orderForLocality();
  }
  EXPECT_GT(ops, 5000u);
  EXPECT_EQ(renumbered.checkInvariants(), "");
  EXPECT_EQ(plain.checkInvariants(), "");
}

// The evaluation skips the vertices that had nothing to do when its pass began unless their
// ring, lock or sibling changed since (AdaptiveMesh::idleAtStart, touchSlot): the adapted mesh
// is the same as when every vertex is evaluated, frame by frame, through orbits, a fast
// zoom-out with geomorphs and a zoom back in, on a closed mesh and an open one with many
// components; alone and with worker threads under an operation budget (the round robin's
// resume path). And no vertex the skipping would pass over acts when evaluated.
TEST(AdaptiveMesh, SkippingIdleVerticesChangesNoDecision) {
  WorkerPool pool(3);
  for (const bool threaded_budget : {false, true}) {
    for (const char* name : {"fine_torus", "cow.off"}) {
      SCOPED_TRACE(std::string(name) + (threaded_budget ? ", threads and a budget" : ""));
      const Model& m = model(name);
      ASSERT_FALSE(m.mesh.faces.empty());
      AdaptiveMesh every(m.pm), skipping(m.pm);
      every.setEvaluateEveryVertex(true);
      DetailParams d;
      d.target_area = 8.0f;
      if (threaded_budget) {
        every.setWorkerPool(&pool);
        skipping.setWorkerPool(&pool);
        d.max_operations = 60;
      }
      uint32_t ops = 0;
      for (int k = 0; k < 150; ++k) {
        const float dist = k < 50 ? 2.0f + 0.05f * k : k < 90 ? 4.5f * std::pow(8.0f, (k - 50) / 40.0f) : 1.5f;
        const Camera cam = cameraAt(m.bounds, 3.0f * k, 20.0f, dist);
        ASSERT_TRUE(adaptAlike(every, skipping, cam, d)) << "frame " << k;
        ASSERT_EQ(every.stats().morphing, skipping.stats().morphing) << "frame " << k;
        ASSERT_EQ(every.stats().pending_collapses, skipping.stats().pending_collapses) << "frame " << k;
        const NodeView a = nodeView(every), b = nodeView(skipping);
        ASSERT_EQ(a.positions, b.positions) << "frame " << k;
        ASSERT_EQ(a.faces, b.faces) << "frame " << k;
        ASSERT_EQ(every.idleMispredictions(), 0u) << "frame " << k;
        ops += every.stats().splits + every.stats().collapses;
      }
      EXPECT_GT(ops, 3000u);
      EXPECT_EQ(skipping.checkInvariants(), "");
    }
  }
}

// adapt() orders the slots by itself as the mesh changes; the mesh stays valid and converges
// into the band at rest.
TEST(AdaptiveMesh, AdaptOrdersSlotsAsTheMeshChanges) {
  const Model& m = model("fine_torus");
  ASSERT_FALSE(m.mesh.faces.empty());
  AdaptiveMesh lod(m.pm);
  DetailParams d;
  d.target_area = 16.0f;
  int ordered = 0;
  for (int k = 0; k < 150; ++k) {
    ASSERT_TRUE(stepTo(lod, cameraAt(m.bounds, 3.0f * k, 30.0f, 3.0f + 3.0f * std::abs(std::sin(0.04f * k))), d));
    if (lod.stats().slots_ordered) {
      ++ordered;
      ASSERT_EQ(lod.checkInvariants(), "") << k;
    }
  }
  EXPECT_GE(ordered, 2);
  EXPECT_EQ(lod.checkInvariants(), "");
  // At rest it converges into the band.
  for (int k = 0; k < 40; ++k) lod.adapt(1.0f / 30.0f);
  float band = 0.0f;
  uint32_t visible = 0;
  lod.measureBand(band, visible);
  EXPECT_GT(band, 0.9f) << lod.activeFaceCount() << " of " << m.mesh.faceCount();
  EXPECT_EQ(lod.checkInvariants(), "");
}

}  // namespace
}  // namespace lodline
