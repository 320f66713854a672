// Fuzz target: scene files (`lodline render SCENE.json`, docs/scenes.md) through loadScene and,
// when accepted, every object's mesh loaded, painted and transformed as the drawing commands do. A
// small mesh "m.off" lies next to the input, so scenes that name it get past the reader.
#include <cmath>
#include <fstream>

#include "harness.h"
#include "io/scene_file.h"

LODLINE_FUZZ_TARGET(scene_json) {
  using namespace lodline;
  const fuzz::InputFile input(".json", "", data, size);
  const auto mesh = input.path().parent_path() / "m.off";
  if (!std::filesystem::exists(mesh))
    std::ofstream(mesh) << "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  Result<Scene> scene = loadScene(input.path());
  if (!scene) {
    fuzz::expectCleanError(scene.error(), input.path());
    return;
  }
  if (scene->objects.empty()) fuzz::fail("an accepted scene has no objects");
  for (const SceneObject& obj : scene->objects) {
    if (!(obj.detail_factor > 0.0f) || !std::isfinite(obj.detail_factor))
      fuzz::fail("accepted detail factor " + std::to_string(obj.detail_factor));
    Result<TriMesh> m = loadObjectMesh(obj);
    if (!m) {
      // Transforms may overflow the positions: refused by the validator, naming the scene.
      fuzz::expectCleanError(m.error(), obj.mesh);
      continue;
    }
    if (!m->face_materials.empty() && m->face_materials.size() != m->faces.size())
      fuzz::fail("painted mesh with " + std::to_string(m->face_materials.size()) + " materials for " +
                 std::to_string(m->faces.size()) + " faces");
    for (const glm::vec3& p : m->positions)
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) fuzz::fail("a transformed vertex is not finite");
  }
}
