// lodline's own bounded readers of the mesh formats it accepts: OFF (ASCII and binary), OBJ,
// PLY (ASCII, binary little- and big-endian) and STL (ASCII and binary).
//
// They stand between untrusted bytes and the rest of lodline. Every count a file announces
// is checked against the file's size before anything is allocated, every index against the
// vertex count, every token against its syntax, so memory and time stay proportional to the
// file's size whatever it holds, and a malformed file gives one line that says where
// ("mesh.obj: line 12: face vertex 'x' is not an index"). OpenMesh's readers, used before,
// allocated whatever a header announced, looped forever on a PLY header without end,
// aborted on an OBJ face token they could not parse and opened any file an OBJ `mtllib`
// named (docs/reliability.md). loadMesh (load_mesh.h) builds the polygons read here.
//
// What is read: vertex positions and polygons (and OBJ `l` lines, the sharp edges). Colours,
// normals, texture coordinates and other properties are skipped. Format notes:
//  - OFF: header [ST][C][N]OFF [BINARY] (4OFF and nOFF are refused), `#` comments, counts
//    "V F [E]"; a vertex's line may hold more than x y z (ignored); a face is
//    "k i_1 ... i_k" and the rest of its line (a colour) is ignored. Binary OFF is
//    little-endian 32-bit, as OpenMesh writes it.
//  - OBJ: `v x y z ...`, `f a b c ...` with a, a/t, a/t/n or a//n, negative indices relative
//    to the vertices so far, `l` polylines; other statements are ignored (no file they
//    name is opened).
//  - PLY: any element order; the vertex element needs x, y, z (any numeric type); faces come
//    from the `vertex_indices` (or `vertex_index`) list of the `face` element; other elements
//    and properties are skipped.
//  - STL: binary when the size is exactly 84 + 50·(triangle count), ASCII when it starts with
//    "solid", else an error. Identical corner positions become one vertex (first seen first).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "core/mesh.h"
#include "core/result.h"

namespace lodline {

/// Polygons as read from a file: indices are < positions.size(), every face has ≥ 3 corners
/// (a face may repeat a vertex; loadMesh drops those). Coordinates are as written (they may
/// be NaN or infinite; validateMesh refuses those).
struct PolygonMesh {
  std::vector<glm::vec3> positions;   ///< one per vertex, file order
  std::vector<uint32_t> face_start;   ///< faceCount() + 1 offsets into `corners`
  std::vector<uint32_t> corners;      ///< vertex index of each face corner
  std::vector<EdgeKey> marked_edges;  ///< OBJ `l` segments (sharp edges)
  /// Per face, the index of its material in order of first use (OBJ `usemtl`); empty when
  /// the file names fewer than two materials.
  std::vector<uint32_t> face_materials;

  size_t faceCount() const { return face_start.empty() ? 0 : face_start.size() - 1; }
};

/// Parses `bytes` as the format named by `extension` (".off", ".obj", ".ply" or ".stl", lower
/// case). `name` prefixes every error (the file name). Memory used is at most a small multiple
/// of bytes.size() plus what the accepted mesh needs.
Result<PolygonMesh> parsePolygonMesh(std::string_view bytes, std::string_view extension, const std::string& name);

}  // namespace lodline
