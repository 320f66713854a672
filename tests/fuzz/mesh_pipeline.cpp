#include "mesh_pipeline.h"

#include <array>
#include <memory>

#include "core/camera.h"
#include "frame/lod_drawing.h"
#include "io/load_mesh.h"
#include "pm/progressive_mesh.h"

namespace lodline::fuzz {

void runMeshInput(std::string_view extension, std::string_view prefix, const uint8_t* data, size_t size) {
  const InputFile input(extension, prefix, data, size);
  Result<TriMesh> mesh = loadMesh(input.path());
  if (!mesh) {
    expectCleanError(mesh.error(), input.path());
    return;
  }
  if (Status s = validateMesh(*mesh, input.path().string()); !s)
    fail("loadMesh accepted an invalid mesh: " + s.error().message);
  Result<ProgressiveMesh> pm = buildProgressiveMesh(*mesh);
  if (!pm) {
    expectCleanError(Error::runtime(input.path().string() + ": " + pm.error().message), input.path());
    return;
  }
  pm->content_hash = meshContentHash(*mesh);
  // As `render` does: the default 3/4 view, converged detail (small image, few steps).
  auto shared = std::make_shared<const ProgressiveMesh>(std::move(pm.value()));
  LodDrawing drawing(std::move(mesh.value()), std::move(shared));
  const int width = 96, height = 64;
  const Camera camera = orbitCamera(drawing.bounds(), OrbitView{}, 35.0f, static_cast<float>(width) / height);
  std::array<bool, kLineKindCount> enabled;
  enabled.fill(true);
  Result<int> steps = drawing.converge(camera, width, height, DetailParams{}, 1.0f / 30.0f, 6, enabled);
  if (!steps) fail("converge failed on an accepted mesh: " + steps.error().message);
}

}  // namespace lodline::fuzz
