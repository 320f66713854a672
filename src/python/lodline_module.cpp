// The `lodline` Python module (pybind11): meshes from files or numpy arrays, renders that
// return numpy buffers, the `--stats` dict, the visible strokes and the SVG, and capture
// iterators that yield frames with their coherence metrics (docs/python.md). Like the
// commands of src/app, it only parses: keyword arguments become the command line's options,
// parsed by the same CLI11 definitions (app/options.h), and the work is done by present/.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "app/model.h"
#include "app/options.h"
#include "core/line_kind.h"
#include "core/timer.h"
#include "io/image.h"
#include "io/load_mesh.h"
#include "io/scene_file.h"
#include "present/capture.h"
#include "present/frame_report.h"
#include "present/presenter.h"
#include "present/still.h"
#include "present/svg_output.h"

namespace py = pybind11;

namespace lodline {
namespace {

// A lodline Error as a C++ exception, turned into lodline.Error / lodline.UsageError.
struct PyError : std::runtime_error {
  explicit PyError(const Error& e) : std::runtime_error(e.message) {}
};
struct PyUsageError : std::runtime_error {
  explicit PyUsageError(const std::string& m) : std::runtime_error(m) {}
};

[[noreturn]] void raise(const Error& e) {
  if (e.exitCode() == 2) throw PyUsageError(e.message);
  throw PyError(e);
}
template <typename T>
T take(Result<T> r) {
  if (!r) raise(r.error());
  return std::move(r.value());
}
void check(const Status& s) {
  if (!s) raise(s.error());
}

// ---- meshes and scenes -------------------------------------------------------------------

// An immutable triangle mesh (lodline.Mesh).
struct PyMesh {
  std::shared_ptr<const TriMesh> mesh;
  std::string name = "mesh";
};

template <typename T>
void copyVertices(const py::array& a, std::vector<glm::vec3>& out) {
  auto v = a.unchecked<T, 2>();
  out.resize(static_cast<size_t>(v.shape(0)));
  for (py::ssize_t i = 0; i < v.shape(0); ++i)
    out[static_cast<size_t>(i)] = glm::vec3(static_cast<float>(v(i, 0)), static_cast<float>(v(i, 1)),
                                            static_cast<float>(v(i, 2)));
}

template <typename T>
bool copyFaces(const py::array& a, size_t vertex_count, std::vector<std::array<uint32_t, 3>>& out, std::string& bad) {
  auto f = a.unchecked<T, 2>();
  out.resize(static_cast<size_t>(f.shape(0)));
  for (py::ssize_t i = 0; i < f.shape(0); ++i)
    for (int c = 0; c < 3; ++c) {
      const T x = f(i, c);
      if (x < 0 || static_cast<uint64_t>(x) >= vertex_count) {
        bad = "F[" + std::to_string(i) + ", " + std::to_string(c) + "] = " + std::to_string(static_cast<long long>(x)) +
              " is not a vertex index (0.." + std::to_string(static_cast<long long>(vertex_count) - 1) + ")";
        return false;
      }
      out[static_cast<size_t>(i)][static_cast<size_t>(c)] = static_cast<uint32_t>(x);
    }
  return true;
}

PyMesh meshFromArrays(const py::array& V, const py::array& F, const std::string& name) {
  const std::string what = name.empty() ? "Mesh(V, F)" : name;
  if (V.ndim() != 2 || V.shape(1) != 3)
    throw PyUsageError(what + ": V must be an N×3 array of vertex positions");
  if (F.ndim() != 2 || F.shape(1) != 3) throw PyUsageError(what + ": F must be an M×3 array of vertex indices");
  if (V.shape(0) == 0 || F.shape(0) == 0) throw PyUsageError(what + ": the mesh has no vertices or no faces");
  auto mesh = std::make_shared<TriMesh>();
  const char vk = V.dtype().kind();
  if (V.dtype().is(py::dtype::of<float>()))
    copyVertices<float>(py::array_t<float, py::array::c_style | py::array::forcecast>(V), mesh->positions);
  else if (V.dtype().is(py::dtype::of<double>()))
    copyVertices<double>(py::array_t<double, py::array::c_style | py::array::forcecast>(V), mesh->positions);
  else
    throw PyUsageError(what + ": V must be float32 or float64, got dtype kind '" + std::string(1, vk) + "'");
  for (size_t i = 0; i < mesh->positions.size(); ++i) {
    const glm::vec3& p = mesh->positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw PyUsageError(what + ": vertex " + std::to_string(i) + " has a coordinate that is not finite");
  }
  std::string bad;
  const char fk = F.dtype().kind();
  if (fk != 'i' && fk != 'u') throw PyUsageError(what + ": F must be an integer array");
  const bool ok = copyFaces<int64_t>(py::array_t<int64_t, py::array::c_style | py::array::forcecast>(F),
                                     mesh->positions.size(), mesh->faces, bad);
  if (!ok) throw PyUsageError(what + ": " + bad);
  check(validateMesh(*mesh, what));
  return {std::move(mesh), name.empty() ? "mesh" : name};
}

PyMesh meshFromFile(const std::filesystem::path& path) {
  auto m = loadMesh(path);
  if (!m) raise(m.error());
  return {std::make_shared<const TriMesh>(std::move(m.value())), path.stem().string()};
}

// A scene built in Python (lodline.Scene): objects from files or meshes, settings, camera.
struct PyScene {
  Scene scene;
  std::set<std::string> names;
};

glm::mat4 matrixOf(const py::object& m) {
  if (m.is_none()) return glm::mat4(1.0f);
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>(m);
  if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4) throw PyUsageError("matrix: expected a 4×4 array");
  glm::mat4 out(1.0f);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[c][r] = static_cast<float>(a.at(r, c));  // row-major in, glm column-major
  return out;
}

nlohmann::json toJson(const py::handle& h) {
  py::module_ json = py::module_::import("json");
  return nlohmann::json::parse(py::str(json.attr("dumps")(h)).cast<std::string>());
}
py::object fromJson(const nlohmann::json& j) {
  py::module_ json = py::module_::import("json");
  return json.attr("loads")(j.dump());
}

void sceneAdd(PyScene& s, const py::object& model, const py::object& matrix, const std::string& name,
              float detail_factor, const py::dict& style) {
  SceneObject o;
  if (py::isinstance<PyMesh>(model)) {
    const PyMesh& m = model.cast<const PyMesh&>();
    o.preloaded = m.mesh;
    o.name = name.empty() ? m.name : name;
  } else {
    o.mesh = std::filesystem::path(py::str(model).cast<std::string>());
    if (isSceneFile(o.mesh)) throw PyUsageError(o.mesh.string() + ": Scene.add takes mesh files or Meshes, not scenes");
    o.name = name.empty() ? o.mesh.stem().string() : name;
  }
  if (!(detail_factor > 0.0f)) throw PyUsageError("Scene.add: detail_factor must be > 0");
  const std::string base = o.name;
  for (int k = 2; s.names.count(o.name); ++k) o.name = base + "#" + std::to_string(k);
  s.names.insert(o.name);
  o.transform = o.placement = matrixOf(matrix);
  o.detail_factor = detail_factor;
  for (auto item : style) {
    std::string key = py::str(item.first).cast<std::string>();
    for (char& c : key)
      if (c == '_') c = '-';
    o.style[key] = toJson(item.second);
  }
  o.where = "Scene: objects[" + std::to_string(s.scene.objects.size()) + "]";
  s.scene.objects.push_back(std::move(o));
}

// ---- keyword arguments as command-line options ---------------------------------------------

// The options a render or capture parses: the command line's own definitions.
struct ParsedOptions {
  CLI::App app{"lodline (Python)"};
  ViewOptions view;
  DetailOptions detail;
  CapturePathOptions capture;
  std::vector<std::string> args;  ///< the options as given, for the scene cache's key
};

std::string valueText(const std::string& name, const py::handle& v) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "on" : "off";
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v)) return py::str(v).cast<std::string>();
  if (py::hasattr(v, "__fspath__")) return py::str(v.attr("__fspath__")()).cast<std::string>();
  if (py::isinstance<py::sequence>(v)) {
    const std::string sep = name == "size" ? "x" : name == "frames" ? ":" : ",";
    std::string out;
    for (auto x : v.cast<py::sequence>()) out += (out.empty() ? "" : sep) + valueText(name, x);
    return out;
  }
  return py::str(v).cast<std::string>();
}

// Appends `--name value` for each keyword argument, checked against `app`'s options.
void appendOptions(const CLI::App& app, const py::dict& kwargs, std::vector<std::string>& args) {
  for (auto item : kwargs) {
    std::string name = py::str(item.first).cast<std::string>();
    for (char& c : name)
      if (c == '_') c = '-';
    const py::handle v = item.second;
    if (v.is_none()) continue;
    const CLI::Option* opt = app.get_option_no_throw("--" + name);
    if (!opt) throw PyUsageError("unknown option '" + py::str(item.first).cast<std::string>() + "'");
    if (opt->get_expected_max() == 0) {  // a flag
      if (v.cast<bool>()) args.push_back("--" + name);
      continue;
    }
    // Repeatable options take a list as several occurrences.
    if (opt->get_items_expected_max() > 1 && py::isinstance<py::list>(v)) {
      for (auto x : v.cast<py::list>()) {
        args.push_back("--" + name);
        args.push_back(valueText(name, x));
      }
      continue;
    }
    args.push_back("--" + name);
    args.push_back(valueText(name, v));
  }
}

// Keyword arguments the module handles itself (not command-line options).
const std::set<std::string> kOwnArgs = {"detail_map", "camera", "surface", "metrics"};

std::unique_ptr<ParsedOptions> parseOptions(const std::optional<std::string>& model_path, const py::dict& kwargs,
                                            bool capture) {
  auto p = std::make_unique<ParsedOptions>();
  addViewOptions(p->app, p->view);
  addDetailOptions(p->app, p->detail);
  p->app.add_option("--max-adapt-frames", p->detail.max_adapt_frames, "");
  if (capture) addCaptureOptions(p->app, p->capture);
  py::dict options;
  for (auto item : kwargs)
    if (!kOwnArgs.count(py::str(item.first).cast<std::string>())) options[item.first] = item.second;
  std::vector<std::string> args;
  if (model_path) args.push_back(*model_path);
  appendOptions(p->app, options, args);
  p->args = args;
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 parses a reversed vector
  try {
    p->app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    throw PyUsageError(e.what());
  }
  return p;
}

// ---- the renderer --------------------------------------------------------------------------

// A detail map from a numpy array: uint8 H×W (grey, as the PNG of the same pixels is read,
// times detail_map_scale) or float H×W (the factors themselves).
std::shared_ptr<const DetailMap> detailMapOf(const py::array& a, float scale) {
  if (a.ndim() != 2 || a.shape(0) < 1 || a.shape(1) < 1)
    throw PyUsageError("detail_map: expected an H×W array (uint8 grey levels or float factors)");
  const int h = static_cast<int>(a.shape(0)), w = static_cast<int>(a.shape(1));
  if (a.dtype().is(py::dtype::of<uint8_t>())) {
    auto g = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>(a);
    Image img(w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        uint8_t* px = img.pixel(x, y);
        px[0] = px[1] = px[2] = g.at(y, x);
        px[3] = 255;
      }
    return detailMapFromImage(img, scale);
  }
  if (a.dtype().kind() != 'f') throw PyUsageError("detail_map: expected a uint8 or float array");
  auto f = py::array_t<float, py::array::c_style | py::array::forcecast>(a);
  auto map = std::make_shared<DetailMap>();
  map->width = w;
  map->height = h;
  map->values.resize(static_cast<size_t>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float v = f.at(y, x);
      if (!(std::isfinite(v) && v >= 0.0f)) throw PyUsageError("detail_map: factors must be finite and >= 0");
      map->values[static_cast<size_t>(y) * w + x] = v;
    }
  return map;
}

// What a render returns (lodline.Frame).
struct PyFrame {
  py::array_t<uint8_t> image;
  py::array_t<float> depth;
  py::object surface = py::none();
  py::object objects = py::none();
  py::dict stats;
  py::list strokes;
  py::list stroke_kinds;
  py::list stroke_objects;
  std::string svg;
};

// What a capture yields (lodline.CaptureFrame).
struct PyCaptureFrame {
  int64_t index = 0;
  py::array_t<uint8_t> image;
  py::dict metrics;
};

py::array_t<uint8_t> imageArray(const Image& im) {
  py::array_t<uint8_t> a({im.height, im.width, 4});
  std::memcpy(a.mutable_data(), im.rgba.data(), im.rgba.size());
  return a;
}

// The CSV row as a dict of the header's columns (numbers where they parse).
py::dict metricsDict(const std::string& row) {
  std::string header = metricsCsvHeader();
  if (!header.empty() && header.back() == '\n') header.pop_back();
  std::vector<std::string> names, values;
  std::stringstream hs(header), rs(row);
  for (std::string x; std::getline(hs, x, ',');) names.push_back(x);
  std::string line = row;
  if (!line.empty() && line.back() == '\n') line.pop_back();
  std::stringstream ls(line);
  for (std::string x; std::getline(ls, x, ',');) values.push_back(x);
  py::dict d;
  for (size_t i = 0; i < names.size() && i < values.size(); ++i) {
    char* end = nullptr;
    const double v = std::strtod(values[i].c_str(), &end);
    if (end && *end == '\0' && !values[i].empty())
      d[py::str(names[i])] = (names[i] == "frame") ? py::object(py::int_(static_cast<long long>(v))) : py::object(py::float_(v));
    else
      d[py::str(names[i])] = values[i];
  }
  return d;
}

class PyRenderer;

// A capture in progress (lodline.Capture): owns its scene and presenter.
struct PyCapture {
  std::unique_ptr<LoadedScene> loaded;
  std::unique_ptr<ScenePresenter> presenter;
  std::unique_ptr<CaptureRun> run;
  int64_t first = 0, end = 0;
  std::mutex mutex;
};

class PyRenderer {
 public:
  PyRenderer(const std::string& context, const std::string& backend, bool reuse)
      : context_(take(parseContextBackend(context))), backend_(take(parsePresenterBackend(backend))), reuse_(reuse) {}

  PyFrame render(const py::object& model, const py::kwargs& kwargs) {
    Stopwatch total;
    auto input = prepare(model, kwargs, false);
    const bool want_surface = kwargs.contains("surface") && kwargs["surface"].cast<bool>();
    StillFrame still;
    nlohmann::json stats;
    std::string svg;
    SurfaceImage surface;
    std::vector<StrokeRuns> visible;
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(mutex_);
      LoadedScene& loaded = sceneFor(std::move(input));
      Stopwatch setup;
      ScenePresenter& p = presenterFor(loaded);
      const double ms_setup = setup.elapsed();
      still = take(drawStill(loaded, p));
      const double before = total.elapsed() - setup.elapsed();
      stats = stillStats(loaded, p, still, ms_setup, before);
      svg = take(frameSvgText(loaded.drawing, p));
      visible = p.visible();
      if (want_surface) check(p.readSurface(surface));
      depth_ = p.depth();
    }
    PyFrame f;
    f.image = imageArray(still.image);
    f.depth = py::array_t<float>({depth_.height, depth_.width});
    std::memcpy(f.depth.mutable_data(), depth_.depth.data(), depth_.depth.size() * sizeof(float));
    if (want_surface) {
      py::array_t<float> pos({surface.height, surface.width, 3});
      py::array_t<int32_t> obj({surface.height, surface.width});
      float* pp = pos.mutable_data();
      int32_t* op = obj.mutable_data();
      for (size_t i = 0; i < surface.texels.size(); ++i) {
        const glm::vec4& t = surface.texels[i];
        pp[3 * i] = t.x;
        pp[3 * i + 1] = t.y;
        pp[3 * i + 2] = t.z;
        op[i] = static_cast<int32_t>(std::lround(t.w)) - 1;
      }
      f.surface = pos;
      f.objects = obj;
    }
    f.stats = fromJson(stats);
    for (size_t o = 0; o < visible.size(); ++o) {
      const StrokeRuns& r = visible[o];
      for (size_t s = 0; s < r.strokeCount(); ++s) {
        const uint32_t a = r.offsets[s], b = r.offsets[s + 1];
        py::array_t<float> pts({static_cast<py::ssize_t>(b - a), static_cast<py::ssize_t>(2)});
        float* d = pts.mutable_data();
        for (uint32_t i = a; i < b; ++i) {
          d[2 * (i - a)] = r.points[i].x;
          d[2 * (i - a) + 1] = r.points[i].y;
        }
        f.strokes.append(pts);
        f.stroke_kinds.append(py::str(lineKindName(r.kinds[s])));
        f.stroke_objects.append(py::int_(o));
      }
    }
    f.svg = std::move(svg);
    return f;
  }

  std::shared_ptr<PyCapture> capture(const py::object& model, const py::kwargs& kwargs) {
    auto input = prepare(model, kwargs, true);
    const bool measure = !kwargs.contains("metrics") || kwargs["metrics"].cast<bool>();
    auto c = std::make_shared<PyCapture>();
    {
      py::gil_scoped_release release;
      c->loaded = take(loadSceneDrawing(std::move(input.scene)));
      LoadedScene& l = *c->loaded;
      const CapturePathOptions& co = input.options->capture;
      CaptureRequest rq;
      rq.context = context_;
      auto path = take(scenePath({co.path, givenOnCommandLine(input.options->app, "path"), co.duration},
                                 l.drawing.bounds(), l.camera, l.view.fov_deg, l.view.frame.aspect(), l.view.orbit));
      check(resolveCaptureOptions(co, std::move(path), rq));
      c->presenter = take(createPresenter(PresenterBackend::kGl, context_, l.drawing, l.view.frame));
      c->run = take(CaptureRun::start(l, *c->presenter, rq, measure));
      c->first = rq.range.first;
      c->end = rq.range.end;
    }
    return c;
  }

 private:
  struct Prepared {
    std::unique_ptr<ParsedOptions> options;
    SceneInput scene;
    std::string key;  ///< what the loaded drawing depends on
  };

  // Parses the keyword arguments and resolves the input (cheap: no mesh is read).
  Prepared prepare(const py::object& model, const py::kwargs& kwargs, bool capture) {
    Prepared p;
    std::optional<std::string> path;
    std::string identity;
    std::optional<Scene> scene;
    if (py::isinstance<PyMesh>(model)) {
      const PyMesh& m = model.cast<const PyMesh&>();
      Scene s;
      s.file = m.name;
      SceneObject o;
      o.name = m.name;
      o.preloaded = m.mesh;
      o.where = m.name;
      s.objects.push_back(std::move(o));
      scene = std::move(s);
      identity = "mesh:" + std::to_string(reinterpret_cast<uintptr_t>(m.mesh.get()));
    } else if (py::isinstance<PyScene>(model)) {
      const PyScene& s = model.cast<const PyScene&>();
      if (s.scene.objects.empty()) throw PyUsageError("Scene: add at least one object");
      scene = s.scene;
      identity = "scene:" + std::to_string(reinterpret_cast<uintptr_t>(&s)) + ":" + std::to_string(s.scene.objects.size());
    } else {
      path = py::str(py::module_::import("os").attr("fspath")(model)).cast<std::string>();
      std::error_code ec;
      const auto t = std::filesystem::last_write_time(*path, ec);
      identity = "file:" + std::filesystem::absolute(*path).string() + ":" +
                 std::to_string(ec ? 0 : t.time_since_epoch().count());
    }
    p.options = parseOptions(path, kwargs, capture);
    ParsedOptions& o = *p.options;
    if (scene) {
      o.view.models = {scene->file.string()};
      if (kwargs.contains("camera")) scene->camera = cameraOf(kwargs["camera"]);
      p.scene = take(resolveInput(o.app, o.view, o.detail, std::move(*scene)));
    } else {
      p.scene = take(readInput(o.app, o.view, o.detail));
      if (kwargs.contains("camera")) p.scene.scene.camera = cameraOf(kwargs["camera"]);
    }
    if (kwargs.contains("detail_map") && !kwargs["detail_map"].is_none()) {
      py::object dm = kwargs["detail_map"];
      if (py::isinstance<py::array>(dm)) {
        p.scene.detail.params.detail_map = detailMapOf(dm.cast<py::array>(), o.detail.detail_map_scale);
      } else {
        o.detail.detail_map = py::str(py::module_::import("os").attr("fspath")(dm)).cast<std::string>();
        p.scene.detail.params.detail_map = take(readDetailMap(o.detail.detail_map, o.detail.detail_map_scale));
        p.scene.detail.detail_map_file = o.detail.detail_map;
      }
    }
    // Options that only change the camera, the image or the detail parameters leave the
    // loaded drawing as it is; any other option is part of the key.
    static const std::set<std::string> kPerFrame = {
        "--view", "--fov", "--size", "--background", "--msaa", "--target-area", "--t-c", "--t-s",
        "--detail-map-scale", "--depth-falloff", "--foveation", "--focus", "--object-factor", "--max-adapt-frames",
        "--geomorphs", "--morph-time", "--adapt-budget", "--min-suggestive-length", "--smoothing", "--smoothing-alpha", "--smoothing-time"};
    p.key = identity;
    for (size_t i = path ? 1 : 0; i < o.args.size(); ++i) {
      if (kPerFrame.count(o.args[i]) && i + 1 < o.args.size()) {
        ++i;
        continue;
      }
      p.key += "\n" + o.args[i];
    }
    return p;
  }

  static SceneCamera cameraOf(const py::handle& h) {
    if (py::isinstance<py::array>(h)) {
      // A 4×4 view matrix (world to eye, OpenGL's convention: the eye looks down −z).
      const glm::mat4 v = matrixOf(py::reinterpret_borrow<py::object>(h));
      const glm::mat4 inv = glm::inverse(v);
      SceneCamera c;
      c.explicit_pose = true;
      c.eye = glm::vec3(inv[3]);
      c.target = c.eye - glm::normalize(glm::vec3(inv[2]));
      c.up = glm::normalize(glm::vec3(inv[1]));
      if (!std::isfinite(c.eye.x + c.eye.y + c.eye.z + c.target.x + c.up.x))
        throw PyUsageError("camera: the view matrix is not invertible");
      return c;
    }
    if (!py::isinstance<py::dict>(h))
      throw PyUsageError("camera: expected a 4×4 view matrix or a dict with eye, target and up (and optionally fov)");
    const py::dict d = h.cast<py::dict>();
    SceneCamera c;
    c.explicit_pose = true;
    auto vec = [&](const char* key, glm::vec3 fallback) {
      if (!d.contains(key)) return fallback;
      auto v = d[key].cast<std::vector<double>>();
      if (v.size() != 3) throw PyUsageError(std::string("camera: ") + key + " must have 3 numbers");
      return glm::vec3(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
    };
    if (!d.contains("eye") || !d.contains("target")) throw PyUsageError("camera: eye and target are required");
    c.eye = vec("eye", c.eye);
    c.target = vec("target", c.target);
    c.up = vec("up", c.up);
    if (d.contains("fov")) c.fov_deg = d["fov"].cast<float>();
    return c;
  }

  LoadedScene& sceneFor(Prepared input) {
    if (reuse_ && scene_ && input.key == scene_key_) {
      // The same drawing: the camera, image and detail parameters are this call's.
      scene_->view = std::move(input.scene.view);
      scene_->detail = std::move(input.scene.detail);
      scene_->camera = input.scene.scene.camera;
      if (scene_->camera && scene_->view.orbit_given && !scene_->camera->explicit_pose) scene_->camera.reset();
      return *scene_;
    }
    scene_.reset();  // free the previous scene before loading the next
    presenter_.reset();
    scene_ = take(loadSceneDrawing(std::move(input.scene)));
    scene_key_ = input.key;
    return *scene_;
  }

  ScenePresenter& presenterFor(const LoadedScene& loaded) {
    const FrameParams& f = loaded.view.frame;
    const std::string key = std::to_string(f.width) + "x" + std::to_string(f.height) + "/" + std::to_string(f.msaa) +
                            "/" + std::to_string(loaded.drawing.size());
    if (presenter_ && key == presenter_key_) {
      check(presenter_->check(loaded.drawing));
      return *presenter_;
    }
    presenter_.reset();
    presenter_ = take(createPresenter(backend_, context_, loaded.drawing, f));
    presenter_key_ = key;
    return *presenter_;
  }

  ContextBackend context_;
  PresenterBackend backend_;
  bool reuse_ = true;
  std::mutex mutex_;
  std::unique_ptr<LoadedScene> scene_;
  std::string scene_key_;
  std::unique_ptr<ScenePresenter> presenter_;
  std::string presenter_key_;
  DepthImage depth_;
};

PyCaptureFrame captureNext(PyCapture& c) {
  CapturedFrame f;
  {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(c.mutex);
    if (!c.run || c.run->done()) {
      py::gil_scoped_acquire acquire;
      throw py::stop_iteration();
    }
    f = take(c.run->next());
    if (c.run->done()) {
      // Free the context and the scene as soon as the last frame is out.
      c.run.reset();
      c.presenter.reset();
      c.loaded.reset();
    }
  }
  PyCaptureFrame out;
  out.index = f.index;
  out.image = imageArray(f.image);
  if (f.measured) out.metrics = metricsDict(f.metrics_row);
  return out;
}

}  // namespace
}  // namespace lodline

PYBIND11_MODULE(lodline, m) {
  using namespace lodline;
  m.doc() = "lodline: line drawings of 3D meshes at a chosen scale in the image (docs/python.md)";
  m.attr("__version__") = "0.1.0";

  static py::exception<PyError> error(m, "Error", PyExc_RuntimeError);
  static py::exception<PyUsageError> usage_error(m, "UsageError", error.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const PyUsageError& e) {
      usage_error(e.what());
    } catch (const PyError& e) {
      error(e.what());
    }
  });

  m.def(
      "render",
      [m](const py::object& model, const py::kwargs& kwargs) mutable {
        if (!py::hasattr(m, "_default_renderer")) m.attr("_default_renderer") = m.attr("Renderer")();
        return m.attr("_default_renderer").attr("render")(model, **kwargs);
      },
      py::arg("model"), "render(model, **options): Renderer.render with the module's default renderer");
  m.def(
      "capture",
      [m](const py::object& model, const py::kwargs& kwargs) mutable {
        if (!py::hasattr(m, "_default_renderer")) m.attr("_default_renderer") = m.attr("Renderer")();
        return m.attr("_default_renderer").attr("capture")(model, **kwargs);
      },
      py::arg("model"), "capture(model, **options): Renderer.capture with the module's default renderer");

  m.def(
      "read_png",
      [](const py::object& path) {
        auto im = take(readPng(py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>()));
        return imageArray(im);
      },
      py::arg("path"), "Reads a PNG as an H×W×4 uint8 array (as lodline reads detail maps and images)");
  m.def(
      "write_png",
      [](const py::object& path, const py::array& a) {
        if (a.dtype().kind() != 'u' || a.itemsize() != 1 || (a.ndim() != 2 && a.ndim() != 3) ||
            (a.ndim() == 3 && a.shape(2) != 1 && a.shape(2) != 3 && a.shape(2) != 4))
          throw PyUsageError("write_png: expected an H×W, H×W×3 or H×W×4 uint8 array");
        auto c = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>(a);
        const int h = static_cast<int>(a.shape(0)), w = static_cast<int>(a.shape(1));
        const int ch = a.ndim() == 2 ? 1 : static_cast<int>(a.shape(2));
        Image im(w, h);
        const uint8_t* src = c.data();
        for (size_t i = 0; i < static_cast<size_t>(w) * h; ++i) {
          const uint8_t* s = src + i * ch;
          uint8_t* d = &im.rgba[i * 4];
          d[0] = s[0];
          d[1] = ch >= 3 ? s[1] : s[0];
          d[2] = ch >= 3 ? s[2] : s[0];
          d[3] = ch == 4 ? s[3] : 255;
        }
        check(writePng(py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>(), im));
      },
      py::arg("path"), py::arg("image"), "Writes a uint8 grey, RGB or RGBA array as a PNG (atomically)");

  py::class_<PyMesh>(m, "Mesh", "An immutable triangle mesh: Mesh(V, F) from numpy arrays, or Mesh.load(path)")
      .def(py::init([](const py::array& V, const py::array& F, const std::string& name) {
             return meshFromArrays(V, F, name);
           }),
           py::arg("V"), py::arg("F"), py::arg("name") = "",
           "V: N×3 float32/float64 positions; F: M×3 integer vertex indices. Checked as files are.")
      .def_static("load", [](const py::object& path) {
        return meshFromFile(py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>());
      }, py::arg("path"), "Reads a mesh file (OFF, OBJ, PLY, STL)")
      .def_property_readonly("vertex_count", [](const PyMesh& s) { return s.mesh->positions.size(); })
      .def_property_readonly("face_count", [](const PyMesh& s) { return s.mesh->faces.size(); })
      .def_property_readonly("V", [](const PyMesh& s) {
        py::array_t<float> a({static_cast<py::ssize_t>(s.mesh->positions.size()), static_cast<py::ssize_t>(3)});
        std::memcpy(a.mutable_data(), s.mesh->positions.data(), s.mesh->positions.size() * sizeof(glm::vec3));
        return a;
      })
      .def_property_readonly("F", [](const PyMesh& s) {
        py::array_t<uint32_t> a({static_cast<py::ssize_t>(s.mesh->faces.size()), static_cast<py::ssize_t>(3)});
        std::memcpy(a.mutable_data(), s.mesh->faces.data(), s.mesh->faces.size() * sizeof(s.mesh->faces[0]));
        return a;
      })
      .def_readonly("name", &PyMesh::name)
      .def("__repr__", [](const PyMesh& s) {
        return "<lodline.Mesh '" + s.name + "' " + std::to_string(s.mesh->positions.size()) + " vertices, " +
               std::to_string(s.mesh->faces.size()) + " faces>";
      });

  py::class_<PyScene>(m, "Scene", "A scene built in Python: objects placed by 4×4 matrices, with per-object "
                                  "detail factors and styles (render option names as keys)")
      .def(py::init([](const py::dict& settings) {
             PyScene s;
             s.scene.file = "Scene";
             for (auto item : settings) {
               std::string key = py::str(item.first).cast<std::string>();
               for (char& c : key)
                 if (c == '_') c = '-';
               s.scene.settings[key] = toJson(item.second);
             }
             return s;
           }),
           py::arg("settings") = py::dict())
      .def("add", &sceneAdd, py::arg("model"), py::arg("matrix") = py::none(), py::arg("name") = "",
           py::arg("detail_factor") = 1.0f, py::arg("style") = py::dict(),
           "Adds an object: a mesh file or a Mesh, placed by `matrix` (4×4, row-major, model to world)")
      .def("__len__", [](const PyScene& s) { return s.scene.objects.size(); });

  py::class_<PyFrame>(m, "Frame", "A rendered frame")
      .def_readonly("image", &PyFrame::image, "H×W×4 uint8 RGBA, row 0 = top")
      .def_readonly("depth", &PyFrame::depth, "H×W float32 window depth in [0, 1] (1: background), row 0 = top")
      .def_readonly("surface", &PyFrame::surface, "H×W×3 float32 world positions (render(..., surface=True))")
      .def_readonly("objects", &PyFrame::objects, "H×W int32 object index per pixel, -1 background (surface=True)")
      .def_readonly("stats", &PyFrame::stats, "the --stats dict (docs/stats.md)")
      .def_readonly("strokes", &PyFrame::strokes, "visible strokes: N×2 float32 pixel coordinates each")
      .def_readonly("stroke_kinds", &PyFrame::stroke_kinds, "each stroke's line kind")
      .def_readonly("stroke_objects", &PyFrame::stroke_objects, "each stroke's object index")
      .def_readonly("svg", &PyFrame::svg, "the visible strokes as an SVG document (as --svg writes)");

  py::class_<PyCaptureFrame>(m, "CaptureFrame", "One frame of a capture")
      .def_readonly("index", &PyCaptureFrame::index)
      .def_readonly("image", &PyCaptureFrame::image, "H×W×4 uint8 RGBA")
      .def_readonly("metrics", &PyCaptureFrame::metrics, "the frame's row of the --metrics CSV (docs/capture.md)");

  py::class_<PyCapture, std::shared_ptr<PyCapture>>(m, "Capture", "An iterator over a capture's frames")
      .def("__iter__", [](std::shared_ptr<PyCapture> c) { return c; })
      .def("__next__", [](PyCapture& c) { return captureNext(c); })
      .def("__len__", [](const PyCapture& c) { return static_cast<size_t>(c.end - c.first); });

  py::class_<PyRenderer>(m, "Renderer",
                         "Renders headlessly, keeping its OpenGL context, and the loaded scene when only the camera, "
                         "size or detail parameters change, between calls")
      .def(py::init<const std::string&, const std::string&, bool>(), py::arg("context") = "auto",
           py::arg("backend") = "gl", py::arg("reuse") = true)
      .def("render", &PyRenderer::render, py::arg("model"),
           "render(model, **options) -> Frame. `model`: a path, Mesh or Scene; options: the command line's long "
           "options with '_' for '-' (size=(W, H), view=(az, el, dist), target_area=16, lines='contour,suggestive', "
           "full_detail=True, ...), detail_map (a path or an H×W array), camera (a 4×4 view matrix or "
           "dict(eye, target, up, fov)), "
           "surface=True for the surface buffer")
      .def("capture", &PyRenderer::capture, py::arg("model"),
           "capture(model, path='orbit', duration=8, fps=30, frames='A:B', metrics=True, **options) -> Capture, "
           "an iterator of CaptureFrame");
}
