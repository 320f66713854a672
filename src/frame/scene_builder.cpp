#include "frame/scene_builder.h"

#include <algorithm>

#include "core/timer.h"
#include "core/worker_pool.h"
#include "pm/pm_file.h"

namespace lodline {

const char* lodChoiceName(const LodChoice& lod) {
  if (std::holds_alternative<ClusteredDetail>(lod)) return "cluster";
  if (std::holds_alternative<FullDetail>(lod)) return "none";
  return "pm";
}

Result<SceneDrawing> buildSceneDrawing(const Scene& scene, std::span<const ObjectStyle> styles, const LodChoice& lod,
                                       const LineParams& lines, SceneBuildInfo& info, const MeshPrepare& prepare,
                                       const PmProgressFor& progress) {
  LODLINE_ASSERT(styles.size() == scene.objects.size());
  SceneDrawing drawing;
  auto pool = std::make_shared<WorkerPool>(ShapeParams{}.threads);
  Stopwatch sw;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& obj = scene.objects[i];
    sw.lap();
    auto mesh = loadObjectMesh(obj);
    if (!mesh) return mesh.error();
    info.load_ms += sw.lap();
    SceneDrawing::Object o;
    o.name = obj.name;
    o.style = styles[i];
    o.detail_factor = obj.detail_factor;
    o.input_vertices = mesh->vertexCount();
    o.input_faces = mesh->faceCount();
    if (prepare) {
      auto prepared = prepare(std::move(mesh.value()), obj);
      if (!prepared) return prepared.error();
      mesh = std::move(prepared.value());
    }
    if (std::holds_alternative<FullDetail>(lod)) {
      o.drawing = std::make_unique<LodDrawing>(std::move(mesh.value()), lines, pool);
    } else if (const auto* cluster = std::get_if<ClusteredDetail>(&lod)) {
      o.drawing = std::make_unique<LodDrawing>(std::move(mesh.value()), cluster->params, lines, pool);
      info.cache_note = "vertex clustering";
    } else {
      const auto& pm_choice = std::get<ProgressiveDetail>(lod);
      std::string note;
      const uint64_t hash = meshContentHash(*mesh);
      auto pm = loadOrBuildPm(*mesh, hash, pm_choice.cache_dir, {}, progress ? progress(obj) : PmProgress{}, &note);
      if (!pm) return Error::runtime(obj.mesh.string() + ": " + pm.error().message);
      if (!info.cache_note.empty()) info.cache_note += "; ";
      info.cache_note += note;
      auto shared = std::make_shared<const ProgressiveMesh>(std::move(pm.value()));
      o.drawing = std::make_unique<LodDrawing>(std::move(mesh.value()), std::move(shared), lines, pool);
    }
    info.pm_ms += sw.lap();
    drawing.add(std::move(o));
  }
  return drawing;
}

Result<std::unique_ptr<LoadedScene>> loadSceneDrawing(SceneInput input, const PmProgressFor& progress) {
  auto loaded = std::make_unique<LoadedScene>();
  auto drawing = buildSceneDrawing(input.scene, input.styles, input.detail.lod, input.view.line_params, loaded->build,
                                   {}, progress);
  if (!drawing) return drawing.error();
  loaded->drawing = std::move(drawing.value());
  loaded->view = std::move(input.view);
  loaded->detail = std::move(input.detail);
  loaded->camera = input.scene.camera;
  loaded->scene = std::move(input.scene);
  return loaded;
}

Result<Camera> initialCamera(const LoadedScene& loaded, float aspect) {
  const Bounds& bounds = loaded.drawing.bounds();
  if (loaded.camera && loaded.camera->explicit_pose) {
    Camera cam;
    cam.eye = loaded.camera->eye;
    cam.target = loaded.camera->target;
    cam.up = loaded.camera->up;
    cam.fov_deg = loaded.view.fov_deg;
    fitClipPlanes(cam, bounds);
    return cam;
  }
  if (loaded.camera && loaded.camera->path) {
    auto path = scenePath({"", false, loaded.camera->duration.value_or(8.0)}, bounds, loaded.camera,
                          loaded.view.fov_deg, aspect);
    if (!path) return path.error();
    return path->at(path->keys().front().time, bounds);
  }
  return orbitCamera(bounds, loaded.view.orbit, loaded.view.fov_deg, aspect);
}

Result<CameraPath> scenePath(const PathChoice& choice, const Bounds& bounds, const std::optional<SceneCamera>& camera,
                             float fov_deg, float aspect) {
  std::string name = choice.name_or_file;
  double duration = choice.duration;
  if (!choice.given && camera && camera->path) {
    name = *camera->path;
    if (camera->duration) duration = *camera->duration;
  }
  const auto& names = builtinPathNames();
  if (std::find(names.begin(), names.end(), name) != names.end() ||
      std::filesystem::path(name).extension() != ".json")  // unknown names get the usage error
    return builtinPath(name, bounds, fov_deg, aspect, duration);
  return loadCameraPath(name);
}

}  // namespace lodline
