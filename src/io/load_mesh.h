// Mesh input through OpenMesh's readers (OFF, OBJ, PLY ascii/binary, STL ascii/binary).
// Polygons are fan-triangulated; the result is validated (finite coordinates, indices in
// range, at least one face). The file itself is never modified.
#pragma once

#include <filesystem>

#include "core/mesh.h"
#include "core/result.h"

namespace lodline {

/// Reads `path` into flat arrays. Errors name the file and the problem, e.g.
/// "bunny.off: 3 faces reference vertex indices out of range (35947 vertices)".
Result<TriMesh> loadMesh(const std::filesystem::path& path);

/// Checks the TriMesh invariants (finite coordinates, indices in range, ≥ 1 face, no face
/// with a repeated vertex); the message is prefixed by `what` (usually the file name).
Status validateMesh(const TriMesh& mesh, const std::string& what);

/// Writes an ASCII OFF file atomically (temporary file, then rename).
Status saveOff(const std::filesystem::path& path, const TriMesh& mesh);

/// FNV-1a 64-bit hash of the file's bytes (cache keys); error if unreadable.
Result<uint64_t> hashFile(const std::filesystem::path& path);

}  // namespace lodline
