// Step 1 of AdaptiveMesh::adapt(): the image area of every active face and whether it is
// visible (Jeong et al. 2005 §3.1: the criterion's areas k·A/d²; docs/detail-control.md).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace lodline {

/// The frustum planes of AdaptiveMesh (no far plane).
constexpr int kFrustumPlanes = 5;

/// What faceImageAreas() reads: faces as corner indices into `pos`, and the view.
struct FaceAreaView {
  const std::array<uint32_t, 3>* faces;
  const glm::vec3* pos;
  const glm::vec4* planes;  ///< kFrustumPlanes planes, inside where dot(xyz, p) + w ≥ 0
  glm::vec3 eye;            ///< perspective: the eye, model units
  glm::vec3 forward;        ///< orthographic: the viewing direction
  float k;                  ///< image area = k·A/d² (perspective) or k·A (orthographic), px²
  float near2;              ///< d² is clamped to at least this
  bool ortho;
};

/// For faces [begin, end): area[f] = the face's image area, k·A/max(d², near2) with A its area
/// and d the distance from the eye to its centre (k·A when orthographic); visible[f] = 1 when
/// it faces the camera (its normal against the direction to its centre, or `forward`) and its
/// centre lies inside every plane, else 0. `area` and `visible` hold at least `end` entries
/// and alias nothing else. Eight faces a step where the processor has AVX2 or AVX-512F (the
/// compiler keeps to 256-bit vectors here), with the same bits as one face at a time.
void faceImageAreas(const FaceAreaView& view, size_t begin, size_t end, float* area, uint8_t* visible);

}  // namespace lodline
