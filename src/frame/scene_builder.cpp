#include "frame/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/timer.h"
#include "core/worker_pool.h"
#include "pm/pm_file.h"

namespace lodline {

const char* lodChoiceName(const LodChoice& lod) {
  if (std::holds_alternative<ClusteredDetail>(lod)) return "cluster";
  if (std::holds_alternative<FullDetail>(lod)) return "none";
  return "pm";
}

void chainIntersections(std::span<const glm::vec3> segments, float weld, StrokeSet& out) {
  LineSet set;
  // Endpoints welded on a grid of `weld` cells (a point and its twin from the neighbouring
  // triangle pair agree to rounding): the cell is the point id.
  std::unordered_map<uint64_t, uint32_t> ids;
  const float inv = weld > 0.0f ? 1.0f / weld : 1e6f;
  auto id = [&](const glm::vec3& p) {
    const auto q = [&](float v) { return static_cast<uint64_t>(static_cast<int64_t>(std::llround(v * inv)) & 0x1fffff); };
    const uint64_t key = q(p.x) | (q(p.y) << 21) | (q(p.z) << 42);
    return ids.emplace(key, static_cast<uint32_t>(ids.size())).first->second;
  };
  for (size_t i = 0; i + 1 < segments.size(); i += 2) {
    const uint32_t a = id(segments[i]), b = id(segments[i + 1]);
    if (a == b) continue;
    set.points.push_back(segments[i]);
    set.points.push_back(segments[i + 1]);
    set.alpha.push_back(1.0f);
    set.alpha.push_back(1.0f);
    set.point_ids.push_back(a);
    set.point_ids.push_back(b);
    set.kinds.push_back(LineKind::kIntersection);
    set.sources.push_back(static_cast<uint32_t>(i / 2));
    ++set.counts[static_cast<int>(LineKind::kIntersection)];
  }
  ChainScratch scratch;
  chainStrokes(set, out, scratch);
}

Result<SceneDrawing> buildSceneDrawing(const Scene& scene, std::span<const ObjectStyle> styles, const LodChoice& lod,
                                       const LineParams& lines, SceneBuildInfo& info, const MeshPrepare& prepare,
                                       const PmProgressFor& progress, const IntersectionFinder& intersections) {
  LODLINE_ASSERT(styles.size() == scene.objects.size());
  SceneDrawing drawing;
  auto pool = std::make_shared<WorkerPool>(ShapeParams{}.threads);
  Stopwatch sw;
  // Every mesh first: the crossings need them all.
  std::vector<TriMesh> meshes;
  std::vector<size_t> input_vertices, input_faces;
  for (const SceneObject& obj : scene.objects) {
    sw.lap();
    auto mesh = loadObjectMesh(obj);
    if (!mesh) return mesh.error();
    info.load_ms += sw.lap();
    input_vertices.push_back(mesh->vertexCount());
    input_faces.push_back(mesh->faceCount());
    if (prepare) {
      auto prepared = prepare(std::move(mesh.value()), obj);
      if (!prepared) return prepared.error();
      mesh = std::move(prepared.value());
    }
    meshes.push_back(std::move(mesh.value()));
  }
  std::vector<StrokeSet> crossings(meshes.size());
  const bool want_crossings =
      intersections && std::any_of(styles.begin(), styles.end(), [](const ObjectStyle& s) {
        return s.lines[LineKind::kIntersection].enabled;
      });
  if (want_crossings) {
    sw.lap();
    std::vector<const TriMesh*> ptrs;
    Bounds all;
    for (size_t i = 0; i < meshes.size(); ++i) {
      ptrs.push_back(&meshes[i]);
      const Bounds b = computeBounds(meshes[i].positions);
      all = i == 0 ? b : unionBounds(all, b);
    }
    const auto segments = intersections(ptrs);
    for (size_t i = 0; i < meshes.size() && i < segments.size(); ++i)
      chainIntersections(segments[i], 1e-6f * std::max(all.radius, 1e-6f), crossings[i]);
    info.intersect_ms += sw.lap();
  }
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& obj = scene.objects[i];
    TriMesh& mesh = meshes[i];
    sw.lap();
    SceneDrawing::Object o;
    o.name = obj.name;
    o.style = styles[i];
    o.detail_factor = obj.detail_factor;
    o.input_vertices = input_vertices[i];
    o.input_faces = input_faces[i];
    o.intersections = std::move(crossings[i]);
    if (std::holds_alternative<FullDetail>(lod)) {
      o.drawing = std::make_unique<LodDrawing>(std::move(mesh), lines, pool);
    } else if (const auto* cluster = std::get_if<ClusteredDetail>(&lod)) {
      o.drawing = std::make_unique<LodDrawing>(std::move(mesh), cluster->params, lines, pool);
      info.cache_note = "vertex clustering";
    } else {
      const auto& pm_choice = std::get<ProgressiveDetail>(lod);
      std::string note;
      const uint64_t hash = meshContentHash(mesh);
      auto pm = loadOrBuildPm(mesh, hash, pm_choice.cache_dir, {}, progress ? progress(obj) : PmProgress{}, &note);
      if (!pm) return Error::runtime((obj.mesh.empty() ? obj.name : obj.mesh.string()) + ": " + pm.error().message);
      if (!info.cache_note.empty()) info.cache_note += "; ";
      info.cache_note += note;
      auto shared = std::make_shared<const ProgressiveMesh>(std::move(pm.value()));
      o.drawing = std::make_unique<LodDrawing>(std::move(mesh), std::move(shared), lines, pool);
    }
    info.pm_ms += sw.lap();
    drawing.add(std::move(o));
  }
  return drawing;
}

Result<std::unique_ptr<LoadedScene>> loadSceneDrawing(SceneInput input, const PmProgressFor& progress) {
  auto loaded = std::make_unique<LoadedScene>();
  auto drawing = buildSceneDrawing(input.scene, input.styles, input.detail.lod, input.view.line_params, loaded->build,
                                   {}, progress, input.intersections);
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
                             float fov_deg, float aspect, const OrbitView& start) {
  std::string name = choice.name_or_file;
  double duration = choice.duration;
  if (!choice.given && camera && camera->path) {
    name = *camera->path;
    if (camera->duration) duration = *camera->duration;
  }
  const auto& names = builtinPathNames();
  if (std::find(names.begin(), names.end(), name) != names.end() ||
      std::filesystem::path(name).extension() != ".json")  // unknown names get the usage error
    return builtinPath(name, bounds, fov_deg, aspect, duration, start);
  return loadCameraPath(name);
}

}  // namespace lodline
