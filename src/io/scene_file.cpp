#include "io/scene_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include "io/atomic_file.h"
#include "core/printable.h"
#include "io/input_check.h"
#include "io/load_gltf.h"
#include "io/load_mesh.h"

namespace lodline {
namespace {

constexpr size_t kMaxObjects = 256;     // objects in a scene, includes expanded
constexpr int kMaxIncludeDepth = 16;    // nested scene includes
constexpr size_t kMaxSceneBytes = 16u << 20;
constexpr size_t kMaxPaintRegions = 64;  // per object

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Style keys an object may carry: JSON key → render option name.
const std::map<std::string, std::string>& styleKeys() {
  static const std::map<std::string, std::string> keys = {
      {"style", "style"},         {"lines", "lines"},     {"line_style", "line-style"},
      {"line_width", "line-width"}, {"chamfer", "chamfer"}, {"chamfer_radius", "chamfer-radius"},
      {"hidden_lines", "hidden-lines"}, {"stroke_style", "stroke-style"}};
  return keys;
}

struct Reader {
  std::vector<std::filesystem::path> stack;  // canonical paths of the files being read
  std::vector<SceneObject> objects;
};

Error bad(const std::string& where, const std::string& what) { return Error::runtime(where + ": " + what); }

// A key or path taken from the file, made fit for a one-line error message.
std::string enclosed(char mark, const std::string& text, size_t max_chars) {
  std::string out(1, mark);
  out += printableText(text, max_chars);
  out += mark;
  return out;
}
std::string quoted(const std::string& text) { return enclosed('"', text, 80); }
std::string shownPath(const std::filesystem::path& p) { return enclosed('\'', p.string(), 300); }

Result<glm::vec3> readVec3(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3) return bad(where, "expected an array of 3 numbers");
  glm::vec3 v;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number()) return bad(where, "expected an array of 3 numbers");
    const double d = j[i].get<double>();
    if (!std::isfinite(d) || std::abs(d) > 1e30) return bad(where, "numbers must be finite (|x| <= 1e30)");
    v[i] = static_cast<float>(d);
  }
  return v;
}

Result<float> readNumber(const nlohmann::json& j, const std::string& where) {
  if (!j.is_number()) return bad(where, "expected a number");
  const double d = j.get<double>();
  if (!std::isfinite(d) || std::abs(d) > 1e30) return bad(where, "must be finite (|x| <= 1e30)");
  return static_cast<float>(d);
}

// translate / rotate / quaternion / scale of one object entry → model → world matrix.
Result<glm::mat4> readTransform(const nlohmann::json& o, const std::string& where) {
  if (o.contains("matrix")) {
    if (o.contains("translate") || o.contains("rotate") || o.contains("quaternion") || o.contains("scale"))
      return bad(where, "give either \"matrix\" or translate/rotate/quaternion/scale, not both");
    const auto& j = o["matrix"];
    const std::string w = where + ".matrix";
    if (!j.is_array() || j.size() != 16) return bad(w, "expected 16 numbers (column-major)");
    glm::mat4 m;
    for (int i = 0; i < 16; ++i) {
      auto n = readNumber(j[i], w);
      if (!n) return n.error();
      m[i / 4][i % 4] = *n;
    }
    if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f)
      return bad(w, "must be affine (last row 0, 0, 0, 1)");
    if (!(glm::determinant(glm::mat3(m)) > 0.0f)) return bad(w, "must not be singular or mirror (determinant > 0)");
    return m;
  }
  glm::vec3 t(0.0f), s(1.0f);
  glm::mat4 r(1.0f);
  if (o.contains("translate")) {
    auto v = readVec3(o["translate"], where + ".translate");
    if (!v) return v.error();
    t = *v;
  }
  if (o.contains("rotate") && o.contains("quaternion"))
    return bad(where, "give either \"rotate\" (Euler degrees) or \"quaternion\", not both");
  if (o.contains("rotate")) {
    auto v = readVec3(o["rotate"], where + ".rotate");
    if (!v) return v.error();
    r = eulerRotation(*v);
  }
  if (o.contains("quaternion")) {
    const auto& q = o["quaternion"];
    const std::string w = where + ".quaternion";
    if (!q.is_array() || q.size() != 4) return bad(w, "expected [x, y, z, w]");
    float c[4];
    for (int i = 0; i < 4; ++i) {
      auto n = readNumber(q[i], w);
      if (!n) return n.error();
      c[i] = *n;
    }
    const glm::quat quat(c[3], c[0], c[1], c[2]);
    const float len = glm::length(quat);
    if (!(len > 1e-6f)) return bad(w, "must not be zero");
    r = glm::mat4_cast(quat / len);
  }
  if (o.contains("scale")) {
    const auto& j = o["scale"];
    const std::string w = where + ".scale";
    if (j.is_number()) {
      auto n = readNumber(j, w);
      if (!n) return n.error();
      s = glm::vec3(*n);
    } else {
      auto v = readVec3(j, w);
      if (!v) return bad(w, "expected a number or an array of 3 numbers");
      s = *v;
    }
    if (!(s.x > 0.0f && s.y > 0.0f && s.z > 0.0f)) return bad(w, "must be > 0 (mirroring is not supported)");
  }
  return composeTransform(t, r, s);
}

// "paint": [{"plane": [a, b, c, d], "thickness": w}, ...] → the regions a·x + b·y + c·z ≥ d
// (or the slab of thickness w above that plane), in the mesh's coordinates.
Result<std::vector<PaintRegion>> readPaint(const nlohmann::json& o, const std::string& where) {
  std::vector<PaintRegion> out;
  if (!o.contains("paint")) return out;
  const auto& j = o["paint"];
  const std::string w = where + ".paint";
  if (!j.is_array() || j.empty() || j.size() > kMaxPaintRegions)
    return bad(w, "expected an array of 1 to " + std::to_string(kMaxPaintRegions) + " regions");
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string wi = w + "[" + std::to_string(i) + "]";
    if (!j[i].is_object()) return bad(wi, "expected {\"plane\": [a, b, c, d], \"thickness\": w}");
    for (const auto& [k, v] : j[i].items())
      if (k != "plane" && k != "thickness") return bad(wi, "unknown key " + quoted(k));
    const auto& p = j[i].value("plane", nlohmann::json());
    if (!p.is_array() || p.size() != 4)
      return bad(wi + ".plane", "expected [a, b, c, d]: the points with a*x + b*y + c*z >= d");
    PaintRegion r;
    float c[4];
    for (int k = 0; k < 4; ++k) {
      auto n = readNumber(p[k], wi + ".plane");
      if (!n) return n.error();
      c[k] = *n;
    }
    r.normal = {c[0], c[1], c[2]};
    if (!(glm::length(r.normal) > 0.0f)) return bad(wi + ".plane", "the normal (a, b, c) must not be zero");
    r.offset = c[3];
    if (j[i].contains("thickness")) {
      auto t = readNumber(j[i]["thickness"], wi + ".thickness");
      if (!t) return t.error();
      if (!(*t > 0.0f)) return bad(wi + ".thickness", "must be > 0 (leave it out to paint the half-space)");
      r.thickness = *t;
    }
    out.push_back(r);
  }
  return out;
}

Status readFile(const std::filesystem::path& path, std::string& text) {
  if (Status s = checkInputFile(path, "scene file"); !s) return s;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return Error::runtime(path.string() + ": cannot read (" + ec.message() + ")");
  if (size > kMaxSceneBytes) return Error::runtime(path.string() + ": scene file larger than 16 MB");
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error::runtime(path.string() + ": cannot open for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (!in.good() && !in.eof()) return Error::runtime(path.string() + ": read error");
  text = ss.str();
  return {};
}

Status readSceneText(Reader& r, const std::string& text, const std::filesystem::path& file, const glm::mat4& parent,
                     float parent_factor, const nlohmann::json& parent_style, Scene* top);

// Reads the scene file `path` as an include of the scene being read.
Status includeScene(Reader& r, const std::filesystem::path& path, const std::string& where, const glm::mat4& m,
                    float factor, const nlohmann::json& style) {
  std::error_code ec;
  const auto canon = std::filesystem::weakly_canonical(path, ec);
  for (const auto& p : r.stack)
    if (p == canon) {
      std::string cycle;
      for (const auto& q : r.stack) cycle += printableText(q.filename().string(), 60) + " -> ";
      return bad(where, "include cycle: " + cycle + printableText(canon.filename().string(), 60));
    }
  if (static_cast<int>(r.stack.size()) >= kMaxIncludeDepth)
    return bad(where, "includes nested deeper than " + std::to_string(kMaxIncludeDepth) + " levels");
  if (lower(path.extension().string()) != ".json") return bad(where, "an included scene must be a .json file");
  std::string text;
  if (Status s = readFile(path, text); !s) return bad(where, s.error().message);
  return readSceneText(r, text, path, m, factor, style, nullptr);
}

Status readObject(Reader& r, const nlohmann::json& o, const std::string& where, const std::filesystem::path& dir,
                  const glm::mat4& parent, float parent_factor, const nlohmann::json& parent_style) {
  if (!o.is_object()) return bad(where, "expected an object");
  static const std::set<std::string> known = {"name",   "mesh",       "scene", "gltf_node",    "translate",
                                              "matrix", "rotate",     "quaternion", "scale", "detail_factor", "paint"};
  for (const auto& [k, v] : o.items())
    if (!known.count(k) && !styleKeys().count(k)) return bad(where, "unknown key " + quoted(k));
  const bool has_mesh = o.contains("mesh"), has_scene = o.contains("scene");
  if (has_mesh == has_scene) return bad(where, "needs exactly one of \"mesh\" (a mesh file) or \"scene\" (a scene to include)");
  std::string name;
  if (o.contains("name")) {
    if (!o["name"].is_string() || o["name"].get<std::string>().empty()) return bad(where + ".name", "expected a non-empty string");
    name = o["name"].get<std::string>();
  }
  auto m = readTransform(o, where);
  if (!m) return m.error();
  const glm::mat4 transform = parent * *m;
  float factor = parent_factor;
  if (o.contains("detail_factor")) {
    auto f = readNumber(o["detail_factor"], where + ".detail_factor");
    if (!f) return f.error();
    if (!(*f > 0.0f)) return bad(where + ".detail_factor", "must be > 0");
    factor *= *f;
  }
  auto paint = readPaint(o, where);
  if (!paint) return paint.error();
  // Style: this entry's keys, then whatever an including entry gave and this one did not.
  nlohmann::json style = nlohmann::json::object();
  for (const auto& [key, option] : styleKeys()) {
    if (!o.contains(key)) continue;
    const auto& v = o[key];
    const bool ok = v.is_string() || v.is_number() ||
                    (key == "line_style" && v.is_array() &&
                     std::all_of(v.begin(), v.end(), [](const nlohmann::json& e) { return e.is_string(); }));
    if (!ok) return bad(where + "." + key, key == "line_style" ? "expected a string or an array of strings" : "expected a string or a number");
    style[option] = v;
    // A style file is relative to the scene file, as mesh paths are.
    if (key == "stroke_style" && v.is_string() && std::filesystem::path(v.get<std::string>()).extension() == ".json" &&
        std::filesystem::path(v.get<std::string>()).is_relative())
      style[option] = (dir / v.get<std::string>()).string();
  }
  for (const auto& [k, v] : parent_style.items())
    if (!style.contains(k)) style[k] = v;

  const std::string key = has_mesh ? "mesh" : "scene";
  if (!o[key].is_string() || o[key].get<std::string>().empty()) return bad(where + "." + key, "expected a file path");
  const std::filesystem::path file = dir / o[key].get<std::string>();
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return bad(where + "." + key, "no such file " + shownPath(file));
  if (!std::filesystem::is_regular_file(file, ec)) return bad(where + "." + key, shownPath(file) + " is not a regular file");
  if (has_scene) {
    if (o.contains("gltf_node")) return bad(where + ".gltf_node", "only for glTF meshes");
    if (o.contains("paint")) return bad(where + ".paint", "only for meshes (paint the objects of the included scene)");
    return includeScene(r, file, where + ".scene", transform, factor, style);
  }

  const std::string ext = lower(file.extension().string());
  int gltf_node = -1;
  if (o.contains("gltf_node")) {
    if (ext != ".gltf" && ext != ".glb") return bad(where + ".gltf_node", "only for .gltf and .glb meshes");
    if (!o["gltf_node"].is_number_integer() || o["gltf_node"].get<long long>() < 0)
      return bad(where + ".gltf_node", "expected a node index >= 0");
    gltf_node = static_cast<int>(std::min<long long>(o["gltf_node"].get<long long>(), INT32_MAX));
  }
  if (ext == ".json") return bad(where + ".mesh", "is a scene file: include scenes with \"scene\"");
  if (ext == ".gltf" || ext == ".glb") {
    auto nodes = loadGltf(file);
    if (!nodes) return bad(where + ".mesh", nodes.error().message);
    bool found = false;
    for (auto& g : *nodes) {
      if (gltf_node >= 0 && g.node != gltf_node) continue;
      found = true;
      SceneObject obj;
      obj.name = !name.empty() && (gltf_node >= 0 || nodes->size() == 1) ? name
                 : !name.empty()                                       ? name + "/" + g.name
                                                                       : g.name;
      obj.mesh = file;
      obj.gltf_node = g.node;
      obj.transform = transform * g.transform;
      obj.placement = transform;
      obj.preloaded = std::make_shared<const TriMesh>(std::move(g.mesh));
      obj.detail_factor = factor;
      obj.paint = *paint;
      obj.style = style;
      obj.source = o;
      obj.source["gltf_node"] = g.node;
      obj.where = where;
      r.objects.push_back(std::move(obj));
    }
    if (!found) return bad(where + ".gltf_node", "node " + std::to_string(gltf_node) + " has no triangle mesh");
  } else {
    SceneObject obj;
    obj.name = name.empty() ? file.stem().string() : name;
    obj.mesh = file;
    obj.transform = transform;
    obj.placement = transform;
    obj.detail_factor = factor;
    obj.paint = *paint;
    obj.style = style;
    obj.source = o;
    obj.where = where;
    r.objects.push_back(std::move(obj));
  }
  if (r.objects.size() > kMaxObjects)
    return bad(where, "more than " + std::to_string(kMaxObjects) + " objects in the scene");
  return {};
}

Result<SceneCamera> readCamera(const nlohmann::json& c, const std::string& where, const std::filesystem::path& dir) {
  if (!c.is_object()) return bad(where, "expected an object");
  static const std::set<std::string> known = {"view", "eye", "target", "up", "fov", "path", "duration"};
  for (const auto& [k, v] : c.items())
    if (!known.count(k)) return bad(where, "unknown key " + quoted(k));
  SceneCamera cam;
  const int forms = int(c.contains("view")) + int(c.contains("eye") || c.contains("target")) + int(c.contains("path"));
  if (forms > 1) return bad(where, "give one of \"view\", \"eye\"/\"target\" or \"path\"");
  if (c.contains("view")) {
    const auto& v = c["view"];
    if (v.is_string()) {
      cam.view = v.get<std::string>();
    } else {
      auto a = readVec3(v, where + ".view");
      if (!a) return bad(where + ".view", "expected \"AZ,EL,DIST\" or [az, el, dist]");
      std::ostringstream s;
      s.precision(9);
      s << a->x << ',' << a->y << ',' << a->z;
      cam.view = s.str();
    }
  }
  if (c.contains("eye") || c.contains("target")) {
    if (!c.contains("eye") || !c.contains("target")) return bad(where, "needs both \"eye\" and \"target\"");
    auto e = readVec3(c["eye"], where + ".eye");
    if (!e) return e.error();
    auto t = readVec3(c["target"], where + ".target");
    if (!t) return t.error();
    if (glm::length(*e - *t) <= 0.0f) return bad(where, "\"eye\" and \"target\" must differ");
    cam.explicit_pose = true;
    cam.eye = *e;
    cam.target = *t;
  }
  if (c.contains("up")) {
    if (!cam.explicit_pose) return bad(where + ".up", "only with \"eye\" and \"target\"");
    auto u = readVec3(c["up"], where + ".up");
    if (!u) return u.error();
    if (glm::length(glm::cross(*u, cam.target - cam.eye)) <= 0.0f)
      return bad(where + ".up", "must not be zero or parallel to the view direction");
    cam.up = *u;
  }
  if (c.contains("fov")) {
    auto f = readNumber(c["fov"], where + ".fov");
    if (!f) return f.error();
    if (!(*f >= 1.0f && *f <= 170.0f)) return bad(where + ".fov", "must be in [1, 170] degrees");
    cam.fov_deg = *f;
  }
  if (c.contains("path")) {
    if (!c["path"].is_string() || c["path"].get<std::string>().empty())
      return bad(where + ".path", "expected a built-in path name or a path file");
    const std::string p = c["path"].get<std::string>();
    cam.path = lower(std::filesystem::path(p).extension().string()) == ".json" ? (dir / p).string() : p;
  }
  if (c.contains("duration")) {
    if (!cam.path) return bad(where + ".duration", "only with \"path\"");
    auto d = readNumber(c["duration"], where + ".duration");
    if (!d) return d.error();
    if (!(*d > 0.0f && *d <= 86400.0f)) return bad(where + ".duration", "must be in (0, 86400] seconds");
    cam.duration = *d;
  }
  return cam;
}

Status readSceneText(Reader& r, const std::string& text, const std::filesystem::path& file, const glm::mat4& parent,
                     float parent_factor, const nlohmann::json& parent_style, Scene* top) {
  const std::string name = file.string();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // parse_error, and out_of_range for numbers past double
    std::string what = e.what();
    if (const auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    return Error::runtime(name + ": invalid JSON: " + printableText(what, 300));
  }
  if (!j.is_object()) return Error::runtime(name + ": expected a JSON object with an \"objects\" array");
  static const std::set<std::string> known = {"lodline", "description", "objects", "settings", "camera", "light"};
  for (const auto& [k, v] : j.items())
    if (!known.count(k)) return Error::runtime(name + ": unknown key " + quoted(k));
  if (j.contains("lodline") && !(j["lodline"].is_number_integer() && j["lodline"].get<long long>() == 1))
    return Error::runtime(name + ": lodline: unsupported scene format version (this lodline reads version 1)");
  if (j.contains("description") && !j["description"].is_string())
    return Error::runtime(name + ": description: expected a string");
  if (!j.contains("objects") || !j["objects"].is_array() || j["objects"].empty())
    return Error::runtime(name + ": objects: expected a non-empty array of objects");

  std::error_code ec;
  r.stack.push_back(std::filesystem::weakly_canonical(file, ec));
  const std::filesystem::path dir = file.parent_path();
  for (size_t i = 0; i < j["objects"].size(); ++i) {
    const std::string where = name + ": objects[" + std::to_string(i) + "]";
    if (Status s = readObject(r, j["objects"][i], where, dir, parent, parent_factor, parent_style); !s) return s;
  }
  r.stack.pop_back();
  if (!top) return {};  // an include contributes its objects only

  if (j.contains("settings")) {
    if (!j["settings"].is_object()) return Error::runtime(name + ": settings: expected an object of render options");
    for (const auto& [k, v] : j["settings"].items()) {
      const bool ok = v.is_string() || v.is_number() || v.is_boolean() ||
                      (v.is_array() && std::all_of(v.begin(), v.end(), [](const nlohmann::json& e) { return e.is_string(); }));
      if (!ok) return Error::runtime(name + ": settings." + printableText(k, 80) + ": expected a string, number, boolean or array of strings");
    }
    top->settings = j["settings"];
  }
  if (j.contains("camera")) {
    auto cam = readCamera(j["camera"], name + ": camera", dir);
    if (!cam) return cam.error();
    top->camera = *cam;
  }
  if (j.contains("light")) {
    const auto& l = j["light"];
    if (!l.is_object()) return Error::runtime(name + ": light: expected an object");
    for (const auto& [k, v] : l.items())
      if (k != "direction") return Error::runtime(name + ": light: unknown key " + quoted(k));
    if (!l.contains("direction")) return Error::runtime(name + ": light: needs \"direction\"");
    auto d = readVec3(l["direction"], name + ": light.direction");
    if (!d) return d.error();
    if (!(glm::length(*d) > 0.0f)) return Error::runtime(name + ": light.direction: must not be zero");
    top->light_dir_eye = *d;
  }
  return {};
}

// The first of several objects with a name keeps it; the others get "#2", "#3", ... (a
// suffix that no other object already uses).
void uniqueNames(std::vector<SceneObject>& objects) {
  std::map<std::string, int> count;
  for (const auto& o : objects) ++count[o.name];
  std::set<std::string> taken;
  for (const auto& o : objects) taken.insert(o.name);
  std::map<std::string, int> next;
  std::set<std::string> first_kept;
  for (auto& o : objects) {
    if (count[o.name] < 2 || first_kept.insert(o.name).second) continue;
    std::string name;
    for (int& n = next[o.name];;) {
      name = o.name;
      name.push_back('#');
      name.append(std::to_string(n < 2 ? (n = 2) : ++n));
      if (taken.insert(name).second) break;
    }
    o.name = std::move(name);
  }
}

}  // namespace

bool isSceneFile(const std::filesystem::path& path) {
  const std::string ext = lower(path.extension().string());
  return ext == ".json" || ext == ".gltf" || ext == ".glb";
}

glm::mat4 eulerRotation(glm::vec3 degrees) {
  const glm::mat4 rx = glm::rotate(glm::mat4(1.0f), glm::radians(degrees.x), glm::vec3(1, 0, 0));
  const glm::mat4 ry = glm::rotate(glm::mat4(1.0f), glm::radians(degrees.y), glm::vec3(0, 1, 0));
  const glm::mat4 rz = glm::rotate(glm::mat4(1.0f), glm::radians(degrees.z), glm::vec3(0, 0, 1));
  return rz * ry * rx;
}

nlohmann::json matrixJson(const glm::mat4& m) {
  nlohmann::json j = nlohmann::json::array();
  for (int i = 0; i < 16; ++i) j.push_back(m[i / 4][i % 4]);
  return j;
}

glm::mat4 composeTransform(glm::vec3 t, const glm::mat4& r, glm::vec3 s) {
  return glm::translate(glm::mat4(1.0f), t) * r * glm::scale(glm::mat4(1.0f), s);
}

void transformMesh(TriMesh& mesh, const glm::mat4& transform) {
  if (transform == glm::mat4(1.0f)) return;
  for (glm::vec3& p : mesh.positions) p = glm::vec3(transform * glm::vec4(p, 1.0f));
  if (glm::determinant(glm::mat3(transform)) < 0.0f)
    for (auto& f : mesh.faces) std::swap(f[1], f[2]);
}

Result<TriMesh> loadObjectMesh(const SceneObject& object) {
  TriMesh mesh;
  if (object.preloaded) {
    mesh = *object.preloaded;
  } else {
    auto m = loadMesh(object.mesh);
    if (!m) {
      // A mesh named by a scene file: say which entry of which scene names it.
      if (object.where == object.mesh.string()) return m.error();
      return Error{m.error().kind, object.where + ".mesh: " + m.error().message};
    }
    mesh = std::move(m.value());
  }
  if (!object.paint.empty())
    if (auto painted = paintMesh(mesh, object.paint, object.mesh.string() + " (painted by " + object.where + ")"); !painted)
      return painted.error();
  transformMesh(mesh, object.transform);
  if (Status s = validateMesh(mesh, object.mesh.string() + " (placed by " + object.where + ")"); !s) return s.error();
  return mesh;
}

Result<Scene> parseScene(const std::string& text, const std::filesystem::path& file) {
  Scene scene;
  scene.file = file;
  Reader r;
  if (Status s = readSceneText(r, text, file, glm::mat4(1.0f), 1.0f, nlohmann::json::object(), &scene); !s)
    return s.error();
  scene.objects = std::move(r.objects);
  uniqueNames(scene.objects);
  return scene;
}

Result<Scene> loadScene(const std::filesystem::path& path) {
  const std::string ext = lower(path.extension().string());
  if (ext == ".json") {
    std::string text;
    if (Status s = readFile(path, text); !s) return s.error();
    return parseScene(text, path);
  }
  Scene scene;
  scene.file = path;
  if (ext == ".gltf" || ext == ".glb") {
    auto nodes = loadGltf(path);
    if (!nodes) return nodes.error();
    for (auto& g : *nodes) {
      SceneObject obj;
      obj.name = g.name;
      obj.mesh = path;
      obj.gltf_node = g.node;
      obj.transform = g.transform;
      obj.preloaded = std::make_shared<const TriMesh>(std::move(g.mesh));
      obj.source = {{"mesh", path.filename().string()}, {"gltf_node", g.node}};
      obj.where = path.string() + ": node " + std::to_string(g.node);
      scene.objects.push_back(std::move(obj));
    }
    uniqueNames(scene.objects);
    return scene;
  }
  SceneObject obj;
  obj.name = path.stem().string();
  obj.mesh = path;
  obj.source = {{"mesh", path.filename().string()}};
  obj.where = path.string();
  scene.objects.push_back(std::move(obj));
  return scene;
}

std::string pathRelativeTo(const std::filesystem::path& file, const std::filesystem::path& folder) {
  std::error_code ec;
  const auto abs_file = std::filesystem::absolute(file, ec);
  const auto abs_base = std::filesystem::absolute(folder.empty() ? "." : folder, ec);
  auto rel = abs_file.lexically_relative(abs_base);
  return rel.empty() ? abs_file.string() : rel.string();
}

namespace {

nlohmann::json vec3Json(glm::vec3 v) { return {v.x, v.y, v.z}; }

}  // namespace

Status writeSceneFile(const std::filesystem::path& path, const Scene& scene, const std::string& description) {
  const std::filesystem::path dir = path.parent_path();
  nlohmann::json j;
  j["lodline"] = 1;
  if (!description.empty()) j["description"] = description;
  if (!scene.settings.empty()) j["settings"] = scene.settings;
  if (const auto& c = scene.camera) {
    nlohmann::json cam = nlohmann::json::object();
    if (c->explicit_pose) {
      cam["eye"] = vec3Json(c->eye);
      cam["target"] = vec3Json(c->target);
      cam["up"] = vec3Json(c->up);
    } else if (c->view) {
      cam["view"] = *c->view;
    } else if (c->path) {
      const bool file = std::filesystem::path(*c->path).extension() == ".json";
      cam["path"] = file ? pathRelativeTo(*c->path, dir) : *c->path;
      if (c->duration) cam["duration"] = *c->duration;
    }
    if (c->fov_deg) cam["fov"] = *c->fov_deg;
    j["camera"] = cam;
  }
  if (scene.light_dir_eye) j["light"] = {{"direction", vec3Json(*scene.light_dir_eye)}};
  nlohmann::json objects = nlohmann::json::array();
  for (const SceneObject& so : scene.objects) {
    nlohmann::json o;
    o["name"] = so.name;
    o["mesh"] = pathRelativeTo(so.mesh, dir);
    if (so.gltf_node >= 0) o["gltf_node"] = so.gltf_node;
    if (so.placement != glm::mat4(1.0f)) o["matrix"] = matrixJson(so.placement);
    o["detail_factor"] = so.detail_factor;
    for (const auto& [key, value] : so.style.items()) {
      std::string k = key;
      std::replace(k.begin(), k.end(), '-', '_');
      o[k] = value;
    }
    objects.push_back(o);
  }
  j["objects"] = objects;
  const std::string text = j.dump(2) + "\n";
  return writeFileAtomically(path, [&](std::ostream& out) -> Status {
    out << text;
    return {};
  });
}

}  // namespace lodline
