#include "present/stroke_ids.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace lodline {
namespace {

struct Claim {
  uint32_t votes;
  uint32_t object;
  uint32_t run;
  uint64_t id;
};

}  // namespace

void StrokeIdTracker::update(std::span<const StrokeRuns> visible, const Camera& camera, int width, int height) {
  const PixelProjector proj(camera, width, height);
  // The previous frame's samples where this camera sees them.
  owner_.assign(static_cast<size_t>(std::max(width, 0)) * static_cast<size_t>(std::max(height, 0)), 0);
  for (size_t i = 0; i < prev_points_.size(); ++i) {
    glm::vec2 px;
    float z;
    if (!proj.project(prev_points_[i], px, z)) continue;
    const int x = static_cast<int>(std::floor(px.x)), y = static_cast<int>(std::floor(px.y));
    if (x >= 0 && y >= 0 && x < width && y < height) owner_[static_cast<size_t>(y) * width + x] = prev_ids_[i];
  }
  // Each run samples itself about once per pixel; the samples vote for the ids near them.
  ids_.assign(visible.size(), {});
  points_.clear();
  std::vector<Claim> claims;
  std::vector<std::pair<uint64_t, uint32_t>> votes;  // id, count (a handful per run)
  std::vector<uint64_t> near;                        // distinct ids near one sample
  std::vector<size_t> run_first(1, 0);               // per run (flattened): first sample in points_
  std::vector<std::pair<uint32_t, uint32_t>> flat;   // object, run
  const int r = std::max(params_.radius_px, 0);
  for (size_t o = 0; o < visible.size(); ++o) {
    const StrokeRuns& runs = visible[o];
    ids_[o].assign(runs.strokeCount(), 0);
    for (size_t k = 0; k < runs.strokeCount(); ++k) {
      votes.clear();
      uint32_t samples = 0;
      for (uint32_t i = runs.offsets[k]; i < runs.offsets[k + 1]; ++i) {
        const bool last = i + 1 == runs.offsets[k + 1];
        const int steps = last ? 1
                               : std::clamp(static_cast<int>(std::ceil(glm::length(runs.points[i + 1] - runs.points[i]))),
                                            1, 4096);
        for (int s = 0; s < steps; ++s) {
          const float t = static_cast<float>(s) / static_cast<float>(steps);
          const glm::vec2 px = last ? runs.points[i] : runs.points[i] + t * (runs.points[i + 1] - runs.points[i]);
          points_.push_back(last ? runs.positions[i] : runs.positions[i] + t * (runs.positions[i + 1] - runs.positions[i]));
          ++samples;
          const int x = static_cast<int>(std::floor(px.x)), y = static_cast<int>(std::floor(px.y));
          // One vote per sample for each distinct id near it.
          near.clear();
          for (int yy = std::max(0, y - r); yy <= std::min(height - 1, y + r); ++yy)
            for (int xx = std::max(0, x - r); xx <= std::min(width - 1, x + r); ++xx) {
              const uint64_t id = owner_[static_cast<size_t>(yy) * width + xx];
              if (id != 0 && std::find(near.begin(), near.end(), id) == near.end()) near.push_back(id);
            }
          for (uint64_t id : near) {
            auto it = std::find_if(votes.begin(), votes.end(), [&](const auto& v) { return v.first == id; });
            if (it == votes.end()) votes.push_back({id, 1});
            else ++it->second;
          }
        }
      }
      run_first.push_back(points_.size());
      flat.push_back({static_cast<uint32_t>(o), static_cast<uint32_t>(k)});
      const auto best = std::max_element(votes.begin(), votes.end(),
                                         [](const auto& a, const auto& b) { return a.second < b.second; });
      if (best != votes.end() && static_cast<float>(best->second) >= params_.min_share * static_cast<float>(samples))
        claims.push_back({best->second, static_cast<uint32_t>(o), static_cast<uint32_t>(k), best->first});
    }
  }
  // The strongest claim on an id keeps it.
  std::stable_sort(claims.begin(), claims.end(), [](const Claim& a, const Claim& b) { return a.votes > b.votes; });
  std::vector<uint64_t> taken;
  for (const Claim& c : claims) {
    if (std::find(taken.begin(), taken.end(), c.id) != taken.end()) continue;
    taken.push_back(c.id);
    ids_[c.object][c.run] = c.id;
  }
  prev_ids_.clear();
  for (size_t f = 0; f < flat.size(); ++f) {
    uint64_t& id = ids_[flat[f].first][flat[f].second];
    if (id == 0) id = next_id_++;
    prev_ids_.insert(prev_ids_.end(), run_first[f + 1] - run_first[f], id);
  }
  prev_points_.swap(points_);
}

}  // namespace lodline
