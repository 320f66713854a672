// Painting a mesh by planes: the faces on one side of a plane (or inside a slab between two
// parallel planes) get a material of their own, and the mesh is first cut exactly along the
// plane so the material boundary is a chain of mesh edges on the plane. Scene files use it
// ("paint" on an object, docs/scenes.md) to give meshes without materials — OFF/PLY/STL
// parts — material lines (docs/lines.md "Material boundaries"): the progressive mesh keeps
// vertices on material boundaries (pm/progressive_mesh.h), so the painted edge stays exact
// at every level of detail.
#pragma once

#include <span>
#include <string>

#include <glm/vec3.hpp>

#include "core/mesh.h"
#include "core/result.h"

namespace lodline {

/// One painted region, in the mesh's own (model) coordinates: the points p with
/// n·p ≥ offset, or, when `thickness` > 0, the slab offset ≤ n·p ≤ offset + thickness.
/// `normal` need not be unit length (the plane is normalised: offset and thickness are in
/// model units along the unit normal); it must not be zero.
struct PaintRegion {
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  float offset = 0.0f;     ///< model units along the unit normal
  float thickness = 0.0f;  ///< 0: the half-space; > 0: a slab this thick
};

/// What paintMesh did, for messages and tests.
struct PaintInfo {
  size_t cut_edges = 0;      ///< edges split by a new vertex on a plane
  size_t painted_faces = 0;  ///< faces that got a region's material
};

/// Cuts `mesh` along every region's plane(s) and gives the faces inside region k the material
/// index base + k, where base is one more than the mesh's largest material index (a mesh
/// without materials counts as material 0: base 1); later regions paint over earlier ones. An edge
/// crossing a plane gets one new vertex shared by both its faces (the mesh stays as closed
/// as it was); a crossing closer than 5% of the edge to one end uses that end instead, so
/// no sliver triangles appear. Marked (sharp) edges that are cut stay marked in both
/// halves. Errors (a zero normal, a negative or non-finite number) name `what`.
Result<PaintInfo> paintMesh(TriMesh& mesh, std::span<const PaintRegion> regions, const std::string& what);

}  // namespace lodline
