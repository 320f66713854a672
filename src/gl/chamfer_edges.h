// Sharp edges for the chamfer highlights (Wei, Shi, Yong 2014; docs/design.md §2.2): edges of the
// mesh actually drawn (the adapted mesh under level of detail) whose dihedral angle (the
// angle between the two face normals) reaches a threshold, plus the edges the file marks
// (TriMesh::marked_edges). GL-free; the ChamferLayer uploads the result.
//
// Vertices at equal positions are welded before the edge list is built (MeshAdjacency), so
// meshes whose vertices are split along sharp edges (flat-shaded exports, per-face normals)
// still have their sharp edges found. Boundary and non-manifold edges are never chamfered.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/mesh.h"
#include "shape/adjacency.h"

namespace lodline {

/// Angle given to marked edges so they sort first and pass every threshold.
inline constexpr float kMarkedEdgeAngleDeg = 1000.0f;

/// Candidate edges, sorted by decreasing dihedral angle, so the edges at or above any
/// threshold are a prefix (countAtLeast()). All arrays have one entry per edge.
struct ChamferEdges {
  std::vector<EdgeKey> vertices;  ///< end vertices, indices into the caller's positions
  std::vector<glm::vec3> normal1, normal2;  ///< unit normals of the two faces
  /// Unit directions from the edge into each face, in the face's plane, ⟂ to the edge.
  std::vector<glm::vec3> inward1, inward2;
  std::vector<float> angle_deg;  ///< dihedral angle in degrees; kMarkedEdgeAngleDeg if marked

  size_t size() const { return vertices.size(); }
  /// Number of leading edges with angle_deg ≥ threshold_deg.
  size_t countAtLeast(float threshold_deg) const;
};

/// Reusable scratch of findChamferEdges (no allocation after warm-up).
struct ChamferEdgeScratch {
  std::vector<uint32_t> order, weld;
  TriMesh welded;
  MeshAdjacency adjacency;
  std::vector<glm::vec3> face_normals;
  std::vector<uint32_t> sorted;
  std::vector<float> angle;
};

/// Welds (positions, faces) by position and builds the adjacency of the result into
/// `scratch`: the shared first step of findChamferEdges() and computeCornerNormals(), which
/// skip it when called with `prepared` = true on the same arrays. O(V log V + F).
void prepareChamferMesh(std::span<const glm::vec3> positions,
                        std::span<const std::array<uint32_t, 3>> faces, ChamferEdgeScratch& scratch);

/// Finds the edges of (positions, faces) with a dihedral angle ≥ `min_angle_deg` plus the
/// `marked` ones (pairs of indices into `positions`; unknown pairs are ignored), into `out`.
/// O(V log V + F).
void findChamferEdges(std::span<const glm::vec3> positions,
                      std::span<const std::array<uint32_t, 3>> faces,
                      std::span<const EdgeKey> marked, float min_angle_deg,
                      ChamferEdgeScratch& scratch, ChamferEdges& out, bool prepared = false);

/// Crease-aware normals for flat-and-smooth shading of CAD-like meshes: `out` gets 3 unit
/// normals per face (corner j of face f at out[3f + j]), the area-weighted mean of the
/// normals of the faces around that corner's vertex (welded by position) whose normal is
/// within `smooth_angle_deg` of face f's, so shading never smears across a sharp edge.
void computeCornerNormals(std::span<const glm::vec3> positions,
                          std::span<const std::array<uint32_t, 3>> faces, float smooth_angle_deg,
                          ChamferEdgeScratch& scratch, std::vector<glm::vec3>& out,
                          bool prepared = false);

}  // namespace lodline
