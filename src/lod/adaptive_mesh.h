// View-dependent selective refinement of a progressive mesh with image-space area control and
// real-time geomorphs.
//
//   Hoppe 1997, "View-dependent refinement of progressive meshes", §4-5 (legal vsplit/ecol,
//     force_vsplit through a stack, the adapt loop over the active vertices, bounding spheres
//     and normal cones for view-frustum and back-face tests).
//   Hoppe 1998, "Efficient implementation of progressive meshes", §5 (active vertices and faces
//     in flat arrays with free lists).
//   Jeong, Ni, Lee, Markosian 2005, "Detail control in line drawings of 3D meshes", §3.1 (the
//     criterion: mean image-space area of the active faces around a vertex, split above
//     t_s·T, collapse below t_c·T; varying T) and §3.2 (real-time geomorphs).
//
// Typical frame loop:
//
//   AdaptiveMesh lod(pm);                      // starts at the base mesh
//   DetailParams detail;                       // T = 16 px², t_c = 0.7, t_s = 1.42, ...
//   for (;;) {
//     if (Status s = lod.setView(camera, width, height, detail); !s.ok()) ...;
//     lod.adapt(dt_seconds);                   // refine/coarsen + advance geomorphs
//     const LodChanges& ch = lod.changes();    // what the shape stage must update
//     lod.positions(); lod.exportFaces(faces); // draw (slot-indexed arrays)
//   }
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/camera.h"
#include "core/huge_pages.h"
#include "core/mesh.h"
#include "core/result.h"
#include "core/timer.h"
#include "core/worker_pool.h"
#include "lod/face_areas.h"
#include "pm/progressive_mesh.h"

namespace lodline {

/// A grayscale image that scales the target area T per pixel (Jeong §3.1, "detail map").
/// Row-major, top row first, `width × height` values; sampled bilinearly in normalised image
/// coordinates, so its size need not match the rendered image.
struct DetailMap {
  int width = 0;
  int height = 0;
  std::vector<float> values;  ///< width·height factors (1: T unchanged, 4: 4× larger faces)
};

/// How much detail to show. Filled identically by CLI, scene file and viewer.
struct DetailParams {
  /// Target image-space triangle area T, px². 16 px² (edges of ~6 px) keeps contours and
  /// suggestive contours smooth at 1280x720 while a model filling the image needs only
  /// ~50-70k active faces.
  float target_area = 16.0f;
  float t_c = 0.7f;             ///< collapse when the mean area falls below t_c·T (Jeong §3.1)
  float t_s = 1.42f;            ///< split when it exceeds t_s·T (needs 2·t_c < t_s)
  float object_factor = 1.0f;   ///< per-object factor on T (e.g. 3 for a background object)
  /// Optional detail map (null: none). The value at a vertex's pixel multiplies T.
  std::shared_ptr<const DetailMap> detail_map;
  float min_map_value = 0.0625f;  ///< detail-map values are clamped to at least this
  /// Depth-dependent T (the paper's terrain figure): T·(d/d_focus)^depth_falloff, d the
  /// distance to the eye, d_focus the eye-target distance, ratio clamped to ≥ 0.25. 0: off.
  float depth_falloff = 0.0f;
  /// Foveation: T·((90°/(90°−q))²)^foveation, q the angle between the vertex and the gaze
  /// point focus_px (q clamped to 80°). 0: off; 1: Pan et al.'s factor.
  float foveation = 0.0f;
  glm::vec2 focus_px{-1.0f, -1.0f};  ///< gaze point, pixels; negative: the image centre
  bool geomorphs = true;       ///< Jeong §3.2 geomorphs; false: changes show at once
  float morph_time = 0.5f;     ///< seconds a split's children take to morph out
  float coarsen_time_factor = 0.5f;  ///< collapse morphs take morph_time × this (bounds lag)
  /// Morphs run up to this much faster when the area is far from its threshold: splits at
  /// speed ∝ (mean / t_s·T), collapses ∝ (t_c·T / mean)²; a morph shorter than the frame is
  /// executed at once.
  float max_morph_speedup = 16.0f;
  bool cull = true;            ///< coarsen freely outside the frustum and where back-facing
  /// Budget of splits+collapses per adapt() call (0: unlimited). Checked before each vertex,
  /// so a forced split chain may overshoot it a little; the rest waits for later frames.
  uint32_t max_operations = 0;
  /// Time budget of one adapt() call, ms (0: none). Hoppe 1997 §5 amortises the traversal
  /// of the active vertices over frames: when the budget (or max_operations) is spent the
  /// evaluation stops, and the next frame resumes at the vertex where it stopped, so every
  /// vertex is visited within a few frames however the work is cut: a frame evaluates at
  /// least an eighth of the active vertices, so all within 8 frames. Checked every 32
  /// vertices; the face areas (step 1 of adapt) and the geomorphs always run in full.
  float max_adapt_ms = 0.0f;
  /// Suggestive contours whose whole stroke is shorter on screen than this × √T px (T with
  /// object_factor; the stroke projected whole, visible or not) are not drawn: a zero crossing
  /// that spans less than a face of the adapted mesh is detail below the chosen scale, and
  /// such strokes were most of the specks left under detail control
  /// (docs/temporal-coherence.md, "Suggestive contours below the scale"). Default 0.75 (3 px
  /// at T = 16, the length of a speck); 0: all are drawn. Full detail draws all.
  float min_suggestive_length = 0.75f;
};

/// Cheap per-frame statistics (exposed as "lod" in --stats).
struct LodStats {
  uint32_t active_vertices = 0;
  uint32_t active_faces = 0;
  uint32_t visible_faces = 0;  ///< active faces in the frustum and facing the camera
  uint32_t splits = 0;         ///< this frame
  uint32_t collapses = 0;      ///< this frame (executed; pending morphs are not counted)
  uint32_t morphing = 0;       ///< vertices in a geomorph after this frame
  uint32_t pending_collapses = 0;  ///< collapses morphing towards their parent
  /// Fraction of visible active faces whose image area lies in [t_c·T/2, 2·t_s·T] (T with
  /// all modifiers at the face). Measured on the mesh that entered this adapt() call (the
  /// mesh drawn last frame) under the current view; see measureBand() for the current one.
  float band_fraction = 0.0f;
  /// As band_fraction, counting as in the band the faces outside it only because the
  /// progressive mesh ends there: larger than the band with every corner at full detail
  /// (a leaf), or smaller with every corner in the base mesh (a root). What the adaptation can
  /// be held to where the model itself is too coarse or too fine for the view.
  float band_or_limit_fraction = 0.0f;
  float target_area = 0.0f;    ///< T·object_factor used this frame, px²
  uint32_t folds = 0;          ///< this frame's collapses that turned a sub-pixel face over
  uint32_t fold_repairs = 0;   ///< folded faces grown past that size, refined this frame
  uint32_t folded_faces = 0;   ///< faces still listed as turned over after this frame (sub-pixel, or being refined back)
  bool slots_ordered = false;  ///< this frame renumbered the slots (orderForLocality())
};

/// What changed in the last adapt() call, for incremental downstream stages. Slot indices
/// refer to positions()/slotVertices(). Each slot appears at most once per list.
struct LodChanges {
  std::vector<uint32_t> split;      ///< PM nodes that were split (parents)
  std::vector<uint32_t> collapsed;  ///< PM nodes that became active by a collapse (parents)
  std::vector<uint32_t> moved;      ///< slots whose displayed position changed by a morph
  /// Slots whose vertex, incident faces or displayed position changed (a superset of
  /// `moved`); may hold slots that are now free. Consumers expand this to the k-ring they
  /// need (normals: 1-ring, curvature: 2-ring).
  std::vector<uint32_t> dirty;
  bool everything = false;          ///< set after fullyRefine/fullyCoarsen: recompute all
};

/// The selectively refined mesh. Holds a reference to `pm`, which must outlive it.
/// Memory is allocated in the constructor (about 180 bytes per PM node, e.g. 240 MB for a
/// 1.3M-face model); adapt() allocates nothing after the first frames.
class AdaptiveMesh {
 public:
  explicit AdaptiveMesh(const ProgressiveMesh& pm);

  /// Runs the per-face pass of adapt() on `pool`'s threads (not owned; must outlive this
  /// mesh; null: on the caller's thread). The result does not depend on it.
  void setWorkerPool(WorkerPool* pool) { pool_ = pool; }

  /// Sets camera, image size (px) and detail parameters for the next adapt(). Errors: image
  /// size ≤ 0, T ≤ 0, t_c/t_s not 0 < 2·t_c < t_s, a detail map whose values are not
  /// width·height finite numbers ≥ 0.
  Status setView(const Camera& camera, int width, int height, const DetailParams& params);

  /// One frame: evaluates every active vertex (split above t_s·T, collapse below t_c·T, forced
  /// splits of ancestors as needed), starts/ends geomorphs and advances them by `dt_seconds`.
  void adapt(float dt_seconds);

  /// Refines to the input mesh / coarsens to the base mesh (no geomorphs).
  void fullyRefine();
  void fullyCoarsen();

  /// Renumbers the active vertices' slots along a Morton curve through the model's bounds and
  /// sorts the active faces by their lowest corner slot, so that neighbours lie near each
  /// other in the slot-indexed arrays; adds every slot to changes().dirty (what follows a
  /// vertex over frames follows its node, as across splits and collapses). The mesh, its
  /// displayed positions and its geomorphs are unchanged: only the numbering, and later
  /// frames adapt as they would have without it (the order of evaluation keeps each vertex's
  /// place). adapt() runs it before its evaluation once a quarter of at least 4096 active
  /// vertices have taken new slots since the last time (docs/design.md §4).
  void orderForLocality();

  /// A check of the evaluation's shortcut: when on, every pass evaluates every active vertex,
  /// including those it marked as having nothing to do (docs/performance.md, "Adapt at
  /// T = 7"). The adapted mesh is the same either way; only the time differs.
  void setEvaluateEveryVertex(bool on) { evaluate_every_vertex_ = on; }
  /// With setEvaluateEveryVertex(true): how many vertices, marked as having nothing to do
  /// and untouched since, did something when evaluated (an operation, or a collapse morph
  /// started or cancelled). The vertices a skipping pass would have skipped wrongly: 0.
  uint64_t idleMispredictions() const { return idle_mispredictions_; }

  // ---- output (slot-indexed; a slot keeps its index while its vertex stays active) ----
  /// Displayed (morphed) position per slot, size slotCount(); free slots hold stale values.
  std::span<const glm::vec3> positions() const { return {disp_.data(), slot_count_}; }
  /// PM node per slot, kPmNone for a free slot.
  std::span<const uint32_t> slotVertices() const { return {slot_node_.data(), slot_count_}; }
  uint32_t slotCount() const { return slot_count_; }
  /// Active faces as slot triples (counter-clockwise); `out` is resized to activeFaceCount().
  void exportFaces(std::vector<std::array<uint32_t, 3>>& out) const;
  /// Active faces as PM face ids (ids of the input faces they stand for), in exportFaces()'s
  /// order.
  std::span<const uint32_t> activeFaceIds() const { return active_faces_; }
  /// The active mesh with compact (renumbered) vertices and displayed positions;
  /// `node_ids[i]` is the PM node of vertex i (pm().origin[] maps it to an input vertex).
  void exportCompact(TriMesh& out, std::vector<uint32_t>& node_ids) const;

  uint32_t activeVertexCount() const { return active_vertices_; }
  uint32_t activeFaceCount() const { return static_cast<uint32_t>(active_faces_.size()); }
  const LodStats& stats() const { return stats_; }
  const LodChanges& changes() const { return changes_; }
  const ProgressiveMesh& pm() const { return pm_; }

  /// Band fraction and visible faces of the current mesh under the current view.
  void measureBand(float& band_fraction, uint32_t& visible_faces,
                   float* band_or_limit_fraction = nullptr) const;

  /// Full consistency check (tests and debugging; O(n·depth)): manifold rings, face adjacency,
  /// slot/free-list consistency, the active front of the hierarchy, face corners equal to the
  /// active ancestors of their input corners, no face flipped relative to its full-detail
  /// normal (logical positions) unless listed with the folds. Returns "" or a description of
  /// the first violation.
  std::string checkInvariants() const;

 private:
  // Node state bits.
  static constexpr uint8_t kLocked = 1;   // child of a pending collapse
  static constexpr uint8_t kPending = 2;  // parent whose collapse is morphing

  void resetToBase();
  uint32_t allocSlot(uint32_t node);
  void freeSlot(uint32_t slot);
  void activateFace(uint32_t f);
  void deactivateFace(uint32_t f);
  uint32_t cornerOf(uint32_t f, uint32_t v) const {
    const auto& c = fv_[f];
    return c[0] == v ? 0 : c[1] == v ? 1 : c[2] == v ? 2 : 3;
  }
  float triangleImageArea(const glm::vec3& a, const glm::vec3& b, const glm::vec3& d) const;
  float faceImageArea(uint32_t f) const;
  float faceImageAreaWith(uint32_t f, uint32_t moved, const glm::vec3& p) const;
  bool flipped(uint32_t f) const;
  /// Face f's normal at its corners' positions (not normalised; zero for a face of no area).
  glm::vec3 faceNormalNow(uint32_t f) const;
  /// How many of fn0..fn3 of v's split are not active (the forced splits its split needs).
  uint32_t missingNeighbours(uint32_t v) const;
  bool facingAllowed(uint32_t f, const glm::vec3 (&q)[3], bool* folds) const;
  /// Whether a split may give a face it keeps the corners q: where the face ends facing as
  /// its full-detail face does, and also where it ends against that normal without turning
  /// over (its normal stays within 90° of the current one); `turned` is then set, and the
  /// split lists the face with the folds.
  bool splitFacingAllowed(uint32_t f, const glm::vec3 (&q)[3], bool& turned) const;
  /// The same for a face the split creates, (a, b, c), which opens between the faces `side0`
  /// and `side1` (adjacent before the split): it may end against its full-detail normal
  /// (`turned` is set) as long as it is not turned over against the two faces it opens
  /// between (its normal within 90° of the sum of their unit normals before the split).
  bool splitNewFaceAllowed(uint32_t f, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                           uint32_t side0, uint32_t side1, bool& turned) const;
  bool fanFacingAllowed(uint32_t vu, const glm::vec3& pp, bool& folds) const;
  /// Adds to folded_ those of `faces` that are against their full-detail normal and not
  /// listed yet (after a collapse that folded one, or a split that left one so).
  void listFlipped(std::span<const uint32_t> faces);
  void repairFolds();
  /// Collapses x, the last split made, as if it had not been made (its collapse leaves no
  /// record in changes_ or the counts; the caller drops x from changes_.split). False when
  /// the collapse cannot be made.
  bool undoSplit(uint32_t x);
  /// Collapses the splits recorded in changes_.split from index `mark` on, newest first, as
  /// if they had not been made this frame, and lets each wait kRetryFrames.
  void undoSplitsSince(size_t mark);
  float targetAt(const glm::vec3& p) const;
  /// Static per-node data for the view tests, also copied into each active vertex's slot.
  struct NodeBounds {
    glm::vec3 pos{0.0f};        // position (model units)
    float radius = 0.0f;        // bounding sphere of the node's region, around pos
    glm::vec3 axis{0.0f};       // normal cone of the region
    float cone_sin = 0.0f, cone_cos = -1.0f;  // of the cone's half-angle
    uint32_t parent = kPmNone;  // parent node
    uint32_t sibling = kPmNone;  // vu of the parent's split if this node is its vt
  };
  /// In the frustum and not entirely back-facing (Hoppe 1997 §4).
  bool visible(const NodeBounds& nb) const;
  /// Mean image area of the faces around active vertex v (0 if none).
  float ringMean(uint32_t v) const;
  float ringMeanAt(uint32_t slot) const;  ///< the same for the vertex in `slot`
  /// Mean image area around p if p's children were collapsed now (children active).
  float predictedMean(uint32_t p) const;
  /// Mean image area of the faces in the children's 1-rings (the collapse criterion), from
  /// the ring accumulators of their slots.
  float ringsMean(uint32_t st, uint32_t su) const;
  float pairMean(uint32_t st, uint32_t su, uint32_t p) const;
  /// ln(image area at the last adapt()'s view / now) per second at p (> 0: receding).
  float areaShrinkRate(const glm::vec3& p) const;
  /// Geomorph speed-up of a collapse whose rings' mean is `now` (see adaptive_mesh.cpp).
  float collapseSpeedup(float now, float target, const glm::vec3& pos) const;
  /// Collapses, at once, what keeps the due collapse of p illegal (finer faces beside fl and
  /// fr), up to `depth` levels; advanceCollapse() makes or unblocks the collapse of q.
  bool unblockCollapse(uint32_t p, int depth);
  bool advanceCollapse(uint32_t q, int depth);
  /// Adds (sign 1) or removes (sign -1) face f's area to/from its corners' accumulators.
  void accumulate(uint32_t f, float sign);
  // The slot's ring, lock or vertex changed: it, and the slot of its vertex's vt sibling
  // where it holds a vu (whose collapse test reads it), must be evaluated again in this pass.
  void touchSlot(uint32_t slot);
  bool idleAtStart(uint32_t slot, uint32_t node, bool vis, float target, float t_s, float t_c) const;
  // Where a face of image area `img` lies against the band [t_c·T/2, 2·t_s·T] for target T
  // `t` (LodStats::band_fraction): -1 below, 0 in it, 1 above.
  int bandSide(float img, float t) const {
    if (!(img >= 0.5f * params_.t_c * t)) return -1;  // (a NaN counts as below, out of the band)
    return img <= 2.0f * params_.t_s * t ? 0 : 1;
  }
  // Whether a face outside the band on `side` with these corner nodes is at the end of the
  // hierarchy in that direction: above with every corner a leaf, below with every corner a
  // root (LodStats::band_or_limit_fraction).
  bool atLimit(const std::array<uint32_t, 3>& nodes, int side) const {
    for (uint32_t v : nodes)
      if (side > 0 ? !pm_.isLeaf(v) : pm_.parent[v] != kPmNone) return false;
    return true;
  }
  bool splitDone(uint32_t node) const {
    return !pm_.isLeaf(node) && face_pos_[pm_.split(node).fl] != kPmNone;
  }
  bool ecolLegal(uint32_t p) const;
  /// ecolLegal(p) for the collapse of the vt in slot st and the vu in slot su, skipping the
  /// check while an earlier illegal verdict still holds (see the .cpp).
  bool collapseMayBeLegal(uint32_t st, uint32_t su, uint32_t p);
  /// Executes the split of active node s (legal, fn active). False (nothing changed) if the
  /// neighbourhood is not the recorded one or, with `check`, a face would flip.
  bool doSplit(uint32_t s, bool check, bool morph);
  bool doCollapse(uint32_t p, bool check);
  /// Hoppe's force_vsplit: splits ancestors and the creators of missing fn faces first.
  /// With `split_above` > 0, once those are split v itself is split only if its ring mean is
  /// still above it; otherwise the whole chain is undone, as a refused split is.
  bool forceSplit(uint32_t v, bool check, bool morph, float split_above = 0.0f);
  /// No face around vu would flip if p's children were collapsed now (ecol legal).
  bool collapseGeometryOk(uint32_t p) const;
  void startCollapseMorph(uint32_t p, float speedup);
  void cancelCollapse(uint32_t p);
  /// Takes p out of the list of pending (morphing) collapses.
  void removePending(uint32_t p);
  void startMorph(uint32_t slot, const glm::vec3& from, const glm::vec3& to, float duration);
  void stopMorph(uint32_t slot);
  void advanceMorphs(float dt);
  /// One pass of the selective refinement over all active vertices.
  void evaluatePass();
  void markDirty(uint32_t slot);
  void markMoved(uint32_t slot);
  void clearAllMorphs();
  /// Collects the faces around v counter-clockwise from `from` up to and including `to`.
  bool collectFan(uint32_t v, uint32_t from, uint32_t to, std::vector<uint32_t>& out) const;

  const ProgressiveMesh& pm_;
  WorkerPool* pool_ = nullptr;
  uint32_t n_nodes_ = 0, n_faces_ = 0;

  // Static per node / per face.
  HugeVector<glm::vec3> node_pos_;
  HugeVector<NodeBounds> bounds_;
  HugeVector<glm::vec3> ref_normal_;  // unit full-detail normal per face (0: degenerate)

  // Dynamic per node.
  HugeVector<uint32_t> node_slot_;
  HugeVector<uint8_t> node_state_;
  HugeVector<uint32_t> pending_pos_;
  HugeVector<uint32_t> retry_frame_;  // frame before which a refused split is not retried
  // Dynamic per face.
  HugeVector<std::array<uint32_t, 3>> fv_;   // corner nodes
  HugeVector<std::array<uint32_t, 3>> fnb_;  // neighbour across (c[i], c[i+1])
  HugeVector<uint32_t> face_pos_;            // index in active_faces_, kPmNone if inactive
  // Per active face, by position in the active list (swap-removed together, read in order by
  // the per-frame pass): face id, corner slots, image area in px² (logical positions).
  HugeVector<uint32_t> active_faces_;
  HugeVector<std::array<uint32_t, 3>> active_fs_;
  HugeVector<float> active_area_;
  HugeVector<uint8_t> active_visible_;  // adapt() step 1: per active face, facing and in the frustum
  // Slots.
  uint32_t slot_count_ = 0;
  uint32_t active_vertices_ = 0;
  HugeVector<uint32_t> slot_node_;
  HugeVector<uint32_t> slot_face_;
  HugeVector<glm::vec3> disp_, morph_from_, morph_to_;
  HugeVector<float> morph_t_, morph_rate_;
  HugeVector<uint32_t> morph_pos_;
  HugeVector<uint8_t> slot_locked_;     // copy of kLocked of the slot's node (read per frame)
  HugeVector<uint32_t> illegal_frame_;  // frame whose check found the slot's collapse illegal
  // Per slot: the ring mean after / before the last forced split of its vertex that was undone
  // because the chain left its own split not due (0: none since the slot took its vertex).
  HugeVector<float> undone_ratio_;
  HugeVector<uint8_t> refusals_;  // per slot: its vertex's forced splits refused in a row
  // evaluatePass(): node, visibility and target T of each slot, computed up front.
  HugeVector<uint32_t> pre_node_;
  HugeVector<uint8_t> pre_visible_;
  HugeVector<float> pre_target_;
  // Per slot: when the pass began, evaluating its vertex would have done nothing (the loop
  // skips it unless touchSlot() cleared the mark since: see evaluatePass()).
  HugeVector<uint8_t> eval_idle_;
  bool evaluate_every_vertex_ = false;
  uint64_t idle_mispredictions_ = 0;
  HugeVector<uint32_t> dirty_stamp_, moved_stamp_;
  HugeVector<NodeBounds> slot_bounds_;  // copy of bounds_ of the slot's node
  HugeVector<glm::vec3> slot_pos_;      // its position alone (the per-face pass reads 3 per face)
  HugeVector<double> ring_sum_;   // per slot: sum of the image areas of the incident faces
  HugeVector<int32_t> ring_cnt_;  // per slot: number of incident active faces
  std::vector<uint32_t> free_slots_;
  // The order of evaluation, apart from the slots' numbering (orderForLocality()): each slot's
  // place in it, the slot at each place (kPmNone: free), the free places (reused last freed
  // first, as slots were) and the places used so far.
  HugeVector<uint32_t> slot_eval_, eval_slot_;
  std::vector<uint32_t> eval_free_;
  uint32_t eval_count_ = 0;
  std::vector<uint32_t> morphing_;
  std::vector<uint32_t> pending_;

  // Scratch (reserved once).
  std::vector<uint32_t> work_;
  std::vector<uint32_t> stack_;
  std::vector<uint32_t> chain_;  // splits made by the current forceSplit
  mutable std::vector<uint32_t> fan_u_, fan_t_;
  // Faces against their full-detail normal: turned over by a collapse while sub-pixel, or
  // left so by a split that did not turn them over, kept (splitFacingAllowed()) or created
  // (splitNewFaceAllowed()); repairFolds() refines them.
  std::vector<uint32_t> folded_;
  std::vector<uint32_t> done_pending_;
  mutable std::vector<uint32_t> compact_index_;  // exportCompact's slot → vertex map
  // orderForLocality(): slots allocated since it last ran, the box its Morton codes span
  // (all nodes' positions), and its scratch.
  uint32_t fresh_slots_ = 0;
  glm::vec3 order_min_{0.0f}, order_extent_{1.0f};
  std::vector<uint32_t> order_code_, order_items_, order_tmp_, order_map_;
  std::vector<unsigned char> order_scratch_;

  // View.
  bool have_view_ = false;
  DetailParams params_;
  Camera camera_;
  int width_ = 0, height_ = 0;
  glm::mat4 view_proj_{1.0f};
  std::array<glm::vec4, kFrustumPlanes> planes_{};
  glm::vec3 eye_{0.0f}, forward_{0.0f, 0.0f, -1.0f};
  float k_ = 1.0f;
  glm::vec3 last_eye_{0.0f};  // eye and k_ of the last adapt() (areaShrinkRate)
  float last_k_ = 1.0f;
  bool have_last_view_ = false;
  uint32_t unblock_visits_ = 0;  // nodes visited by the current unblockCollapse()
  float t0_ = 16.0f;
  float focus_dist_ = 1.0f;
  float focal_px_ = 1.0f;
  glm::vec2 focus_{0.0f};
  bool modifiers_ = false;

  float split_speedup_ = 1.0f;
  float frame_dt_ = 0.0f;  // morph speed-up of the split being executed
  uint32_t frame_ = 1;
  uint32_t ops_ = 0;
  uint32_t resume_eval_ = 0;   // where the next evaluation starts (a budget cut the last one)
  bool budget_spent_ = false;  // this adapt() call stopped at a budget
  Stopwatch adapt_clock_;      // started by adapt(), for max_adapt_ms
  LodStats stats_;
  LodChanges changes_;
};

}  // namespace lodline
