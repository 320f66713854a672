// The triangle mesh that flows between stages: flat arrays, 32-bit indices
// (docs/design.md §6). OpenMesh is used by io/ to read files, never in the frame loop.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace lodline {

/// An undirected edge given by its two vertex indices (any order).
using EdgeKey = std::array<uint32_t, 2>;

/// Indexed triangle mesh. Invariants (checked by validateMesh): every index <
/// positions.size(), all coordinates finite. Faces are counter-clockwise seen
/// from outside.
struct TriMesh {
  std::vector<glm::vec3> positions;           ///< one per vertex, model units
  std::vector<std::array<uint32_t, 3>> faces;  ///< vertex indices per triangle
  /// Edges the file marks as sharp/crease (e.g. OBJ `l` lines); may be empty.
  std::vector<EdgeKey> marked_edges;
  /// Material index per face (OBJ `usemtl`, glTF primitives' materials); empty: one
  /// material. Material lines (lines/lines.h) run where two faces' indices differ.
  std::vector<uint32_t> face_materials;

  size_t vertexCount() const { return positions.size(); }
  size_t faceCount() const { return faces.size(); }
};

/// Axis-aligned box and bounding sphere of a point set (centre of the box, radius
/// = largest distance from that centre).
struct Bounds {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};
  glm::vec3 center{0.0f};
  float radius = 0.0f;
  float diagonal() const;
};

/// Bounds of `positions` (empty span: all zero).
Bounds computeBounds(std::span<const glm::vec3> positions);

/// The median edge length of `mesh` (model units), from the edges of up to 4096 faces spread
/// evenly over the face list (VisibilityParams::segment_tolerance_cap); 0 for an empty mesh.
/// `lengths` is scratch, reused from call to call.
float medianEdgeLength(const TriMesh& mesh, std::vector<float>& lengths);

/// Area-weighted face normals: `out` gets faceCount() unit vectors (zero for a
/// degenerate face).
void computeFaceNormals(const TriMesh& mesh, std::vector<glm::vec3>& out);

}  // namespace lodline
