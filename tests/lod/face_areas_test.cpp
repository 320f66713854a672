// faceImageAreas() runs sixteen or eight faces a step where the processor allows (the clone
// it picks here); it must give the bits of the face-by-face arithmetic it replaced in
// AdaptiveMesh::adapt(), which this test spells out with glm.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "lod/face_areas.h"

namespace lodline {
namespace {

void reference(const FaceAreaView& a, size_t begin, size_t end, float* area, uint8_t* visible) {
  for (size_t f = begin; f < end; ++f) {
    const auto& c = a.faces[f];
    const glm::vec3 &p0 = a.pos[c[0]], &p1 = a.pos[c[1]], &p2 = a.pos[c[2]];
    const glm::vec3 n = glm::cross(p1 - p0, p2 - p0);
    const float face_area = 0.5f * glm::length(n);
    const glm::vec3 centre = (p0 + p1 + p2) * (1.0f / 3.0f);
    const glm::vec3 m = centre - a.eye;
    area[f] = a.ortho ? a.k * face_area : a.k * face_area / std::max(glm::dot(m, m), a.near2);
    bool in = glm::dot(n, a.ortho ? a.forward : m) < 0.0f;
    for (int i = 0; i < kFrustumPlanes; ++i)
      in &= glm::dot(glm::vec3(a.planes[i]), centre) + a.planes[i].w >= 0.0f;
    visible[f] = in;
  }
}

TEST(FaceImageAreas, EqualsTheFaceByFaceArithmetic) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<glm::vec3> pos(500);
  for (auto& p : pos) p = {u(rng), u(rng), u(rng)};
  pos[0] = glm::vec3(0.0f);  // the eye itself below: d² clamped to near²
  pos[1] = glm::vec3(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f);
  std::uniform_int_distribution<uint32_t> pick(0, static_cast<uint32_t>(pos.size() - 1));
  std::vector<std::array<uint32_t, 3>> faces(1000 + 37);  // no multiple of a block
  for (auto& f : faces) f = {pick(rng), pick(rng), pick(rng)};
  faces[5] = {0, 0, 0};   // at the eye
  faces[6] = {7, 7, 9};   // degenerate
  faces[7] = {1, 2, 3};   // a non-finite corner
  faces[8] = {0, 10, 11};
  std::array<glm::vec4, kFrustumPlanes> planes{};
  for (auto& pl : planes) pl = {u(rng), u(rng), u(rng), 0.6f};
  int visible_faces = 0, hidden_faces = 0;
  for (const bool ortho : {false, true}) {
    SCOPED_TRACE(ortho);
    const FaceAreaView view{faces.data(), pos.data(), planes.data(), glm::vec3(0.0f),
                            glm::normalize(glm::vec3(0.3f, -0.2f, -1.0f)), 1234.5f, 1e-4f, ortho};
    for (const auto& [begin, end] : {std::pair<size_t, size_t>{0, faces.size()}, {3, 70}, {64, 65}, {100, 100}}) {
      std::vector<float> area(faces.size(), -1.0f), want_area(faces.size(), -1.0f);
      std::vector<uint8_t> vis(faces.size(), 7), want_vis(faces.size(), 7);
      faceImageAreas(view, begin, end, area.data(), vis.data());
      reference(view, begin, end, want_area.data(), want_vis.data());
      ASSERT_EQ(std::memcmp(area.data(), want_area.data(), area.size() * sizeof(float)), 0) << begin << ".." << end;
      ASSERT_EQ(vis, want_vis) << begin << ".." << end;  // and nothing written outside the range
      for (size_t f = begin; f < end; ++f) (vis[f] ? visible_faces : hidden_faces) += 1;
    }
  }
  EXPECT_GT(visible_faces, 100);  // both outcomes exercised
  EXPECT_GT(hidden_faces, 100);
}

}  // namespace
}  // namespace lodline
