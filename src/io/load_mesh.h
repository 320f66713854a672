// Mesh input (OFF, OBJ, PLY ascii/binary, STL ascii/binary): lodline's bounded readers
// (mesh_reader.h) parse the file, OpenMesh's half-edge mesh settles the topology (a face that
// would make an edge or vertex non-manifold gets its own copies of its vertices; a face that
// repeats a vertex is dropped), polygons are fan-triangulated, and the result is validated
// (finite coordinates, indices in range, at least one face). The file is never modified.
#pragma once

#include <filesystem>

#include "core/mesh.h"
#include "core/result.h"

namespace lodline {

/// Reads `path` into flat arrays. Errors are one line naming the file and the problem, e.g.
/// "bunny.off: line 12: face 3 references vertex 35950, out of range (35947 vertices)".
/// Memory stays within a small multiple of the file size, whatever counts the file claims.
Result<TriMesh> loadMesh(const std::filesystem::path& path);

/// Largest and smallest bounding-box diagonal validateMesh accepts, model units: squared
/// lengths and areas must stay finite and non-zero in single precision.
inline constexpr float kMaxMeshExtent = 1e18f;
inline constexpr float kMinMeshExtent = 1e-18f;

/// Checks the TriMesh invariants (finite coordinates, indices in range, ≥ 1 face, no face
/// with a repeated vertex, a bounding-box diagonal within [kMinMeshExtent, kMaxMeshExtent]);
/// the message is prefixed by `what` (usually the file name).
Status validateMesh(const TriMesh& mesh, const std::string& what);

/// Writes an ASCII OFF file atomically (temporary file, then rename).
Status saveOff(const std::filesystem::path& path, const TriMesh& mesh);

}  // namespace lodline
