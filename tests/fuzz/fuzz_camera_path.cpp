// Fuzz target: camera-path JSON (`capture --path FILE.json`, `view --play`) through
// loadCameraPath, and an accepted path sampled the way a capture samples it.
#include <cmath>

#include <glm/mat4x4.hpp>

#include "frame/camera_path.h"
#include "harness.h"

LODLINE_FUZZ_TARGET(camera_path) {
  using namespace lodline;
  const fuzz::InputFile input(".json", "", data, size);
  Result<CameraPath> path = loadCameraPath(input.path());
  if (!path) {
    fuzz::expectCleanError(path.error(), input.path());
    return;
  }
  if (!path->validate().empty()) fuzz::fail("loadCameraPath accepted an invalid path: " + path->validate());
  Bounds bounds;
  bounds.min = glm::vec3(-1.0f);
  bounds.max = glm::vec3(1.0f);
  bounds.radius = std::sqrt(3.0f);
  const double duration = path->duration();
  if (!std::isfinite(duration) || duration < 0.0) fuzz::fail("accepted path has duration " + std::to_string(duration));
  for (int k = 0; k <= 16; ++k) {
    const Camera cam = path->at(path->keys().front().time + duration * k / 16.0, bounds);
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(cam.eye[c]) || !std::isfinite(cam.target[c]) || !std::isfinite(cam.up[c]))
        fuzz::fail("accepted path gives a non-finite camera at sample " + std::to_string(k));
    if (!(cam.near_plane > 0.0f && cam.far_plane > cam.near_plane)) fuzz::fail("accepted path gives bad clip planes");
    const glm::mat4 view = cam.view();
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (!std::isfinite(view[i][j])) fuzz::fail("accepted path gives a non-finite view matrix at sample " + std::to_string(k));
  }
}
