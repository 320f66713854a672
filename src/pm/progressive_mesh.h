// Progressive mesh: a base mesh plus a vertex hierarchy of vertex splits, built offline by
// quadric-error half-edge collapses.
//
//   Hoppe 1996, "Progressive meshes" (§3: vsplit/ecol records, §4: legality of collapses).
//   Hoppe 1997, "View-dependent refinement of progressive meshes" (§3: the vertex hierarchy,
//     vsplit(vs, vt, vu, fl, fr, fn0..fn3) and its neighbouring faces).
//   Hoppe 1998, "Efficient implementation of progressive meshes" (half-edge collapses keep an
//     original vertex position, flat arrays).
//   Garland, Heckbert 1997, "Surface simplification using quadric error metrics" (§4-5).
//
// Vertex hierarchy. Nodes 0..vertex_count-1 are the input vertices (the leaves). Collapse
// number i creates node `vertex_count + i` (its parent): collapsing the half-edge u→t makes
// the parent node s, whose children are vt (the node of t) and vu (the node of u). The
// parent keeps t's position (half-edge collapse), so a node's position is the position of
// the input vertex `origin[node]`. Faces keep the ids of the input faces: collapse i removes
// faces fl = (u, t, l) and fr = (t, u, r); vsplit i re-creates them. "Fully refined" is
// therefore the input mesh itself, face for face.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/huge_pages.h"
#include "core/mesh.h"
#include "core/result.h"

namespace lodline {

/// "No vertex / no face".
inline constexpr uint32_t kPmNone = 0xffffffffu;

/// One vertex split (the inverse of a half-edge collapse u→t), Hoppe 1997 §3 notation.
/// With fl = (vu, vt, l) and fr = (vt, vu, r) counter-clockwise:
///   fn[0] = the face across edge (t, l) from fl, fn[1] = across (l, u) from fl,
///   fn[2] = the face across edge (u, r) from fr, fn[3] = across (r, t) from fr.
/// Collapses only happen between interior manifold vertices, so all four exist.
struct VertexSplit {
  uint32_t vt = kPmNone;  ///< child keeping the parent's position (node id)
  uint32_t vu = kPmNone;  ///< child removed by the collapse (node id)
  uint32_t fl = kPmNone;  ///< face (vu, vt, l) created by the split (face id)
  uint32_t fr = kPmNone;  ///< face (vt, vu, r) created by the split (face id)
  std::array<uint32_t, 4> fn{kPmNone, kPmNone, kPmNone, kPmNone};  ///< neighbour faces
};

/// Flags per input vertex.
enum PmVertexFlags : uint8_t {
  kPmBoundary = 1,  ///< on an open boundary: kept in the base mesh
  /// non-manifold, isolated, on a degenerate face or on a material boundary
  /// (TriMesh::face_materials): never collapsed
  kPmFrozen = 2,
};

/// Build settings (they are part of the cache key).
struct PmBuildParams {
  /// Largest change of a face normal a single collapse may cause, degrees.
  float max_normal_change_deg = 75.0f;
  /// A face may never turn further than this from the normal of the same face at full detail
  /// (degrees, < 90: no fold-over relative to the input surface).
  float max_normal_deviation_deg = 85.0f;
  /// Collapses may not create a face of quality 4√3·A/Σl² below this (unless the face was
  /// already worse): avoids slivers.
  float min_face_quality = 0.05f;
  /// Collapses may not give a vertex more neighbours than this (keeps rings short).
  uint32_t max_valence = 24;
  /// Stop when the base mesh has this many faces or fewer (0: simplify as far as the checks
  /// allow).
  uint32_t min_base_faces = 0;
};

/// Progress callback: fraction done in [0, 1]. Called about a hundred times per build.
using PmProgress = std::function<void(float fraction)>;

/// The progressive mesh. Built by buildProgressiveMesh, stored by savePm (pm_file.h).
struct ProgressiveMesh {
  // ---- stored ----
  std::vector<glm::vec3> positions;                 ///< input positions, one per leaf node
  std::vector<std::array<uint32_t, 3>> faces;       ///< input faces (full detail), by face id
  std::vector<uint8_t> vertex_flags;                ///< PmVertexFlags per input vertex
  HugeVector<VertexSplit> splits;                    ///< split i creates node vertexCount()+i
  std::vector<uint32_t> base_faces;                 ///< ids of the faces of the base mesh
  std::vector<std::array<uint32_t, 3>> base_corners;    ///< node ids, per base face
  std::vector<std::array<uint32_t, 3>> base_neighbors;  ///< across edge (c[i], c[i+1]), or kPmNone
  uint64_t content_hash = 0;  ///< hash of the input mesh (meshContentHash)
  uint64_t params_hash = 0;   ///< hash of the PmBuildParams used

  // ---- derived by finalize() ----
  HugeVector<uint32_t> parent;        ///< per node: parent node or kPmNone (roots)
  std::vector<uint32_t> origin;       ///< per node: the input vertex whose position it has
  std::vector<uint32_t> face_parent;  ///< per face: node whose split creates it, or kPmNone
  std::vector<uint32_t> roots;        ///< nodes without parent (vertices of the base mesh)

  uint32_t vertexCount() const { return static_cast<uint32_t>(positions.size()); }
  uint32_t faceCount() const { return static_cast<uint32_t>(faces.size()); }
  uint32_t nodeCount() const { return vertexCount() + static_cast<uint32_t>(splits.size()); }
  bool isLeaf(uint32_t node) const { return node < vertexCount(); }
  /// Split record of an internal node (node ≥ vertexCount()).
  const VertexSplit& split(uint32_t node) const { return splits[node - vertexCount()]; }
  /// Position of any node (the input vertex it inherited), model units.
  glm::vec3 nodePosition(uint32_t node) const { return positions[origin[node]]; }

  /// Checks every index and the hierarchy (each node is the child of at most one split,
  /// children precede parents, every face is created exactly once) and fills the derived
  /// arrays. Errors start with `what` (e.g. the file name).
  Status finalize(const std::string& what);

  /// The base mesh as a TriMesh over the input vertex positions (`base_node_ids` receives the
  /// node id of each output vertex).
  TriMesh baseMesh(std::vector<uint32_t>* base_node_ids = nullptr) const;
};

/// Builds the progressive mesh of `mesh`. Non-manifold edges and vertices, open boundaries,
/// isolated vertices and degenerate faces are left untouched (they stay in the base mesh).
/// Errors (naming nothing but the problem): no faces, non-finite coordinates, indices out of
/// range. Speed: about 2.5-6 s per million faces on one core (armadillo / 1.3M icosphere).
Result<ProgressiveMesh> buildProgressiveMesh(const TriMesh& mesh, const PmBuildParams& params = {},
                                             const PmProgress& progress = {});

/// 64-bit hash of the mesh arrays (positions and faces bytes, and the face materials when
/// there are any), the cache key of a model.
uint64_t meshContentHash(const TriMesh& mesh);

/// Hash of the build parameters (part of the cache key).
uint64_t buildParamsHash(const PmBuildParams& params);

/// The mesh after the first `collapses` collapses of `pm` (0: the input mesh, splits.size():
/// the base mesh), compacted: unused vertices are dropped, faces keep their input order.
/// `pm` must be finalized.
TriMesh pmLevelMesh(const ProgressiveMesh& pm, uint32_t collapses);

/// Result of simplifyWithinBound().
struct BoundedSimplification {
  TriMesh mesh;            ///< the simplified mesh (pmLevelMesh of `collapses`)
  uint32_t collapses = 0;  ///< collapses applied
  double error = 0.0;      ///< the measured error of `mesh` (never above the bound)
  int evaluations = 0;     ///< calls of the error function
};

/// Error function for simplifyWithinBound(): the error of a candidate mesh (any unit, e.g.
/// Pan et al.'s E_s relative to the diagonal), or a negative value if it cannot be measured.
using MeshErrorFn = std::function<double(const TriMesh& candidate)>;

/// Error-bounded static simplification (Pan, Zhou, Shi, docs/design.md §2.4): runs the quadric-error
/// collapses of `pm` in their order and keeps the longest prefix whose measured `error` is at
/// most `bound`, found by bisection over the collapse count (about log2(collapses)+2 calls).
/// Every returned level was measured, so the bound holds even where the error is not monotone
/// in the number of collapses (the search then backs off to a measured level).
BoundedSimplification simplifyWithinBound(const ProgressiveMesh& pm, double bound, const MeshErrorFn& error);


}  // namespace lodline
