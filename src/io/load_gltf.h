// glTF 2.0 input (.gltf with its buffers, or binary .glb) through Debian's tinygltf: the
// default scene's nodes that carry a mesh, each with its world transform (the product of
// the node's and its ancestors' matrix or translation·rotation·scale). Triangle primitives
// (modes TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN) of a node's mesh are merged into one
// TriMesh; points and lines are skipped; images are not read.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "core/mesh.h"
#include "core/result.h"

namespace lodline {

struct GltfMeshNode {
  int node = -1;           ///< index into the file's nodes
  std::string name;        ///< the node's name, else its mesh's name, else "node<N>"
  glm::mat4 transform{1};  ///< node space → glTF world space
  TriMesh mesh;            ///< in node space, validated (validateMesh)
};

/// Reads every mesh node of the default scene (or of all root nodes when the file names
/// no scene). Errors name the file and the problem in one line, e.g.
/// "car.glb: mesh 2 primitive 0: index 9001 out of range (120 vertices)". A file with no
/// triangles is an error.
Result<std::vector<GltfMeshNode>> loadGltf(const std::filesystem::path& path);

}  // namespace lodline
