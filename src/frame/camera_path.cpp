#include "frame/camera_path.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "io/atomic_file.h"
#include "core/printable.h"
#include "io/input_check.h"

namespace lodline {
namespace {

template <class T>
T catmullRom(const T& p0, const T& p1, const T& p2, const T& p3, float t) {
  const float t2 = t * t, t3 = t2 * t;
  return 0.5f * ((2.0f * p1) + (-p0 + p2) * t + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * t2 +
                 (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * t3);
}

// Largest coordinate and time a path may hold: interpolation (sums of a few multiples of
// the keys) then stays finite in float, and frame counts stay far below 2^63.
constexpr double kMaxCoordinate = 1e15;
constexpr double kMaxTime = 1e9;  // seconds

glm::vec3 readVec3(const nlohmann::json& j, const char* key, const std::string& where) {
  const auto& v = j.at(key);
  if (!v.is_array() || v.size() != 3) throw std::runtime_error(where + ": '" + key + "' must be [x, y, z]");
  glm::vec3 out;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number()) throw std::runtime_error(where + ": '" + key + "' must hold numbers");
    // As double first: a value beyond float's range must not be narrowed (undefined).
    const double d = v[i].get<double>();
    if (!(std::abs(d) <= kMaxCoordinate))
      throw std::runtime_error(where + ": '" + key + "' coordinates must be within +-1e15");
    out[i] = static_cast<float>(d);
  }
  return out;
}

// Any unit vector perpendicular to `d` (unit).
glm::vec3 perpendicular(const glm::vec3& d) {
  const glm::vec3 axis = std::abs(d.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  return glm::normalize(glm::cross(glm::cross(d, axis), d));
}

}  // namespace

std::string CameraPath::validate() const {
  if (keys_.empty()) return "the path has no keys";
  for (size_t i = 0; i < keys_.size(); ++i) {
    const CameraKey& k = keys_[i];
    const std::string where = "key " + std::to_string(i);
    if (!std::isfinite(k.time)) return where + ": time is not finite";
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(k.eye[c]) || !std::isfinite(k.target[c]) || !std::isfinite(k.up[c]))
        return where + ": non-finite coordinate";
    if (glm::length(k.eye - k.target) < 1e-12f) return where + ": eye and target coincide";
    if (glm::length(k.up) < 1e-12f) return where + ": up is zero";
    if (glm::length(glm::cross(glm::normalize(k.target - k.eye), glm::normalize(k.up))) < 1e-6f)
      return where + ": up is parallel to the view direction";
    if (!(std::abs(k.time) <= kMaxTime)) return where + ": time must be within +-1e9 seconds";
    if (!(k.fov_deg >= 1.0f && k.fov_deg <= 170.0f)) return where + ": fov must be 1-170 degrees";
    if (i > 0 && !(k.time > keys_[i - 1].time)) return where + ": times must increase";
  }
  return {};
}

Camera CameraPath::at(double t, const Bounds& bounds) const {
  Camera cam;
  if (keys_.empty()) return cam;
  const size_t n = keys_.size();
  size_t i = 0;
  float u = 0.0f;
  if (n > 1) {
    t = std::clamp(t, keys_.front().time, keys_.back().time);
    i = static_cast<size_t>(std::upper_bound(keys_.begin(), keys_.end(), t,
                                             [](double tt, const CameraKey& k) { return tt < k.time; }) -
                            keys_.begin());
    i = std::clamp<size_t>(i, 1, n - 1) - 1;
    u = static_cast<float>((t - keys_[i].time) / (keys_[i + 1].time - keys_[i].time));
  }
  const CameraKey& k1 = keys_[i];
  const CameraKey& k2 = keys_[std::min(i + 1, n - 1)];
  const CameraKey& k0 = keys_[i > 0 ? i - 1 : i];
  const CameraKey& k3 = keys_[std::min(i + 2, n - 1)];
  cam.eye = catmullRom(k0.eye, k1.eye, k2.eye, k3.eye, u);
  cam.target = catmullRom(k0.target, k1.target, k2.target, k3.target, u);
  glm::vec3 up = glm::normalize(k1.up) * (1.0f - u) + glm::normalize(k2.up) * u;
  cam.up = glm::length(up) > 1e-6f ? glm::normalize(up) : glm::vec3(0, 1, 0);
  // Between valid keys the splines may still bring eye onto target, or the view direction
  // onto up: keep the camera defined (the key's direction, a perpendicular up).
  const glm::vec3 key_dir = glm::normalize(k1.target - k1.eye);
  const float scale = std::max({glm::length(cam.eye), glm::length(cam.target), 1.0f});
  if (!(glm::length(cam.target - cam.eye) > 1e-5f * scale)) cam.target = cam.eye + key_dir * (1e-3f * scale);
  const glm::vec3 dir = glm::normalize(cam.target - cam.eye);
  if (!(glm::length(glm::cross(dir, cam.up)) > 1e-4f)) cam.up = perpendicular(dir);
  cam.fov_deg = k1.fov_deg + (k2.fov_deg - k1.fov_deg) * u;
  fitClipPlanes(cam, bounds);
  return cam;
}

const std::vector<std::string>& builtinPathNames() {
  static const std::vector<std::string> names = {"orbit", "zoom-out", "dolly", "flyover"};
  return names;
}

Result<CameraPath> builtinPath(const std::string& name, const Bounds& bounds, float fov_deg,
                               float aspect, double duration, const OrbitView& start) {
  if (!(duration > 0.0 && duration <= kMaxTime))
    return Error::usage("a camera path needs a positive duration of at most 1e9 seconds");
  const Camera framing = orbitCamera(bounds, start, fov_deg, aspect);
  const float az0 = start.azimuth_deg, el0 = start.elevation_deg;
  const float frame_dist = glm::length(framing.eye - framing.target);
  const glm::vec3 c = bounds.center;
  const float r = std::max(bounds.radius, 1e-6f);
  std::vector<CameraKey> keys;
  auto key = [&](double t, glm::vec3 eye, glm::vec3 target) {
    CameraKey k;
    k.time = t;
    k.eye = eye;
    k.target = target;
    k.fov_deg = fov_deg;
    keys.push_back(k);
  };
  auto orbit_dir = [](float az_deg, float el_deg) {
    const float az = glm::radians(az_deg), el = glm::radians(el_deg);
    return glm::vec3(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
  };
  if (name == "orbit") {
    const int n = 48;  // dense keys: the spline stays within 0.01% of the circle
    for (int i = 0; i <= n; ++i)
      key(duration * i / n, c + frame_dist * orbit_dir(az0 + 360.0f * i / n, el0), c);
  } else if (name == "zoom-out") {
    const int n = 32;
    for (int i = 0; i <= n; ++i) {
      const float s = std::pow(16.0f, static_cast<float>(i) / n);
      key(duration * i / n, c + frame_dist * s * orbit_dir(az0, el0), c);
    }
  } else if (name == "dolly") {
    const int n = 16;
    for (int i = 0; i <= n; ++i) {
      const float s = 3.0f + (0.6f - 3.0f) * static_cast<float>(i) / n;
      key(duration * i / n, c + frame_dist * s * orbit_dir(az0, el0), c);
    }
  } else if (name == "flyover") {
    const int n = 16;
    const glm::vec3 height(0.0f, bounds.max.y - c.y + 0.35f * r, 0.0f);
    for (int i = 0; i <= n; ++i) {
      const float s = -1.2f + 2.4f * static_cast<float>(i) / n;
      const glm::vec3 eye = c + height + glm::vec3(0.0f, 0.0f, s * r);
      key(duration * i / n, eye, eye + glm::vec3(0.0f, -0.45f * r, -0.6f * r));
    }
  } else {
    return Error::usage("unknown camera path '" + name + "' (built-in: orbit, zoom-out, dolly, flyover; or a .json file)");
  }
  return CameraPath(std::move(keys));
}

Result<CameraPath> loadCameraPath(const std::filesystem::path& path) {
  if (Status s = checkInputFile(path, "camera path (.json)"); !s) return s.error();
  std::ifstream in(path);
  if (!in) return Error::runtime(path.string() + ": cannot open camera path");
  std::vector<CameraKey> keys;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (!j.is_object() || !j.contains("keys") || !j["keys"].is_array())
      return Error::runtime(path.string() + ": expected an object with a \"keys\" array");
    size_t i = 0;
    for (const auto& k : j["keys"]) {
      const std::string where = path.string() + ": key " + std::to_string(i++);
      if (!k.is_object()) return Error::runtime(where + ": not an object");
      CameraKey key;
      if (!k.contains("time") || !k["time"].is_number()) return Error::runtime(where + ": missing numeric \"time\"");
      key.time = k["time"].get<double>();
      if (!k.contains("eye") || !k.contains("target")) return Error::runtime(where + ": needs \"eye\" and \"target\"");
      const std::string key_name = "key " + std::to_string(i - 1);
      key.eye = readVec3(k, "eye", key_name);
      key.target = readVec3(k, "target", key_name);
      if (k.contains("up")) key.up = readVec3(k, "up", key_name);
      if (k.contains("fov")) {
        if (!k["fov"].is_number()) return Error::runtime(where + ": \"fov\" must be a number");
        const double fov = k["fov"].get<double>();
        if (!(fov >= 1.0 && fov <= 170.0)) return Error::runtime(where + ": fov must be 1-170 degrees");
        key.fov_deg = static_cast<float>(fov);
      }
      keys.push_back(key);
    }
  } catch (const std::exception& e) {
    // nlohmann's messages quote the file's bytes: keep the line printable.
    return Error::runtime(path.string() + ": invalid camera path: " + printableText(e.what()));
  }
  CameraPath p(std::move(keys));
  if (const std::string why = p.validate(); !why.empty()) return Error::runtime(path.string() + ": " + why);
  return p;
}

Status saveCameraPath(const std::filesystem::path& path, const CameraPath& cam_path) {
  nlohmann::json keys = nlohmann::json::array();
  for (const CameraKey& k : cam_path.keys())
    keys.push_back({{"time", k.time},
                    {"eye", {k.eye.x, k.eye.y, k.eye.z}},
                    {"target", {k.target.x, k.target.y, k.target.z}},
                    {"up", {k.up.x, k.up.y, k.up.z}},
                    {"fov", k.fov_deg}});
  const std::string text = nlohmann::json{{"keys", keys}}.dump(1) + "\n";
  return writeFileAtomically(path, [&](std::ostream& out) -> Status {
    out << text;
    return {};
  });
}

}  // namespace lodline
