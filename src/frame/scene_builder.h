// From a scene description (io/scene_file.h) and resolved parameters to the SceneDrawing a
// frame adapts and draws: every object's mesh loaded in world space, its level of detail
// (one choice for the scene: full detail, vertex clustering, or the progressive mesh from
// the cache, built and cached on first use), its style and its detail factor; objects share
// one worker pool. `render`, `view`, `capture` and `bench` all build their scene here, so
// they draw the same thing (docs/design.md §1).
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "core/camera.h"
#include "core/render_params.h"
#include "core/result.h"
#include "frame/camera_path.h"
#include "frame/scene_drawing.h"
#include "frame/temporal_smoothing.h"
#include "io/scene_file.h"
#include "lines/lines.h"
#include "lod/adaptive_mesh.h"
#include "lod/vertex_clustering.h"
#include "pm/progressive_mesh.h"

namespace lodline {

/// No level of detail: the input mesh as it is (`--full-detail`, `--lod none`).
struct FullDetail {};
/// View-dependent vertex clustering every frame (Pan, Zhou, Shi; `--lod cluster`).
struct ClusteredDetail {
  ClusterParams params;  ///< the pixel error (foveation and focus come from DetailParams)
};
/// The progressive mesh with image-area detail control (Jeong et al. 2005; `--lod pm`).
struct ProgressiveDetail {
  std::filesystem::path cache_dir;  ///< where progressive meshes are cached
};
/// The level of detail of every object of a scene. Default: the progressive mesh.
using LodChoice = std::variant<ProgressiveDetail, ClusteredDetail, FullDetail>;

/// "pm", "cluster" or "none" (the values of --lod).
const char* lodChoiceName(const LodChoice& lod);

/// Everything a frame needs that does not depend on the model (parsed from the command
/// line and the scene file's settings by the app).
struct ResolvedView {
  std::filesystem::path model;  ///< the input: a mesh, scene (.json) or glTF file
  FrameParams frame;            ///< size, background, multisampling, light
  ObjectStyle style;            ///< the default style of the objects
  LineParams line_params;       ///< thresholds of the line kinds (which kinds: style.lines)
  OrbitView orbit;
  bool orbit_given = false;     ///< --view was given (else: the default framing)
  float fov_deg = 35.0f;
};

/// Detail control and temporal smoothing.
struct ResolvedDetail {
  LodChoice lod;
  DetailParams params;
  SmoothingParams smoothing;
  std::string detail_map_file;  ///< the --detail-map file (empty: none), for writing scenes back
  float detail_map_scale = 8.0f;
  int max_adapt_frames = 300;   ///< adaptation steps at most before a still image
};

/// What building a scene cost and did.
struct SceneBuildInfo {
  double load_ms = 0.0;    ///< reading and checking mesh files
  double intersect_ms = 0.0;  ///< finding where the surfaces cross
  double pm_ms = 0.0;      ///< progressive meshes from the cache or built
  std::string cache_note;  ///< what happened to the progressive-mesh caches
};

/// Where the objects' surfaces cross: for `meshes` (world space, full detail), segment
/// endpoints in pairs per mesh (cgal/intersections.h gives one).
using IntersectionFinder =
    std::function<std::vector<std::vector<glm::vec3>>(std::span<const TriMesh* const> meshes)>;

/// A step between loading an object's mesh and building its level of detail (the hybrid
/// benchmark's static pre-simplification). Errors name the object.
using MeshPrepare = std::function<Result<TriMesh>(TriMesh mesh, const SceneObject& object)>;
/// Progress of one object's progressive-mesh build (e.g. a progress bar); may return {}.
using PmProgressFor = std::function<PmProgress(const SceneObject& object)>;

/// Builds the drawing of `scene`: object i is loaded (loadObjectMesh), passed through
/// `prepare` if given, and drawn in styles[i] (styles.size() == scene.objects.size()) with
/// the level of detail `lod`. When `intersections` is given and some object draws the
/// intersection kind, the crossings of the loaded meshes become the objects' intersection
/// strokes (SceneDrawing::Object::intersections). Errors name the object's file.
Result<SceneDrawing> buildSceneDrawing(const Scene& scene, std::span<const ObjectStyle> styles, const LodChoice& lod,
                                       const LineParams& lines, SceneBuildInfo& info, const MeshPrepare& prepare = {},
                                       const PmProgressFor& progress = {},
                                       const IntersectionFinder& intersections = {});

/// Chains intersection segments (endpoint pairs) into strokes of kind kIntersection:
/// endpoints closer than `weld` (world units) are one point.
void chainIntersections(std::span<const glm::vec3> segments, float weld, StrokeSet& out);

/// A scene described and resolved, not yet loaded: what the app makes of its input file,
/// the command line and the scene's settings.
struct SceneInput {
  Scene scene;
  std::vector<ObjectStyle> styles;  ///< one per scene object
  ResolvedView view;                ///< the scene's light already in view.frame
  ResolvedDetail detail;
  IntersectionFinder intersections;  ///< how crossings are found (empty: none)
};

/// What a command needs to draw its input.
struct LoadedScene {
  Scene scene;             ///< the description, as read (the viewer writes it back)
  ResolvedView view;       ///< frame parameters
  ResolvedDetail detail;
  SceneDrawing drawing;    ///< one object per scene object, styles resolved
  SceneBuildInfo build;
  /// The input's camera unless the command line gave --view: the scene file's view, pose or
  /// path; none: frame the scene with ResolvedView::orbit.
  std::optional<SceneCamera> camera;
};

/// Builds the scene of `input` (buildSceneDrawing with input.detail.lod).
Result<std::unique_ptr<LoadedScene>> loadSceneDrawing(SceneInput input, const PmProgressFor& progress = {});

/// The frame's camera for an image of aspect `aspect`: the scene's camera (a path at its
/// start time), else the orbit of ResolvedView around the scene's bounds; clip planes fitted.
Result<Camera> initialCamera(const LoadedScene& loaded, float aspect);

/// What a command asked of its camera path.
struct PathChoice {
  std::string name_or_file = "orbit";  ///< a built-in path's name or a path file (.json)
  bool given = false;     ///< given on the command line (else the scene file's path wins)
  double duration = 8.0;  ///< a built-in path's length, seconds
};

/// The camera path of a capture or walkthrough: `choice`, or the scene camera's path when
/// the command line gave none, around `bounds` (the scene's) with a vertical field of view of
/// `fov_deg` for images of aspect `aspect`; a built-in path starts from `start` (--view).
Result<CameraPath> scenePath(const PathChoice& choice, const Bounds& bounds, const std::optional<SceneCamera>& camera,
                             float fov_deg, float aspect, const OrbitView& start = {});

}  // namespace lodline
