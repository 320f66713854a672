// Shared body of the glTF fuzz targets: loadGltf on the input, a clean one-line error when it
// is refused, and when accepted, meshes that satisfy the TriMesh invariants with finite
// transforms (what the scene loader then relies on).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace lodline::fuzz {

void runGltfInput(std::string_view extension, const uint8_t* data, size_t size);

}  // namespace lodline::fuzz
