#include "frame/line_drawing.h"

#include <cstring>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "core/timer.h"
#include "lines/level_lines.h"
#include "lines/ridge_lines.h"

namespace lodline {

LineDrawing::LineDrawing(TriMesh mesh, const LineParams& params, const ShapeParams& shape_params,
                         std::shared_ptr<WorkerPool> pool, FullMesh use, std::span<const uint32_t> stored_to_drawn)
    : pool_(pool ? std::move(pool) : std::make_shared<WorkerPool>(shape_params.threads)),
      mesh_(std::move(mesh)),
      params_(params),
      shape_(shape_params) {
  shape_.setWorkerPool(pool_.get());
  scratch_.pool = pool_.get();
  bounds_ = computeBounds(mesh_.positions);
  if (mesh_.face_materials.size() == mesh_.faces.size()) full_face_materials_ = mesh_.face_materials;
  else mesh_.face_materials.clear();
  Stopwatch sw;
  if (use == FullMesh::kDrawn) {
    shape_.compute(mesh_);
    feature_size_ = computeFeatureSize(shape_.k1(), shape_.k2(), bounds_.radius, {}, stored_to_drawn);
    computeFullCreaseDots(shape_.adjacency(), shape_.faceNormals());
    closed_outward_ = isClosedOutward(mesh_, shape_.adjacency());
  } else {
    MeshAdjacency adj;
    buildAdjacency(mesh_, adj);
    feature_size_ = sampledFeatureSize(mesh_, adj, bounds_.radius, shape_params);
    std::vector<glm::vec3> face_normals(mesh_.faces.size(), glm::vec3(0.0f));
    for (size_t f = 0; f < mesh_.faces.size(); ++f)
      if (adj.face_valid[f]) {
        const auto& c = mesh_.faces[f];
        face_normals[f] = faceNormalOf(mesh_.positions[c[0]], mesh_.positions[c[1]], mesh_.positions[c[2]]).n;
      }
    computeFullCreaseDots(adj, face_normals);
    closed_outward_ = isClosedOutward(mesh_, adj);
  }
  updateFullCreaseVertices();
  timings_.shape = sw.lap();
}

// Per vertex of the full-detail mesh, the smallest n1·n2 over its edges with two faces (−2
// for marked and non-manifold edges, which are always creases): the vertex lies on a crease
// of angle a exactly where this is below cos(a), the extractor's own test.
void LineDrawing::computeFullCreaseDots(const MeshAdjacency& adj, std::span<const glm::vec3> face_normals) {
  full_min_dot_.assign(mesh_.positions.size(), 2.0f);
  auto lower = [&](uint32_t e, float d) {
    for (uint32_t v : adj.edges[e]) full_min_dot_[v] = std::min(full_min_dot_[v], d);
  };
  std::vector<uint32_t> marked_edge_ids;  // marked and non-manifold edges
  for (const EdgeKey& k : mesh_.marked_edges)
    if (const uint32_t e = adj.findEdge(k[0], k[1]); e != kNoIndex) marked_edge_ids.push_back(e);
  for (uint32_t e = 0; e < adj.edges.size(); ++e) {
    const uint32_t count = adj.edge_face_count[e];
    if (count > 2) {
      marked_edge_ids.push_back(e);
    } else if (count == 2) {
      const glm::vec3& n1 = face_normals[adj.edge_faces[e][0]];
      const glm::vec3& n2 = face_normals[adj.edge_faces[e][1]];
      if (glm::dot(n1, n1) == 0.0f || glm::dot(n2, n2) == 0.0f) continue;
      lower(e, glm::dot(n1, n2));
    }
  }
  full_min_dot_marked_ = full_min_dot_;
  for (uint32_t e : marked_edge_ids) {
    for (uint32_t v : adj.edges[e]) full_min_dot_marked_[v] = -2.0f;
  }
}

void LineDrawing::updateMesh(std::span<const glm::vec3> positions,
                             std::span<const std::array<uint32_t, 3>> faces,
                             std::span<const uint32_t> changed, std::span<const uint32_t> face_ids) {
  faces_in_.assign(faces.begin(), faces.end());
  updateMesh(positions, faces_in_, changed, face_ids);
}

void LineDrawing::updateMesh(std::span<const glm::vec3> positions,
                             std::vector<std::array<uint32_t, 3>>& faces,
                             std::span<const uint32_t> changed, std::span<const uint32_t> face_ids) {
  const WorkerPool::Awake awake(pool_.get());
  Stopwatch sw;
  // The shape quantities depend on the positions and the faces alone, and update() finds the
  // face slots that changed by itself (and recomputes around their vertices, old and new).
  // So of the changed vertices only those whose position changed need telling: a split that
  // was undone, or a neighbour whose ring gained faces, keeps its position (docs/performance.md,
  // "Where the shape stage's time goes").
  moved_.clear();
  const size_t old_count = mesh_.positions.size();
  for (uint32_t v : changed) {
    if (v >= positions.size()) continue;
    if (v >= old_count || std::memcmp(&positions[v], &mesh_.positions[v], sizeof(glm::vec3)) != 0)
      moved_.push_back(v);
  }
  mesh_.positions.assign(positions.begin(), positions.end());
  mesh_.faces.swap(faces);
  mesh_.marked_edges.clear();  // marked edges refer to full-detail vertex ids
  mesh_.face_materials.clear();
  if (!full_face_materials_.empty() && face_ids.size() == mesh_.faces.size()) {
    mesh_.face_materials.resize(face_ids.size());
    for (size_t i = 0; i < face_ids.size(); ++i) {
      if (face_ids[i] >= full_face_materials_.size()) {  // not a full-detail face: no materials
        mesh_.face_materials.clear();
        break;
      }
      mesh_.face_materials[i] = full_face_materials_[face_ids[i]];
    }
  }
  shape_.update(mesh_, moved_);
  timings_.shape = sw.lap();
}

void LineDrawing::updateFullCreaseVertices() {
  const float cos_limit = std::cos(params_.crease_angle_deg * std::numbers::pi_v<float> / 180.0f);
  const std::vector<float>& min_dot = params_.marked_edges ? full_min_dot_marked_ : full_min_dot_;
  full_crease_vertices_.resize(min_dot.size());
  for (size_t v = 0; v < min_dot.size(); ++v) full_crease_vertices_[v] = min_dot[v] < cos_limit;
  crease_angle_ = params_.crease_angle_deg;
  marked_ = params_.marked_edges;
  ++crease_version_;
}

void LineDrawing::setParams(const LineParams& params) {
  params_ = params;
  if (params_.crease_angle_deg != crease_angle_ || params_.marked_edges != marked_) updateFullCreaseVertices();
}

std::span<const glm::vec3> LineDrawing::normals() const {
  return shading_normals_.size() == mesh_.positions.size() ? shading_normals_ : shape_.normals();
}

void LineDrawing::update(const Camera& camera, const std::array<bool, kLineKindCount>& enabled, float smoothing,
                         int image_height, float dt) {
  LineParams p = params_;
  p.contours = p.contours && enabled[static_cast<int>(LineKind::kContour)];
  p.suggestive = p.suggestive && enabled[static_cast<int>(LineKind::kSuggestive)];
  p.creases = p.creases && enabled[static_cast<int>(LineKind::kCrease)];
  p.marked_edges = p.marked_edges && p.creases;
  p.boundaries = p.boundaries && enabled[static_cast<int>(LineKind::kBoundary)];
  // The level-set kinds are drawn when the style asks for them (lines/level_lines.h).
  p.isophotes = enabled[static_cast<int>(LineKind::kIsophote)];
  p.topo = enabled[static_cast<int>(LineKind::kTopo)];
  p.parabolic = enabled[static_cast<int>(LineKind::kParabolic)];
  p.ridges = enabled[static_cast<int>(LineKind::kRidge)];
  p.valleys = enabled[static_cast<int>(LineKind::kValley)];
  p.suggestive_highlights = enabled[static_cast<int>(LineKind::kSuggestiveHighlight)];
  p.apparent_ridges = enabled[static_cast<int>(LineKind::kApparentRidge)];
  p.principal_highlights = enabled[static_cast<int>(LineKind::kPrincipalHighlight)];
  p.materials = enabled[static_cast<int>(LineKind::kMaterial)];
  const bool dw = p.suggestive || p.suggestive_highlights;  // both test Dw kr on kr = 0

  const WorkerPool::Awake awake(pool_.get());
  Stopwatch sw;
  SurfaceFields fields = shape_.fields(mesh_);
  const bool lazy = dw && shape_.params().derivatives && shape_.params().lazy_derivatives;
  if (!dw || lazy) fields.dcurv = {};
  const bool smooth = smoothing < 1.0f;
  if (smooth) {
    fields.normals = smoother_.blendNormals(shape_.normals(), smoothing);
    shading_normals_ = fields.normals;
  } else {
    smoother_.reset();
    shading_normals_ = {};
  }
  // The other kinds' curvatures, smoothed over time like kr (docs/lines.md); kr itself is
  // computed from the raw ones and smoothed on its own.
  SurfaceFields curv = fields;
  const bool curvature_kinds = p.parabolic || p.ridges || p.valleys || p.principal_highlights || p.apparent_ridges;
  if (smooth && curvature_kinds) {
    curv.k1 = smoother_.blendScalar(TemporalSmoother::kK1, shape_.k1(), smoothing);
    curv.k2 = smoother_.blendScalar(TemporalSmoother::kK2, shape_.k2(), smoothing);
  } else {  // a channel not blended this frame has no history when its kind comes back
    smoother_.resetChannel(TemporalSmoother::kK1);
    smoother_.resetChannel(TemporalSmoother::kK2);
  }
  if (!smooth || !p.apparent_ridges) {
    smoother_.resetChannel(TemporalSmoother::kQ1);
    smoother_.resetChannel(TemporalSmoother::kDt1q1);
  }
  // A change of estimator starts the derivatives' history afresh.
  if (!smooth || !(p.ridges || p.valleys) || p.ridge_estimator != smoothed_ridge_estimator_) {
    smoothed_ridge_estimator_ = p.ridge_estimator;
    smoother_.resetChannel(TemporalSmoother::kC111);
    smoother_.resetChannel(TemporalSmoother::kC222);
  }
  const float fs = feature_size_ > 0.0f && std::isfinite(feature_size_) ? feature_size_ : 1.0f;
  const float sc_threshold = p.suggestive_threshold / (fs * fs);
  computeViewQuantities(fields, ViewSpec::fromCamera(camera), sc_threshold, view_, pool_.get());
  if (smooth) smoother_.blendView(view_, smoothing, sc_threshold);
  if (lazy) {
    // Dw kr where a suggestive contour can be: at the corners of every face that the kr
    // zero set crosses and with a corner that passes the n·v gate — the only faces whose test
    // extractZeroSets() uses (its per-vertex codes read the others' stale values, unused).
    const MeshAdjacency& adj = shape_.adjacency();
    const size_t nv = mesh_.positions.size();
    needed_mark_.resize(nv, 0);
    const std::span<const float> kr = view_.kr, ndotv = view_.ndotv;
    const float gate = p.suggestive_min_ndotv;
    pool_->forRange(mesh_.faces.size(), 4096, [&](size_t begin, size_t end) {
      for (size_t f = begin; f < end; ++f) {
        if (!adj.face_valid[f]) continue;
        const auto& t = mesh_.faces[f];
        const bool s0 = kr[t[0]] < 0.0f, s1 = kr[t[1]] < 0.0f, s2 = kr[t[2]] < 0.0f;
        if (s0 == s1 && s1 == s2) continue;
        if (ndotv[t[0]] < gate && ndotv[t[1]] < gate && ndotv[t[2]] < gate) continue;
        for (uint32_t v : t) std::atomic_ref<uint8_t>(needed_mark_[v]).store(1, std::memory_order_relaxed);
      }
    });
    needed_.clear();  // in vertex order, which the gathers below prefer
    uint32_t v = 0;
    for (; v + 8 <= nv; v += 8) {  // few are marked: eight unmarked ones skipped at a time
      uint64_t word;
      std::memcpy(&word, &needed_mark_[v], sizeof(word));
      if (word == 0) continue;
      for (uint32_t u = v; u < v + 8; ++u)
        if (needed_mark_[u]) {
          needed_.push_back(u);
          needed_mark_[u] = 0;
        }
    }
    for (; v < nv; ++v)
      if (needed_mark_[v]) {
        needed_.push_back(v);
        needed_mark_[v] = 0;
      }
    shape_.ensureDerivatives(mesh_, needed_);
    fields.dcurv = shape_.dcurv();
    computeSuggestiveQuantities(fields, ViewSpec::fromCamera(camera), sc_threshold, needed_, view_);
    if (smooth) smoother_.blendSuggestive(view_, needed_, smoothing, sc_threshold);
  }
  if (p.suggestive_highlights) suggestiveHighlightTest(sc_threshold, view_);
  else view_.sh_num.clear();
  // Suggestive contours that slide fast are faded (DeCarlo et al. 2004 §4): their speed
  // comes from the change of the smoothed kr, so only in smoothed sequences.
  const bool motion_fade = smooth && p.suggestive && dt > 0.0f && image_height > 0 &&
                           p.suggestive_motion_fade_end > 0.0f;
  if (motion_fade)
    suggestiveMotionGain(mesh_.positions, view_, smoother_.krChange(), camera, image_height, dt,
                         p.suggestive_motion_fade_start, p.suggestive_motion_fade_end, motion_gain_, pool_.get());
  {  // with none of the level kinds on, this only clears their arrays
    LevelSpec level;
    level.isophotes = p.isophotes;
    level.light = lightInModelSpace(camera, p.light_dir_eye);
    level.isophote_spacing = p.isophote_spacing;
    level.topo = p.topo;
    level.topo_origin = bounds_.center;
    level.topo_axis = p.topo_axis;
    level.topo_spacing = p.topo_spacing * glm::length(bounds_.max - bounds_.min);
    level.parabolic = p.parabolic;
    level.feature_size = fs;
    level.parabolic_threshold = p.parabolic_threshold;
    computeLevelQuantities(curv, level, view_, pool_.get());
  }
  timings_.view = sw.lap();
  extractLines(mesh_, shape_.adjacency(), shape_.faceNormals(), view_, p, fs, scratch_, segments_, crease_mask_,
               motion_fade ? std::span<const float>(motion_gain_) : std::span<const float>());
  if (p.ridges || p.valleys) {  // lines/ridge_lines.h: k1, k2 and C smoothed in sequences
    const RidgeSpec ridge{p.ridges, p.valleys, p.ridge_threshold, fs};
    SurfaceFields rf = curv;
    const bool fit = p.ridge_estimator == RidgeEstimator::kFit;
    const bool lazy_c = fit || shape_.params().lazy_derivatives;
    if (lazy_c)  // derivatives only where a ridge can be (chosen on the tensors' curvatures)
      ridgeCandidateVertices(mesh_.faces, shape_.adjacency(), rf, ridge, scratch_.vertex_code, needed_mark_,
                             ridge_needed_);
    if (fit) {
      // Fitted jets (shape/jet_fit.h): curvatures, directions and C at the candidates.
      rf = jet_fields_.fit(rf, mesh_.faces, shape_.adjacency(), ridge_needed_, JetFitParams{}, pool_.get());
    } else {
      rf.dcurv = shape_.dcurv();  // curv's is cleared unless the suggestive kinds use it
      if (lazy_c) {
        shape_.ensureDerivatives(mesh_, ridge_needed_);
        rf.dcurv = shape_.dcurv();
      }
    }
    const bool smooth_c = smooth && rf.dcurv.size() == rf.pdir1.size();
    if (smooth_c) {
      // The derivatives along the principal directions, C(e1,e1,e1) for ridges and
      // C(e2,e2,e2) for valleys, smoothed with their directions (a sign flip of e flips C):
      // the zero sets follow the smoothed values, like the suggestive contours' Dw kr.
      // Lazily computed values are known only at the candidates; elsewhere history is dropped.
      const size_t nv = rf.dcurv.size();
      ridge_dir1_.assign(rf.pdir1.begin(), rf.pdir1.end());
      ridge_dir2_.assign(rf.pdir2.begin(), rf.pdir2.end());
      ridge_c1_.resize(nv);
      ridge_c2_.resize(nv);
      for (size_t v = 0; v < nv; ++v) {
        ridge_c1_[v] = rf.dcurv[v][0];
        ridge_c2_[v] = rf.dcurv[v][3];
      }
      ridge_valid_.clear();
      if (lazy_c) {
        ridge_valid_.assign(nv, 0);
        for (uint32_t v : ridge_needed_)
          if (v < nv && (fit || shape_.derivativeValid(v))) ridge_valid_[v] = 1;
      }
      smoother_.blendDirected(TemporalSmoother::kC111, ridge_dir1_, ridge_c1_, smoothing, ridge_valid_);
      smoother_.blendDirected(TemporalSmoother::kC222, ridge_dir2_, ridge_c2_, smoothing, ridge_valid_);
      rf.pdir1 = ridge_dir1_;
      rf.pdir2 = ridge_dir2_;
    }
    extractRidges(mesh_.positions, mesh_.faces, shape_.adjacency(), rf, ridge, scratch_, segments_,
                  smooth_c ? std::span<const float>(ridge_c1_) : std::span<const float>(),
                  smooth_c ? std::span<const float>(ridge_c2_) : std::span<const float>());
  }
  if (p.apparent_ridges) {  // per view, from the normals and k1, k2 (smoothed in sequences)
    computeApparentRidgeQuantities(mesh_.faces, shape_.adjacency(), curv, ViewSpec::fromCamera(camera), apparent_,
                                   pool_.get());
    if (smooth) {
      // Smoothed in bounded forms: q1 grows without bound towards the contour, and a vertex
      // that was near it would keep a large average for many frames. q1 is capped at twice
      // the threshold (where the fade saturates: the same alpha), Dt1 q1 compressed as
      // d/(1 + |d|/D) with D = threshold/fs² (same sign, same zero set where |d| << D).
      const float q_cap = 2.0f * p.apparent_ridge_threshold / fs;
      const float d_scale = p.apparent_ridge_threshold / (fs * fs);
      for (float& q : apparent_.q1) q = std::min(q, q_cap);
      for (float& d : apparent_.dt1q1) d = d / (1.0f + std::abs(d) / d_scale);
      const auto q1 = smoother_.blendScalar(TemporalSmoother::kQ1, apparent_.q1, smoothing);
      std::copy(q1.begin(), q1.end(), apparent_.q1.begin());
      smoother_.blendDirected(TemporalSmoother::kDt1q1, apparent_.t1, apparent_.dt1q1, smoothing);
    }
    extractApparentRidges(mesh_.positions, mesh_.faces, shape_.adjacency(), apparent_, p.apparent_ridge_threshold, fs,
                          segments_);
  }
  if (p.principal_highlights) {
    computePrincipalHighlightQuantities(curv, ViewSpec::fromCamera(camera), fs, principal_, pool_.get());
    extractPrincipalHighlights(mesh_.positions, mesh_.faces, shape_.adjacency(), principal_,
                               p.principal_highlight_threshold, segments_);
  }
  timings_.extract = sw.lap();
  chainStrokes(segments_, strokes_, chain_scratch_);
  timings_.chain = sw.lap();
  // The mesh's own silhouette (present/ completes the outline with it).
  if (p.contours && p.complete_outline) {
    extractMeshSilhouette(mesh_, shape_.adjacency(), shape_.faceNormals(), ViewSpec::fromCamera(camera), scratch_,
                          silhouette_);
    chainStrokes(silhouette_, silhouette_strokes_, chain_scratch_);
  } else {
    silhouette_.clear();
    silhouette_strokes_.clear();
  }
  timings_.silhouette = sw.lap();
}

void LineDrawing::dropShortStrokes(LineKind kind, float min_px, const Camera& camera, int width, int height) {
  if (!(min_px > 0.0f) || width <= 0 || height <= 0) return;
  if (std::find(strokes_.kinds.begin(), strokes_.kinds.end(), kind) == strokes_.kinds.end()) return;
  Stopwatch sw;  // counted with the chaining: both decide which strokes there are
  const PixelProjector proj(camera, width, height);
  keepStrokes(strokes_, [&](size_t s) {
    if (strokes_.kinds[s] != kind) return true;
    const uint32_t begin = strokes_.offsets[s], end = strokes_.offsets[s + 1];
    float length = 0.0f, z = 0.0f;
    glm::vec2 prev(0.0f), cur(0.0f);
    bool have_prev = false;
    for (uint32_t i = begin; i < end && length < min_px; ++i) {
      const bool ok = proj.project(strokes_.points[i], cur, z);
      if (ok && have_prev) length += glm::length(cur - prev);
      prev = cur;
      have_prev = ok;
    }
    return length >= min_px;
  });
  timings_.chain += sw.elapsed();
}

}  // namespace lodline
