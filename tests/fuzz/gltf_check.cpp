#include "gltf_check.h"

#include <cmath>

#include <glm/gtc/type_ptr.hpp>

#include "harness.h"
#include "io/load_gltf.h"
#include "io/load_mesh.h"

namespace lodline::fuzz {

void runGltfInput(std::string_view extension, const uint8_t* data, size_t size) {
  const InputFile input(extension, "", data, size);
  auto nodes = loadGltf(input.path());
  if (!nodes) {
    expectCleanError(nodes.error(), input.path());
    return;
  }
  if (nodes->empty()) fail("loadGltf accepted a file with no meshes");
  for (const GltfMeshNode& n : *nodes) {
    if (Status s = validateMesh(n.mesh, "node"); !s) fail("loadGltf returned an invalid mesh: " + s.error().message);
    for (int k = 0; k < 16; ++k)
      if (!std::isfinite(glm::value_ptr(n.transform)[k])) fail("loadGltf returned a non-finite transform");
  }
}

}  // namespace lodline::fuzz
