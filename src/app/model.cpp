#include "app/model.h"

#include <cstdio>
#include <cstdlib>
#include <set>
#include <sstream>

#include <unistd.h>

#include "cgal/intersections.h"
#include "core/timer.h"
#include "io/image.h"

namespace lodline {

void addDetailOptions(CLI::App& cmd, DetailOptions& o) {
  cmd.add_flag("--full-detail", o.full_detail,
               "Draw the full-detail mesh (no progressive mesh, no detail control); same as --lod none");
  cmd.add_option("--lod", o.lod,
                 "Level of detail: pm (progressive mesh, detail control by --target-area), cluster "
                 "(view-dependent vertex clustering every frame, Pan/Zhou/Shi, by --pixel-error) or none")
      ->capture_default_str();
  cmd.add_option("--pixel-error", o.pixel_error,
                 "--lod cluster: pixel error K in px^2 (vertices within a K-px^2 square at their depth merge; "
                 "--foveation scales it away from --focus)")
      ->capture_default_str();
  cmd.add_option("--target-area", o.target_area,
                 "Target image area T of visible triangles in px^2 (Jeong et al. 2005); larger = coarser")
      ->capture_default_str();
  cmd.add_option("--t-collapse", o.t_c, "Collapse below t_c*T")->capture_default_str();
  cmd.add_option("--t-split", o.t_s, "Split above t_s*T (needs 2*t_c < t_s)")->capture_default_str();
  cmd.add_option("--detail-map", o.detail_map,
                 "Grayscale PNG over the image: a pixel of value v multiplies T by (v/255)*scale "
                 "(white = coarse, black = finest); any size, stretched over the image");
  cmd.add_option("--detail-map-scale", o.detail_map_scale, "Factor of T at a white detail-map pixel")
      ->capture_default_str();
  cmd.add_option("--depth-falloff", o.depth_falloff,
                 "T grows as (distance/focus distance)^X with depth (terrain); 0 = off")
      ->capture_default_str();
  cmd.add_option("--foveation", o.foveation,
                 "T grows away from the focus point by ((90/(90-q))^2)^X, q the angle; 0 = off")
      ->capture_default_str();
  cmd.add_option("--focus", o.focus, "Foveation focus as X,Y pixels (default: image centre)");
  cmd.add_option("--object-factor", o.object_factor, "Per-object factor on T (e.g. 3 for a background object)")
      ->capture_default_str();
  cmd.add_option("--geomorphs", o.geomorphs, "Real-time geomorphs (Jeong et al. 2005 §3.2): on or off")
      ->capture_default_str();
  cmd.add_option("--morph-time", o.morph_time, "Geomorph transition time in seconds")->capture_default_str();
  cmd.add_option("--adapt-budget", o.adapt_budget_ms,
                 "Milliseconds the adaptation may take per frame (view, capture); past it the rest of the mesh "
                 "waits for the next frames, which resume where it stopped (Hoppe 1997 §5). 0 = no budget")
      ->capture_default_str();
  cmd.add_option("--min-suggestive-length", o.min_suggestive_length,
                 "Under detail control, suggestive contours shorter on screen than this times sqrt(T) px are not "
                 "drawn (below the chosen scale); 0 = all")
      ->capture_default_str();
  cmd.add_option("--smoothing", o.smoothing,
                 "Temporal smoothing of normals, kr and Dw kr over frames (Jeong et al. 2005 §3.3): on or off "
                 "(view and capture; a still render uses the current frame's values)")
      ->capture_default_str();
  cmd.add_option("--smoothing-alpha", o.smoothing_alpha, "Fraction of a new value reached within --smoothing-time")
      ->capture_default_str();
  cmd.add_option("--smoothing-time", o.smoothing_time, "Seconds to reach --smoothing-alpha of a new value")
      ->capture_default_str();
  cmd.add_option("--cache-dir", o.cache_dir,
                 "Where progressive meshes are cached (default $XDG_CACHE_HOME/lodline or ~/.cache/lodline)");
}

std::filesystem::path defaultCacheDir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "lodline";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "lodline";
  return std::filesystem::temp_directory_path() / "lodline-cache";
}

std::shared_ptr<const DetailMap> detailMapFromImage(const Image& img, float scale) {
  auto map = std::make_shared<DetailMap>();
  map->width = img.width;
  map->height = img.height;
  map->values.resize(static_cast<size_t>(img.width) * img.height);
  for (size_t i = 0; i < map->values.size(); ++i) {
    const uint8_t* px = &img.rgba[i * 4];
    const float grey = (0.299f * px[0] + 0.587f * px[1] + 0.114f * px[2]) / 255.0f;
    map->values[i] = grey * scale;
  }
  return map;
}

Result<std::shared_ptr<const DetailMap>> readDetailMap(const std::filesystem::path& path, float scale) {
  auto img = readPng(path, kMaxDetailMapPixels);
  if (!img) return img.error();
  return detailMapFromImage(*img, scale);
}

Result<ResolvedDetail> resolveDetailOptions(const DetailOptions& o) {
  ResolvedDetail r;
  if (o.lod != "pm" && o.lod != "cluster" && o.lod != "none")
    return Error::usage("--lod: expected pm, cluster or none, got '" + o.lod + "'");
  if (o.full_detail && o.lod == "cluster") return Error::usage("--full-detail and --lod cluster exclude each other");
  if (!(o.pixel_error > 0.0f && o.pixel_error <= 1e4f)) return Error::usage("--pixel-error: must be in (0, 10000] px^2");
  if (o.full_detail || o.lod == "none") {
    r.lod = FullDetail{};
  } else if (o.lod == "cluster") {
    ClusteredDetail c;
    c.params.pixel_error = o.pixel_error;
    r.lod = c;
  } else {
    r.lod = ProgressiveDetail{o.cache_dir.empty() ? defaultCacheDir() : std::filesystem::path(o.cache_dir)};
  }
  r.max_adapt_frames = o.max_adapt_frames;
  DetailParams& p = r.params;
  if (!(o.target_area > 0.0f && o.target_area < 1e7f)) return Error::usage("--target-area: must be > 0 px^2");
  p.target_area = o.target_area;
  if (!(o.t_c > 0.0f && 2.0f * o.t_c < o.t_s))
    return Error::usage("--t-collapse/--t-split: need 0 < 2*t_c < t_s (defaults 0.7 and 1.42)");
  p.t_c = o.t_c;
  p.t_s = o.t_s;
  if (!(o.depth_falloff >= 0.0f && o.depth_falloff <= 8.0f)) return Error::usage("--depth-falloff: must be in [0, 8]");
  p.depth_falloff = o.depth_falloff;
  if (!(o.foveation >= 0.0f && o.foveation <= 8.0f)) return Error::usage("--foveation: must be in [0, 8]");
  p.foveation = o.foveation;
  if (!o.focus.empty()) {
    float x = 0, y = 0;
    char comma = 0;
    std::istringstream in(o.focus);
    if (!(in >> x >> comma >> y) || comma != ',' || !in.eof())
      return Error::usage("--focus: expected X,Y in pixels, got '" + o.focus + "'");
    p.focus_px = {x, y};
  }
  if (!(o.object_factor > 0.0f)) return Error::usage("--object-factor: must be > 0");
  p.object_factor = o.object_factor;
  if (o.geomorphs != "on" && o.geomorphs != "off") return Error::usage("--geomorphs: expected on or off");
  p.geomorphs = o.geomorphs == "on";
  if (!(o.morph_time > 0.0f && o.morph_time <= 60.0f)) return Error::usage("--morph-time: must be in (0, 60] s");
  p.morph_time = o.morph_time;
  if (!(o.adapt_budget_ms >= 0.0f && o.adapt_budget_ms <= 1000.0f))
    return Error::usage("--adapt-budget: must be in [0, 1000] ms");
  p.max_adapt_ms = o.adapt_budget_ms;
  if (!(o.min_suggestive_length >= 0.0f && o.min_suggestive_length <= 8.0f))
    return Error::usage("--min-suggestive-length: must be in [0, 8]");
  p.min_suggestive_length = o.min_suggestive_length;
  if (!(o.detail_map_scale > 0.0f)) return Error::usage("--detail-map-scale: must be > 0");
  if (!o.detail_map.empty()) {
    auto map = readDetailMap(o.detail_map, o.detail_map_scale);
    if (!map) return map.error();
    p.detail_map = std::move(map.value());
    r.detail_map_file = o.detail_map;
  }
  r.detail_map_scale = o.detail_map_scale;
  if (o.smoothing != "on" && o.smoothing != "off") return Error::usage("--smoothing: expected on or off");
  if (!(o.smoothing_alpha > 0.0f && o.smoothing_alpha < 1.0f)) return Error::usage("--smoothing-alpha: must be in (0, 1)");
  if (!(o.smoothing_time > 0.0f && o.smoothing_time <= 60.0f)) return Error::usage("--smoothing-time: must be in (0, 60] s");
  r.smoothing = {o.smoothing == "on", o.smoothing_alpha, o.smoothing_time};
  return r;
}

PmProgress buildProgressBar(const std::string& label) {
  if (!isatty(STDERR_FILENO)) return {};
  auto clock = std::make_shared<Stopwatch>();
  return [clock, label](float f) {
    if (clock->elapsed() < 1000.0 && f < 1.0f) return;
    const int width = 30, filled = static_cast<int>(f * width);
    std::fprintf(stderr, "\r%s [%s%s] %3d%%", label.c_str(), std::string(filled, '#').c_str(),
                 std::string(width - filled, ' ').c_str(), static_cast<int>(f * 100.0f));
    if (f >= 1.0f) std::fputc('\n', stderr);
    std::fflush(stderr);
  };
}

namespace {

// Options of lodline's drawing commands that only some of them have: a scene's settings may
// name them (they apply where the command has them). The shared ones are found on `cmd`.
const std::set<std::string>& commandSpecificOptions() {
  static const std::set<std::string> names = {"max-adapt-frames", "backend", "context", "fps", "duration",
                                              "path", "play"};
  return names;
}

// Settings that are not drawing parameters: outputs and the input belong to the command line.
const std::set<std::string>& forbiddenSettings() {
  static const std::set<std::string> names = {"model", "output", "o", "svg", "stats", "metrics", "frames", "help"};
  return names;
}

}  // namespace

bool givenOnCommandLine(const CLI::App& cmd, const std::string& name) {
  const CLI::Option* opt = cmd.get_option_no_throw("--" + name);
  return opt && opt->count() > 0;
}

Status applySceneSettings(const Scene& scene, CLI::App& cmd) {
  const std::string file = scene.file.string();
  for (const auto& [key, value] : scene.settings.items()) {
    const std::string where = file + ": settings." + key;
    if (forbiddenSettings().count(key)) return Error::runtime(where + ": not a scene setting (give it on the command line)");
    CLI::Option* opt = cmd.get_option_no_throw("--" + key);
    if (!opt) {
      // Shared drawing options every drawing command has; the rest are listed above.
      CLI::App scratch;
      ViewOptions v;
      DetailOptions d;
      addViewOptions(scratch, v);
      addDetailOptions(scratch, d);
      if (scratch.get_option_no_throw("--" + key) || commandSpecificOptions().count(key)) continue;
      return Error::runtime(where + ": unknown setting (settings are render options by their long name, e.g. "
                                    "\"target-area\"; see `lodline render --help`)");
    }
    if (opt->count() > 0) continue;  // the command line wins
    std::vector<std::string> values;
    if (value.is_array()) {
      for (const auto& e : value) values.push_back(e.get<std::string>());
    } else if (value.is_string()) {
      values.push_back(value.get<std::string>());
    } else if (value.is_boolean()) {
      values.push_back(value.get<bool>() ? "true" : "false");
    } else {
      std::ostringstream s;
      s.precision(9);
      if (value.is_number_integer()) s << value.get<long long>();
      else s << value.get<double>();
      values.push_back(s.str());
    }
    // File settings are relative to the scene file, as its mesh paths are.
    if ((key == "detail-map" || key == "play" ||
         ((key == "path" || key == "stroke-style") && !values.empty() &&
          std::filesystem::path(values[0]).extension() == ".json")) &&
        !values.empty() && std::filesystem::path(values[0]).is_relative())
      values[0] = (scene.file.parent_path() / values[0]).string();
    try {
      opt->clear();
      for (const std::string& v : values) opt->add_result(v);
      opt->run_callback();
    } catch (const CLI::Error& e) {
      return Error::runtime(where + ": " + e.what());
    }
  }
  return {};
}

Result<std::vector<ObjectStyle>> resolveObjectStyles(const Scene& scene, const ViewOptions& view) {
  std::vector<ObjectStyle> styles;
  for (const SceneObject& obj : scene.objects) {
    auto style = resolveObjectStyle(view, obj.style, obj.where);
    if (!style) return style.error();
    styles.push_back(*style);
  }
  return styles;
}

Result<std::filesystem::path> defaultModelPath() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return Error::runtime("/proc/self/exe: cannot find the lodline program to find the default model");
  const std::filesystem::path dir = exe.parent_path();
  // Installed (PREFIX/bin → PREFIX/share/lodline), or built in the source tree (build/ → models/).
  for (const auto& candidate : {dir / ".." / "share" / "lodline" / "models" / "knot.off", dir / ".." / "models" / "knot.off"})
    if (std::filesystem::is_regular_file(candidate, ec)) return candidate.lexically_normal();
  return Error::usage("give a MODEL: the default model (knot.off) is neither in " +
                      (dir / ".." / "share" / "lodline" / "models").lexically_normal().string() + " nor in " +
                      (dir / ".." / "models").lexically_normal().string());
}

Result<SceneInput> readInput(CLI::App& cmd, ViewOptions& view, DetailOptions& detail, double* read_ms) {
  if (view.models.empty()) {
    auto model = defaultModelPath();
    if (!model) return model.error();
    view.models = {model->string()};
  }
  if (view.models.size() != 1)
    return Error::usage("give exactly one MODEL (a mesh, scene or glTF file; got " + std::to_string(view.models.size()) +
                        ")");
  Stopwatch sw;
  auto scene = loadScene(std::filesystem::path(view.models[0]));
  if (!scene) return scene.error();
  if (read_ms) *read_ms = sw.lap();
  return resolveInput(cmd, view, detail, std::move(scene.value()));
}

Result<SceneInput> resolveInput(CLI::App& cmd, ViewOptions& view, DetailOptions& detail, Scene scene) {
  SceneInput in;
  in.scene = std::move(scene);
  if (Status s = applySceneSettings(in.scene, cmd); !s) return s.error();
  auto resolved = resolveViewOptions(view);
  if (!resolved) return resolved.error();
  in.view = std::move(resolved.value());
  auto resolved_detail = resolveDetailOptions(detail);
  if (!resolved_detail) return resolved_detail.error();
  in.detail = std::move(resolved_detail.value());
  // The command line's --view and --fov win over the scene's camera.
  auto& camera = in.scene.camera;
  if (camera && givenOnCommandLine(cmd, "view")) camera.reset();
  if (camera && camera->fov_deg && !givenOnCommandLine(cmd, "fov")) in.view.fov_deg = *camera->fov_deg;
  if (camera && camera->view) {
    auto orbit = parseOrbitView(*camera->view);
    if (!orbit) return Error::runtime(in.scene.file.string() + ": camera.view: " + orbit.error().message);
    in.view.orbit = *orbit;
    in.view.orbit_given = true;
  }
  // The scene's light is the frame's (toon, shaded and chamfer highlights alike).
  if (in.scene.light_dir_eye) in.view.frame.light_dir_eye = *in.scene.light_dir_eye;
  in.view.line_params.light_dir_eye = in.view.frame.light_dir_eye;  // isophotes see the same light
  auto styles = resolveObjectStyles(in.scene, view);
  if (!styles) return styles.error();
  in.styles = std::move(styles.value());
  const std::filesystem::path cache_dir = detail.cache_dir.empty() ? defaultCacheDir() : std::filesystem::path(detail.cache_dir);
  in.intersections = [cache_dir](std::span<const TriMesh* const> meshes) {
    return findIntersectionSegmentsCached(meshes, cache_dir);
  };
  return in;
}

Result<std::unique_ptr<LoadedScene>> loadInput(CLI::App& cmd, ViewOptions& view, DetailOptions& detail) {
  double read_ms = 0.0;
  auto input = readInput(cmd, view, detail, &read_ms);
  if (!input) return input.error();
  auto progress = [](const SceneObject& obj) {
    return buildProgressBar("lodline: building progressive mesh of " + obj.name);
  };
  auto loaded = loadSceneDrawing(std::move(input.value()), progress);
  if (!loaded) return loaded.error();
  (*loaded)->build.load_ms += read_ms;
  return loaded;
}

}  // namespace lodline
