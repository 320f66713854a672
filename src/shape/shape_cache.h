// Per-vertex differential quantities of a triangle mesh: normals, mixed Voronoi point
// areas, principal curvatures and directions, and the curvature-derivative tensor.
//
// Algorithm: S. Rusinkiewicz, "Estimating Curvatures and Their Derivatives on Triangle
// Meshes", 3DPVT 2004 — §3 (per-face least-squares fit of the second fundamental form from
// the variation of vertex normals along the edges; rotation of tensors between frames;
// weighting by Voronoi area), §4 (the same fit one order up for the derivative tensor C).
// Corner areas follow Meyer, Desbrun, Schröder, Barr, "Discrete Differential-Geometry
// Operators for Triangulated 2-Manifolds" (VisMath 2002), §3.3 (mixed Voronoi areas with
// the obtuse-triangle rule) — see docs/design.md §3.
//
// Sign convention: with the mesh oriented counter-clockwise seen from outside, normals point
// outward and a convex surface has positive curvature (sphere of radius r: k1 = k2 = 1/r).
//
// Every per-face and per-vertex value is a pure function of the mesh inside its support
// (gathered over the vertex→face ring in a fixed order), which is what makes the
// incremental ShapeCache::update() bit-identical to a full ShapeCache::compute().
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/mesh.h"
#include "core/worker_pool.h"
#include "shape/adjacency.h"

namespace lodline {

/// How face normals are weighted into a vertex normal.
enum class NormalWeighting : uint8_t {
  kArea,   ///< by face area (sum of unnormalised face cross products)
  kAngle,  ///< by the face's angle at the vertex (Thürmer & Wüthrich 1998)
  kMax,    ///< by sin(angle)/(|a|·|b|) (N. Max, "Weights for computing vertex normals", 1999);
           ///< exact for vertices on a sphere, the trimesh2 choice
};

/// Settings of ShapeCache.
struct ShapeParams {
  /// Vertex-normal weighting. Default kMax: best curvature accuracy in tests/shape.
  NormalWeighting normal_weighting = NormalWeighting::kMax;
  /// Also compute the curvature-derivative tensor (needed by suggestive contours).
  /// Default true.
  bool derivatives = true;
  /// Compute derivative tensors only on request (ensureDerivatives()): compute() and
  /// update() then only invalidate them. Suggestive contours test Dw kr only next to kr zero
  /// crossings, so a mesh that changes every frame (level of detail) skips the widest ring
  /// of the incremental support for most vertices. Default false.
  bool lazy_derivatives = false;
  /// update() recomputes everything (same result, in memory order) when the vertices it
  /// would touch (the changed set grown by three rings with eager derivatives, by two with
  /// lazy ones, whose staleness is read off the curvatures' generations) exceed this fraction of all
  /// vertices. Default 0.8: large incremental sets are visited in memory order anyway. When
  /// chosen (eager tensors, adjacency rebuilt every frame), a 1.1M-triangle knot orbit with
  /// 22k adapted vertices averaged 7.0 ms per update at 0.8 against 8.6 ms at 0.5, which fell
  /// back to full computes in 24 of 60 frames.
  float full_recompute_fraction = 0.8f;
  /// Threads for the per-face and per-vertex loops, the caller included (0: one per core;
  /// 1: none started). Results are bit-identical for every count. Default 0.
  unsigned threads = 0;
  /// update() lets a vertex that moved by less than move_tolerance·√(its point area) since
  /// its quantities were last computed wait: it is recomputed once its moves add up to more,
  /// or once it stops moving (the first update() in which its position is the one of the
  /// update before). A geomorph moves a vertex a little every frame, so a mesh under detail
  /// control recomputes each morphing vertex's rings every few frames instead of every frame;
  /// meanwhile its quantities are those of a position at most that far away. Once nothing
  /// moves, the result is again bit-identical to compute() (docs/design.md §6, item 5).
  /// Default 0: every move is recomputed at once, always bit-identical.
  float move_tolerance = 0.0f;
};

/// What the last compute()/update() touched (for frame stats and tests).
struct ShapeUpdateStats {
  bool full = true;                  ///< true: everything was recomputed
  bool connectivity_rebuilt = false; ///< true: faces changed, the adjacency was brought up to date
  bool adjacency_in_place = false;   ///< ... by updateAdjacency() around the changed slots
  uint32_t changed_vertices = 0;     ///< distinct seeds: vertices passed + those of changed face slots
  uint32_t normal_vertices = 0;      ///< vertices whose normal/area/frame were recomputed
  uint32_t curvature_vertices = 0;   ///< vertices whose curvature was recomputed
  uint32_t derivative_vertices = 0;  ///< vertices whose derivative tensor was recomputed
  /// Vertices whose small moves wait after this update (ShapeParams::move_tolerance).
  uint32_t waiting_vertices = 0;
};

/// Read-only views of the per-vertex fields the lines stage consumes (all of vertexCount
/// entries). A caller may substitute its own arrays (e.g. temporally smoothed normals).
struct SurfaceFields {
  std::span<const glm::vec3> positions;  ///< model units
  std::span<const glm::vec3> normals;    ///< unit
  std::span<const float> k1;             ///< max principal curvature, 1/model units
  std::span<const float> k2;             ///< min principal curvature (k2 ≤ k1)
  std::span<const glm::vec3> pdir1;      ///< unit principal direction of k1
  std::span<const glm::vec3> pdir2;      ///< unit, = normal × pdir1
  /// Derivative tensor (C_111, C_112, C_122, C_222) in the (pdir1, pdir2) frame, 1/units².
  /// May be empty when derivatives were not computed.
  std::span<const glm::vec4> dcurv;
};

/// Evaluates the symmetric cubic form C (components C_111, C_112, C_122, C_222 in some
/// orthonormal frame) on the vectors a, b, c given by their coordinates in that frame.
float cubicForm(const glm::vec4& c, glm::vec2 a, glm::vec2 b, glm::vec2 d);

/// One-shot corner and point areas. `corner_areas` gets faceCount entries (area of corner j
/// of face f, mixed Voronoi), `point_areas` vertexCount entries (sum of a vertex's corners).
/// Degenerate faces (zero area, repeated or out-of-range indices) contribute zero.
void computeCornerAreas(const TriMesh& mesh, std::vector<std::array<float, 3>>& corner_areas,
                        std::vector<float>& point_areas);

/// Settings of computeFeatureSize(); the defaults are those of rtsc (DeCarlo &
/// Rusinkiewicz's suggestive-contour code), so its thresholds carry over.
struct FeatureSizeParams {
  uint32_t max_samples = 500;           ///< vertices sampled, evenly strided. Default 500
  float percentile = 0.1f;              ///< low percentile of |k1|,|k2| used. Default 0.1
  float multiplier = 0.01f;             ///< fs = multiplier / that |k|. Default 0.01
  float max_fraction_of_radius = 0.05f; ///< cap: fs ≤ this · bounding radius. Default 0.05
};

/// A length scale of the model (docs/design.md §3.5), in model units, for making
/// thresholds scale-free (suggestive-contour thresholds scale as 1/fs²). Deterministic.
/// Returns the cap when all sampled curvatures vanish, and 1 for an empty or zero-size input.
/// `stored_to_drawn` (one entry per vertex, or empty): for a mesh renumbered after it was
/// loaded (orderForLocality, core/mesh_order.h), the new index of each vertex as stored; the
/// samples are then the same vertices as in the stored order, so the feature size does not
/// depend on the numbering.
float computeFeatureSize(std::span<const float> k1, std::span<const float> k2,
                         float bounding_radius, const FeatureSizeParams& params = {},
                         std::span<const uint32_t> stored_to_drawn = {});

/// The same feature size for a mesh too large to be worth a whole ShapeCache (a full-detail
/// mesh that level of detail replaces before it is drawn): the curvature is computed only at
/// the vertices computeFeatureSize samples, on the submesh of their two-ring faces (which
/// holds every face their curvature reads, in the same order), so the result equals
/// computeFeatureSize on a ShapeCache of the whole mesh with `shape_params`. `adj` is mesh's
/// adjacency.
float sampledFeatureSize(const TriMesh& mesh, const MeshAdjacency& adj, float bounding_radius,
                         const ShapeParams& shape_params, const FeatureSizeParams& params = {});

/// The unit normal ShapeCache gives a face (corners p0, p1, p2, counter-clockwise) and twice
/// its area; both 0 for a degenerate face or one whose normal is not finite.
struct FaceNormal {
  glm::vec3 n{0.0f};
  float double_area = 0.0f;
};
FaceNormal faceNormalOf(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2);

/// Stateful per-vertex shape quantities for a mesh whose positions change every frame
/// (docs/design.md §6, items 4–5). Allocation-free after warm-up for position-only updates.
///
///   ShapeCache shape;
///   shape.compute(mesh);                    // once, or when connectivity changes
///   ...move some vertices...
///   shape.update(mesh, moved_vertex_ids);   // same arrays as compute(mesh), bit for bit
class ShapeCache {
 public:
  explicit ShapeCache(ShapeParams params = {}) : params_(params) {}

  /// Recomputes everything (adjacency only if mesh.faces differ from the last call).
  void compute(const TriMesh& mesh);

  /// Recomputes what depends on the positions of `changed_vertices` (any order, duplicates
  /// and out-of-range ids ignored): face geometry on their faces, normals on the 1-ring,
  /// curvature on the 1-ring of changed normals, derivatives one ring further.
  /// Connectivity may change too (checked with one memcmp, ~0.05 ms per 100k faces): the
  /// adjacency is then updated in place around the face slots whose triple changed, was
  /// added or removed (rebuilt, O(V + F), when they are more than an eighth), and their
  /// vertices and every new vertex join the changed set — cheap when the caller keeps face
  /// slots stable (edits in place, additions at the end); a compacted face array changes most
  /// slots and falls back to a full compute. Fewer vertices than last
  /// time, or nothing computed yet: compute(mesh). The result is always bit-identical to
  /// compute(mesh) on a fresh cache, except at vertices within three rings of a vertex
  /// whose small move waits (ShapeParams::move_tolerance > 0; waitingVertices()).
  void update(const TriMesh& mesh, std::span<const uint32_t> changed_vertices);
  /// The vertices whose last moves wait (ShapeParams::move_tolerance); empty when the cache
  /// is bit-identical to compute() on the mesh of the last call. An update() with no
  /// changed vertex and the same positions recomputes them all.
  std::span<const uint32_t> waitingVertices() const { return waiting_; }

  /// With lazy_derivatives: makes dcurv() valid at `vertices` (any order, repeats and
  /// out-of-range ids ignored) for `mesh`, the mesh of the last compute()/update(); the
  /// values are bit-identical to an eager compute. Otherwise does nothing.
  void ensureDerivatives(const TriMesh& mesh, std::span<const uint32_t> vertices);
  /// Whether dcurv()[v] holds the current derivative tensor (always, unless lazy).
  bool derivativeValid(uint32_t v) const {
    return params_.derivatives &&
           (!params_.lazy_derivatives || (v < vertex_dgen_.size() && tensorCurrent(v)));
  }
  /// Vertices whose derivative tensor the last ensureDerivatives() computed.
  uint32_t lastEnsured() const { return last_ensured_; }

  const ShapeParams& params() const { return params_; }
  /// Runs the loops on `pool` (not owned; must outlive this cache) instead of starting its
  /// own threads. Null: back to its own.
  void setWorkerPool(WorkerPool* pool) { external_pool_ = pool; }
  /// The adjacency of the mesh last computed. A one-thread compute() needs none (its loops
  /// run over the faces, as rtsc's do), so after it changed the connectivity the adjacency is
  /// built on the first call here; update(), ensureDerivatives() and the threaded compute()
  /// build it themselves. Not to be first called from two threads at once.
  const MeshAdjacency& adjacency() const;
  const ShapeUpdateStats& lastStats() const { return stats_; }
  /// Incremented by every compute()/update().
  uint64_t version() const { return version_; }

  // Per-vertex arrays (vertexCount entries).
  std::span<const glm::vec3> normals() const { return normals_; }
  std::span<const float> pointAreas() const { return point_areas_; }
  std::span<const float> k1() const { return k1_; }
  std::span<const float> k2() const { return k2_; }
  std::span<const glm::vec3> pdir1() const { return pdir1_; }
  std::span<const glm::vec3> pdir2() const { return pdir2_; }
  /// Empty when params().derivatives is false. With lazy_derivatives only the entries for
  /// which derivativeValid() holds are current.
  std::span<const glm::vec4> dcurv() const { return dcurv_; }

  // Per-face arrays (faceCount entries).
  std::span<const glm::vec3> faceNormals() const { return face_normals_; }  ///< unit or 0

  /// The per-vertex fields together with `mesh.positions` (the mesh last computed).
  SurfaceFields fields(const TriMesh& mesh) const;

 private:
  void resize(uint32_t nv, uint32_t nf);
  void vertexNormal(uint32_t v);
  void vertexCurvature(uint32_t v);
  void vertexDerivative(uint32_t v);
  // The face kernels (shape/fit_lanes.h), for faces[0 .. count), count ≤ lanes::kWidth: a
  // face's results do not depend on the block it is in. Face geometry (normal, frame, corner
  // areas, normal weights), and one face's results back (ok false: the record of a face
  // without geometry).
  void faceGeometryBlock(const TriMesh& mesh, const uint32_t* faces, uint32_t count);
  template <int W>
  void storeFaceGeometry(uint32_t f, const float* out, int lane, bool ok);
  // The curvature and derivative fits. `out` receives the kernel's rows, kWidth floats wide,
  // with each corner's term for its vertex's sum (read by computeScattered()).
  void curvatureFitBlock(const TriMesh& mesh, const uint32_t* faces, uint32_t count, float* out);
  void derivativeFitBlock(const TriMesh& mesh, const uint32_t* faces, uint32_t count, float* out);
  // Where a fit finds face f's inputs (lane `lane` of the kernel's sources, fit_lanes.h), and
  // its results back.
  template <int W>
  void gatherCurvatureFit(const TriMesh& mesh, uint32_t f, const float** src, int lane) const;
  template <int W>
  void storeCurvatureFit(uint32_t f, const float* out, int lane, bool ok);
  template <int W>
  void gatherDerivativeFit(const TriMesh& mesh, uint32_t f, const float** src, int lane) const;
  template <int W>
  void storeDerivativeFit(uint32_t f, const float* out, int lane, bool ok);
  // The vertex kernels' last step, from the ring's sums (shared by gather and scatter).
  void finishNormal(uint32_t v, glm::vec3 n, float area);
  void finishCurvature(uint32_t v, glm::vec3 k, float wsum);
  void finishDerivative(uint32_t v, glm::vec4 c, float wsum);
  // compute() on one thread: the faces scatter to their vertices, bit-identical to gathers.
  void computeScattered(const TriMesh& mesh, bool eager_derivatives);
  // Incremental bookkeeping over the nested sets C ⊆ V1 ⊆ V2 ⊆ V3, F1 ⊆ F2 ⊆ F3 kept as
  // prefixes of inc_verts_/inc_faces_: appends the unstamped faces around
  // inc_verts_[begin, end), resp. the unstamped vertices of inc_faces_[begin, end).
  void growFaces(size_t begin, size_t end, uint8_t level);
  void growVertices(const TriMesh& mesh, size_t begin, size_t end, uint8_t level);
  // Calls fn on the first `count` marked faces (or vertices) of level ≤ max_level: in list
  // order when few, in index order when many.
  template <class Fn>
  void forEachMarked(bool faces, size_t count, uint8_t max_level, Fn&& fn);
  // The same faces in blocks of up to lanes::kWidth: block_fn(faces, count).
  template <class Fn>
  void forEachMarkedFaceBlock(size_t count, uint8_t max_level, Fn&& block_fn);
  // Calls block_fn on the faces 0 .. nf − 1 in blocks of up to lanes::kWidth (parallelFor:
  // in face order on one thread).
  template <class Fn>
  void forEachFaceBlock(uint32_t nf, Fn&& block_fn);
  // Calls block_fn on list[0, n) in blocks of up to lanes::kWidth, split over the threads.
  template <class Fn>
  void forEachBlock(const uint32_t* list, size_t n, Fn&& block_fn);
  // fn(i) for i in [0, n), split over the worker threads when n is large.
  template <class Fn>
  void parallelFor(size_t n, Fn&& fn);

  ShapeParams params_;
  std::unique_ptr<WorkerPool> pool_;  // started on the first loop long enough to share
  WorkerPool* external_pool_ = nullptr;
  // Brings adjacency_ up to date with faces_copy_ over vertex_count_ vertices.
  void ensureAdjacency() const;

  mutable MeshAdjacency adjacency_;
  mutable bool adjacency_current_ = false;           // adjacency_ describes faces_copy_
  std::vector<std::array<uint32_t, 3>> faces_copy_;  // connectivity of the last compute
  uint32_t vertex_count_ = 0;                        // vertices of the last compute
  std::vector<uint8_t> face_valid_;  // faceIsValid() of faces_copy_, while adjacency_ is not built
  // Which faces are valid: the adjacency's flags when it is built, else face_valid_.
  const uint8_t* validFaces() const {
    return adjacency_current_ ? adjacency_.face_valid.data() : face_valid_.data();
  }
  bool computed_ = false;
  uint64_t version_ = 0;
  ShapeUpdateStats stats_;

  // Per face.
  std::vector<glm::vec3> face_normals_;
  // Everything a vertex gather reads about one face, in one record (one or two cache
  // lines instead of one per array: the gathers are memory-latency bound).
  struct FaceRecord {
    glm::vec4 rel[3];  // per corner: the vertex frame's axes in face coordinates (u1,v1,u2,v2)
    glm::vec4 dcurv;   // derivative tensor C in (t, b)
    glm::vec3 curv;    // (e, f, g) in (t, b)
    std::array<float, 3> corner;  // corner areas (Meyer et al. 2002 §3.3)
    glm::vec3 n;                  // unit face normal (0 if degenerate)
    std::array<float, 3> normal_weight;  // weight of n in each corner's vertex normal
    uint8_t ok = 0;    // bit 0: geometry ok, bit 1: curvature fit, bit 2: dcurv fit
  };
  std::vector<FaceRecord> faces_;
  // Per vertex.
  std::vector<glm::vec3> normals_;
  struct VertexFrame {
    glm::vec3 n, u, w;  // unit normal and the tangent frame derived from it (u × w = n)
  };
  std::vector<VertexFrame> frames_;
  std::vector<float> point_areas_, k1_, k2_;
  std::vector<glm::vec3> pdir1_, pdir2_;
  std::vector<glm::vec4> vertex_kab_;  // (k1, k2, a, b): pdir1 = a·u + b·w in frames_
  std::vector<glm::vec4> dcurv_;
  std::vector<glm::vec4> sum_;  // computeScattered(): per-vertex sums of one phase
  std::vector<float> sum_w_;

  // Incremental scratch: stamps avoid clearing per-vertex/face marks.
  std::vector<uint32_t> vertex_stamp_, face_stamp_;
  std::vector<uint8_t> vertex_level_, face_level_;  // ring level at which an item was marked
  uint32_t stamp_ = 0;
  std::vector<uint32_t> inc_verts_, inc_faces_;
  std::vector<uint32_t> marked_faces_;  // forEachMarkedFaceBlock(): the many, in index order
  std::vector<uint32_t> changed_faces_;  // face slots whose triple changed in this update
  // Lazy derivatives, by generations (one per compute()/update()): the generation in which
  // each vertex's curvature, each vertex's tensor and each face's fit were last computed. A
  // fit or tensor is current iff computed since the last compute() (dfloor_) and no
  // curvature it reads is newer (fitCurrent(), tensorCurrent()); update() only stamps the
  // curvatures it recomputes, instead of growing a third ring to mark the stale tensors.
  std::vector<uint32_t> vertex_dgen_, face_dgen_, curv_gen_;
  uint32_t dgen_ = 1, dfloor_ = 1;
  void nextGeneration();
  bool fitCurrent(uint32_t f) const;
  bool tensorCurrent(uint32_t v) const;
  uint32_t last_ensured_ = 0;
  std::vector<uint32_t> ens_verts_, ens_faces_;
  std::vector<uint64_t> ens_bits_;  // ensureDerivatives(): its faces as a bitmap, to list them in order
  // move_tolerance: per vertex, the position its quantities were last computed from and the
  // one it had in the last update (to see that it stopped); the vertices that wait.
  std::vector<glm::vec3> computed_pos_, seen_pos_;
  std::vector<uint8_t> waiting_flag_;
  std::vector<uint32_t> waiting_;
  // Resets the move_tolerance state: every vertex computed at its current position.
  void resetWaiting(const TriMesh& mesh);
};

}  // namespace lodline
