#include "lines/level_lines.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace lodline {

float levelWave(float x) {
  // Period 2 in x, zero at every integer: |((x + 1.5) mod 2) − 1| − 0.5.
  const float t = (x + 1.5f) * 0.5f;
  return std::abs((t - std::floor(t)) * 2.0f - 1.0f) - 0.5f;
}

glm::vec3 lightInModelSpace(const Camera& camera, glm::vec3 light_dir_eye) {
  const glm::vec3 fwd = camera.forward();
  const glm::vec3 right = glm::normalize(glm::cross(fwd, camera.up));
  const glm::vec3 up = glm::cross(right, fwd);
  const glm::vec3 l = light_dir_eye.x * right + light_dir_eye.y * up - light_dir_eye.z * fwd;
  const float len = glm::length(l);
  return len > 0.0f ? l / len : glm::vec3(0.0f, 0.0f, 1.0f);
}

void computeLevelQuantities(const SurfaceFields& f, const LevelSpec& spec, ViewQuantities& out, WorkerPool* pool) {
  const size_t n = f.positions.size();
  auto size = [&](std::vector<float>& v, bool on) {
    if (on) v.resize(n);
    else v.clear();
  };
  const bool iso = spec.isophotes && spec.isophote_spacing > 0.0f && f.normals.size() == n;
  const bool topo = spec.topo && spec.topo_spacing > 0.0f;
  const bool para = spec.parabolic && f.k1.size() == n && f.k2.size() == n;
  size(out.isophote, iso);
  size(out.isophote_test, iso);
  size(out.topo, topo);
  size(out.parabolic, para);
  size(out.parabolic_test, para);
  if (!iso && !topo && !para) return;
  const float inv_iso = iso ? 1.0f / spec.isophote_spacing : 0.0f;
  const float inv_topo = topo ? 1.0f / spec.topo_spacing : 0.0f;
  const float fs = spec.feature_size > 0.0f ? spec.feature_size : 1.0f;
  const glm::vec3 axis = glm::length(spec.topo_axis) > 0.0f ? glm::normalize(spec.topo_axis) : glm::vec3(0, 1, 0);
  auto range = [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      if (iso) {
        const float x = glm::dot(f.normals[v], spec.light) * inv_iso;
        out.isophote[v] = levelWave(x);
        out.isophote_test[v] = x + 0.5f;  // levels k ≥ 0: n·l > −spacing/2
      }
      if (topo) out.topo[v] = levelWave(glm::dot(f.positions[v] - spec.topo_origin, axis) * inv_topo);
      if (para) {
        const float a = f.k1[v] * fs, b = f.k2[v] * fs;
        out.parabolic[v] = a * b;
        out.parabolic_test[v] = std::max(std::abs(a), std::abs(b)) - spec.parabolic_threshold;
      }
    }
  };
  if (pool) pool->forRange(n, 8192, range);
  else range(0, n);
}

}  // namespace lodline
