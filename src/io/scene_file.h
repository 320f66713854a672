// Scene files: several objects, each a mesh with its own transform, detail factor on T
// (Jeong et al. 2005 §3.1, "the background is drawn with less detail than the character")
// and style, plus optional render settings, camera and light. The format is JSON,
// documented in docs/scenes.md; glTF 2.0 files (io/load_gltf.h) are scenes too.
//
// This file reads and checks the description only (keys, types, paths, transforms);
// meshes are loaded later, by the caller, from SceneObject::mesh (or taken from
// SceneObject::preloaded for glTF nodes). Every error names the file and the key, e.g.
// "street.json: objects[2].scale: must be > 0". It also writes scenes back
// (writeSceneFile), so the format has one home.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "core/mesh.h"
#include "core/result.h"
#include "io/mesh_paint.h"

namespace lodline {

/// One object of a scene, ready to load.
struct SceneObject {
  /// Unique within the scene: the file's "name", else the mesh file's stem (glTF: the
  /// node's name), made unique by a "#2", "#3", ... suffix.
  std::string name;
  /// The mesh file, resolved against the folder of the scene file that names it.
  std::filesystem::path mesh;
  /// For glTF meshes: the node whose mesh this object is (-1 for other formats).
  int gltf_node = -1;
  /// The mesh itself when it is already in memory (glTF nodes, in node space); null: read
  /// `mesh` with loadMesh().
  std::shared_ptr<const TriMesh> preloaded;
  /// Model → world: the object's translate · rotate · scale, composed with the transforms
  /// of the scene files that include it (and, for glTF, of the node's ancestors).
  glm::mat4 transform{1.0f};
  /// The same without a glTF node's own transform (equal to `transform` for other meshes):
  /// what a scene file written back gives as the object's "matrix".
  glm::mat4 placement{1.0f};
  /// Factor on the target area T for this object (Jeong §3.1 per-object detail); products
  /// of nested includes. Default 1; > 1 draws the object coarser.
  float detail_factor = 1.0f;
  /// "paint": regions of the mesh (its own coordinates) that get materials of their own, so
  /// meshes without materials get material lines (io/mesh_paint.h); applied by loadObjectMesh.
  std::vector<PaintRegion> paint;
  /// Style keys given for this object, by render option name ("style", "lines",
  /// "line-style", "line-width", "chamfer", "chamfer-radius", "hidden-lines"), values as
  /// written; the caller resolves them like the command-line options of the same name.
  nlohmann::json style = nlohmann::json::object();
  /// The object's entry as written in its scene file (for writing a scene back, e.g. the
  /// viewer's "save view"); empty for objects that come from a glTF file.
  nlohmann::json source = nlohmann::json::object();
  /// Where the object was defined, for messages: "scene.json: objects[1]".
  std::string where;
};

/// A camera given by a scene file. Exactly one of the three forms is set.
struct SceneCamera {
  /// "view": "AZ,EL,DIST" as --view (azimuth, elevation in degrees; distance in radii of
  /// the scene's bounding sphere, 0 = frame the scene).
  std::optional<std::string> view;
  /// "eye"/"target"/"up": an explicit camera in world units.
  bool explicit_pose = false;
  glm::vec3 eye{0.0f, 0.0f, 3.0f}, target{0.0f}, up{0.0f, 1.0f, 0.0f};
  /// "path": a built-in path name (orbit, zoom-out, dolly, flyover) or a path file resolved
  /// against the scene file's folder; "duration" its length for built-in paths, seconds.
  std::optional<std::string> path;
  std::optional<double> duration;
  /// "fov": vertical field of view, degrees (all forms).
  std::optional<float> fov_deg;
};

struct Scene {
  std::filesystem::path file;  ///< the scene file (or the mesh / glTF file it stands for)
  std::vector<SceneObject> objects;
  /// Render settings by long option name without dashes ("target-area": 16, "size":
  /// "1280x720", ...): applied like command-line options, which take precedence. Keys are
  /// checked by the caller against the command's options.
  nlohmann::json settings = nlohmann::json::object();
  std::optional<SceneCamera> camera;
  /// "light": {"direction": [x, y, z]}: towards the key light, eye space (toon and shaded
  /// styles). Unset: the styles' defaults.
  std::optional<glm::vec3> light_dir_eye;
};

/// True for paths lodline reads as scenes rather than single meshes: .json, .gltf, .glb.
bool isSceneFile(const std::filesystem::path& path);

/// Reads a scene: a .json scene file (with its includes; glTF meshes it names are read
/// too), a .gltf/.glb file (one object per mesh node), or any other mesh file (a scene of
/// that one object; the mesh is not read here).
Result<Scene> loadScene(const std::filesystem::path& path);

/// The world-space mesh of one object: read from its file (or taken from the glTF already
/// read), painted (SceneObject::paint), its transform applied, validated (a transform that
/// overflows is an error naming the mesh and the object).
Result<TriMesh> loadObjectMesh(const SceneObject& object);

/// Reads a scene from JSON text; `file` names it in errors and resolves relative paths.
Result<Scene> parseScene(const std::string& text, const std::filesystem::path& file);

/// `file` as a path relative to `folder` (absolute when no relative path exists), the form
/// in which scene files name other files.
std::string pathRelativeTo(const std::filesystem::path& file, const std::filesystem::path& folder);

/// Writes `scene` as a scene file at `path` (atomically; errors name the file) that
/// loadScene() reads back as the same objects, settings, camera and light: each object
/// with its name, its mesh file relative to `path`'s folder (and glTF node), its placement
/// as a "matrix" (when not the identity), its detail factor and its style keys; the camera
/// as a view, a pose or a path. `description` goes into the file's "description". The
/// settings are written as they are (path-valued ones must already be relative to `path`'s
/// folder).
Status writeSceneFile(const std::filesystem::path& path, const Scene& scene, const std::string& description = {});

/// The model → world matrix of translate `t`, rotation `r` and scale `s`: T·R·S.
glm::mat4 composeTransform(glm::vec3 t, const glm::mat4& r, glm::vec3 s);

/// The 16 numbers of a "matrix" entry (column-major, as glTF) for `m`.
nlohmann::json matrixJson(const glm::mat4& m);

/// Rotation of Euler angles in degrees, applied about X, then Y, then Z (R = Rz·Ry·Rx).
glm::mat4 eulerRotation(glm::vec3 degrees);

/// Applies `transform` to the positions of `mesh` in place. A transform that mirrors
/// (negative determinant) also reverses the faces' winding so they keep facing outwards.
void transformMesh(TriMesh& mesh, const glm::mat4& transform);

}  // namespace lodline
