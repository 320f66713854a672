// Camera paths for captures and walkthroughs: keyframes (time, eye, target, up, fov) read
// from JSON and interpolated smoothly (Catmull-Rom through the keys), plus built-in paths
// made for a model's bounding sphere.
//
// File format (docs/capture.md):
//   {"keys": [{"time": 0, "eye": [0,0,5], "target": [0,0,0], "up": [0,1,0], "fov": 35}, ...]}
// `up` and `fov` are optional (default +Y and 35°); times must increase.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/result.h"

namespace lodline {

struct CameraKey {
  double time = 0.0;  ///< seconds from the start of the path
  glm::vec3 eye{0.0f, 0.0f, 3.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_deg = 35.0f;
};

class CameraPath {
 public:
  CameraPath() = default;
  /// `keys` must be non-empty with strictly increasing times (checked by validate()).
  explicit CameraPath(std::vector<CameraKey> keys) : keys_(std::move(keys)) {}

  const std::vector<CameraKey>& keys() const { return keys_; }
  double duration() const { return keys_.empty() ? 0.0 : keys_.back().time - keys_.front().time; }
  /// The camera at time `t` seconds (clamped to the path), with clip planes fitted to
  /// `bounds`. Positions follow a uniform Catmull-Rom spline through the keys.
  Camera at(double t, const Bounds& bounds) const;
  /// Empty message when the keys are usable.
  std::string validate() const;

 private:
  std::vector<CameraKey> keys_;
};

/// Names of the built-in paths: orbit, zoom-out, dolly, flyover.
const std::vector<std::string>& builtinPathNames();

/// A built-in path of `duration` seconds around `bounds`, starting from the orbit view
/// `start` (`--view`; default azimuth 35°, elevation 20°, the framing distance):
///  - orbit: one turn around the model from start's azimuth, at its elevation and distance;
///  - zoom-out: from start's distance to 16× farther, exponentially (constant speed in
///    image scale), in start's direction;
///  - dolly: from 3× start's distance to 0.6× (close-up) along a straight line;
///  - flyover: low over the model from one side to the other (terrain), looking ahead and
///    down (start is not used).
Result<CameraPath> builtinPath(const std::string& name, const Bounds& bounds, float fov_deg,
                               float aspect, double duration, const OrbitView& start = {});

/// Reads a path file (JSON); errors name the file and the problem.
Result<CameraPath> loadCameraPath(const std::filesystem::path& path);
/// Writes a path file atomically.
Status saveCameraPath(const std::filesystem::path& path, const CameraPath& cam_path);

}  // namespace lodline
