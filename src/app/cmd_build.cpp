// `lodline build MODEL [-o FILE]`: builds the progressive mesh of a model (Hoppe 1996/1998,
// quadric-error half-edge collapses; see src/pm) into the cache used by render/view/capture,
// or into FILE.
#include <iostream>
#include <memory>

#include "app/commands.h"
#include "cgal/simplify.h"
#include "app/model.h"
#include "core/timer.h"
#include "io/load_mesh.h"
#include "io/scene_file.h"
#include "pm/pm_file.h"

namespace lodline {

Command addBuildCommand(CLI::App& parent) {
  struct Opts {
    std::string model;
    std::string output;
    std::string cache_dir;
    bool force = false;
    std::string pre_simplify;  ///< E% of the diagonal; empty: off
    std::string mesh_out;      ///< where the pre-simplified mesh is written (.off)
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = parent.add_subcommand(
      "build", "Build (or refresh) the cached progressive mesh of a model, or write it to -o FILE");
  cmd->add_option("model", o->model,
                  "Mesh file (.off, .obj, .ply, .stl), or a scene (.json, .gltf, .glb): every object's progressive mesh")
      ->required();
  cmd->add_option("-o,--output", o->output, "Write the progressive mesh to this file instead of the cache");
  cmd->add_option("--cache-dir", o->cache_dir,
                  "Cache directory (default $XDG_CACHE_HOME/lodline or ~/.cache/lodline)");
  cmd->add_flag("--force", o->force, "Rebuild even if the cache is valid");
  cmd->add_option("--pre-simplify", o->pre_simplify,
                  "First simplify within E% of the bounding-box diagonal (Pan/Zhou/Shi E_s, e.g. 0.02%) and build "
                  "the progressive mesh of the result; needs --mesh-out");
  cmd->add_option("--mesh-out", o->mesh_out,
                  "With --pre-simplify: write the simplified mesh here (.off); render/view it to use the cache");
  return {cmd, [o]() -> int {
            Stopwatch sw;
            if (isSceneFile(o->model)) {
              // A scene: the progressive mesh of every object (world space) into the cache.
              if (!o->output.empty() || !o->pre_simplify.empty() || !o->mesh_out.empty())
                return reportError(Error::usage("build: -o, --pre-simplify and --mesh-out take a single mesh, not a scene"));
              auto scene = loadScene(o->model);
              if (!scene) return reportError(scene.error());
              const std::filesystem::path dir = o->cache_dir.empty() ? defaultCacheDir() : std::filesystem::path(o->cache_dir);
              for (const SceneObject& obj : scene->objects) {
                auto mesh = loadObjectMesh(obj);
                if (!mesh) return reportError(mesh.error());
                const uint64_t hash = meshContentHash(*mesh);
                std::string note;
                const auto progress = buildProgressBar("lodline: building " + obj.name);
                auto pm = o->force ? buildProgressiveMesh(*mesh, {}, progress) : loadOrBuildPm(*mesh, hash, dir, {}, progress, &note);
                if (!pm) return reportError(Error::runtime(obj.mesh.string() + ": " + pm.error().message));
                if (o->force) {
                  std::error_code ec;
                  std::filesystem::create_directories(dir, ec);
                  if (Status s = savePm(pmCachePath(dir, hash), *pm); !s) return reportError(s.error());
                  note = "wrote " + pmCachePath(dir, hash).string();
                }
                std::cout << obj.name << ": " << note << "; " << mesh->faceCount() << " faces -> base mesh of "
                          << pm->base_faces.size() << " faces (" << sw.lap() << " ms)\n";
              }
              return 0;
            }
            auto mesh = loadMesh(o->model);
            if (!mesh) return reportError(mesh.error());
            if (!o->pre_simplify.empty()) {
              auto bound = parsePercent(o->pre_simplify, "--pre-simplify");
              if (!bound) return reportError(bound.error());
              if (o->mesh_out.empty())
                return reportError(Error::usage("--pre-simplify needs --mesh-out FILE.off for the simplified mesh"));
              auto simplified = simplifyMesh(*mesh, *bound, o->model);
              if (!simplified) return reportError(simplified.error());
              if (Status s = saveOff(o->mesh_out, simplified->mesh); !s) return reportError(s.error());
              std::cout << "pre-simplified " << mesh->faceCount() << " -> " << simplified->mesh.faceCount()
                        << " faces within " << 100.0 * *bound << "% (E_s " << 100.0 * simplified->e_s_rel
                        << "% of the diagonal, Hausdorff " << simplified->hausdorff << "); wrote " << o->mesh_out
                        << "\n";
              // Reload what was written, so the cache key is that of the file render/view will read.
              mesh = loadMesh(o->mesh_out);
              if (!mesh) return reportError(mesh.error());
            } else if (!o->mesh_out.empty()) {
              return reportError(Error::usage("--mesh-out is only used with --pre-simplify"));
            }
            const double load_ms = sw.lap();
            const uint64_t hash = meshContentHash(*mesh);
            const auto progress = buildProgressBar("lodline: building " + std::filesystem::path(o->model).filename().string());
            if (!o->output.empty() || o->force) {
              auto pm = buildProgressiveMesh(*mesh, {}, progress);
              if (!pm) return reportError(Error::runtime(o->model + ": " + pm.error().message));
              const double build_ms = sw.lap();
              const std::filesystem::path out =
                  !o->output.empty() ? std::filesystem::path(o->output)
                                     : pmCachePath(o->cache_dir.empty() ? defaultCacheDir() : std::filesystem::path(o->cache_dir), hash);
              if (o->output.empty()) {
                std::error_code ec;
                std::filesystem::create_directories(out.parent_path(), ec);
              }
              if (Status s = savePm(out, *pm); !s) return reportError(s.error());
              std::cout << "wrote " << out.string() << ": " << mesh->faceCount() << " faces -> base mesh of "
                        << pm->base_faces.size() << " faces, " << pm->splits.size() << " vertex splits; load "
                        << load_ms << " ms, build " << build_ms << " ms\n";
              return 0;
            }
            std::string note;
            const std::filesystem::path dir = o->cache_dir.empty() ? defaultCacheDir() : std::filesystem::path(o->cache_dir);
            auto pm = loadOrBuildPm(*mesh, hash, dir, {}, progress, &note);
            if (!pm) return reportError(Error::runtime(o->model + ": " + pm.error().message));
            std::cout << note << "; " << mesh->faceCount() << " faces -> base mesh of " << pm->base_faces.size()
                      << " faces, " << pm->splits.size() << " vertex splits (" << sw.lap() << " ms)\n";
            return 0;
          }};
}

}  // namespace lodline
