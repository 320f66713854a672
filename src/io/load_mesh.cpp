#include "io/load_mesh.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <span>
#include <sstream>
#include <system_error>

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include "io/atomic_file.h"
#include "io/input_check.h"
#include "io/mesh_reader.h"

namespace lodline {
namespace {

struct OmTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3f;
};
using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<OmTraits>;

// Routes OpenMesh's omerr/omlog into a string while a mesh is built, so its complaints
// ("complex edge") never reach stderr as stray lines. OpenMesh's multiplexing stream
// never frees a disconnected target, so the capture buffer is connected once per process
// (and OpenMesh's messages stay out of stderr from then on); a mutex serialises reads.
class OmMessageCapture {
 public:
  OmMessageCapture() : lock_(state().mutex) { state().buffer.str(""); }
  OmMessageCapture(const OmMessageCapture&) = delete;
  OmMessageCapture& operator=(const OmMessageCapture&) = delete;
  std::string text() {
    ::omerr().flush();
    ::omlog().flush();
    return state().buffer.str();
  }

 private:
  struct State {
    State() {
      ::omerr().disconnect(std::cerr);
      ::omlog().disconnect(std::cerr);
      ::omerr().connect(buffer);
      ::omlog().connect(buffer);
    }
    std::mutex mutex;
    std::ostringstream buffer;
  };
  static State& state() {
    static State s;
    return s;
  }
  std::lock_guard<std::mutex> lock_;
};

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// The whole file: the readers parse from memory (size known first, so a file that grows
// while it is read is read only up to that size).
Result<std::string> readWholeFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error::runtime(path.string() + ": cannot open for reading");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) return Error::runtime(path.string() + ": cannot read (not seekable)");
  in.seekg(0, std::ios::beg);
  std::string bytes(static_cast<size_t>(size), '\0');
  in.read(bytes.data(), size);
  if (in.gcount() != size) return Error::runtime(path.string() + ": read error");
  return bytes;
}

// True when a polygon lists a vertex twice (OpenMesh refuses such faces).
bool repeatsVertex(std::span<const uint32_t> poly, std::vector<uint32_t>& scratch) {
  if (poly.size() <= 8) {
    for (size_t a = 0; a < poly.size(); ++a)
      for (size_t b = a + 1; b < poly.size(); ++b)
        if (poly[a] == poly[b]) return true;
    return false;
  }
  scratch.assign(poly.begin(), poly.end());
  std::sort(scratch.begin(), scratch.end());
  return std::adjacent_find(scratch.begin(), scratch.end()) != scratch.end();
}

std::string formatNumber(double v) {
  std::ostringstream o;
  o << std::setprecision(3) << v;
  return o.str();
}

// The first vertex with a NaN or infinite coordinate, as an error naming `what`.
Status checkFinite(const std::vector<glm::vec3>& positions, const std::string& what) {
  for (size_t i = 0; i < positions.size(); ++i) {
    const glm::vec3& p = positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return Error::runtime(what + ": vertex " + std::to_string(i) + " has a non-finite coordinate (NaN or inf)");
  }
  return {};
}

}  // namespace

Status validateMesh(const TriMesh& mesh, const std::string& what) {
  if (mesh.positions.empty()) return Error::runtime(what + ": no vertices");
  if (mesh.faces.empty()) return Error::runtime(what + ": no faces");
  if (Status s = checkFinite(mesh.positions, what); !s) return s;
  // The extent must leave room for squared lengths and areas in single precision: beyond
  // 1e18 they overflow, below 1e-18 they vanish (and a model of zero size cannot be framed).
  const float diagonal = computeBounds(mesh.positions).diagonal();
  if (!(diagonal <= kMaxMeshExtent))
    return Error::runtime(what + ": the model is too large to draw (bounding-box diagonal " + formatNumber(diagonal) +
                          ", at most 1e18 model units)");
  if (!(diagonal >= kMinMeshExtent))
    return Error::runtime(what + ": the model has no extent (bounding-box diagonal " + formatNumber(diagonal) +
                          ", at least 1e-18 model units)");
  const size_t n = mesh.positions.size();
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    for (uint32_t v : t)
      if (v >= n)
        return Error::runtime(what + ": face " + std::to_string(f) + " references vertex " +
                              std::to_string(v) + ", out of range (" + std::to_string(n) +
                              " vertices)");
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      return Error::runtime(what + ": face " + std::to_string(f) + " repeats a vertex");
  }
  if (!mesh.face_materials.empty() && mesh.face_materials.size() != mesh.faces.size())
    return Error::runtime(what + ": " + std::to_string(mesh.face_materials.size()) + " face materials for " +
                          std::to_string(mesh.faces.size()) + " faces");
  return {};
}

Result<TriMesh> loadMesh(const std::filesystem::path& path) {
  const std::string name = path.string();
  if (Status s = checkInputFile(path, "mesh file"); !s) return s.error();
  const std::string ext = lowerExtension(path);
  if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl")
    return Error::runtime(name + ": unsupported file type '" + ext + "' (expected .off, .obj, .ply or .stl)");
  Result<std::string> bytes = readWholeFile(path);
  if (!bytes) return bytes.error();
  if (bytes->empty()) return Error::runtime(name + ": empty file");
  Result<PolygonMesh> polygons = parsePolygonMesh(*bytes, ext, name);
  if (!polygons) return polygons.error();
  bytes->clear();
  bytes->shrink_to_fit();
  const PolygonMesh& pm = *polygons;
  // Coordinates first: NaN corners of an STL weld into one vertex, and its faces would be
  // refused for repeating it instead of for what is wrong.
  if (Status s = checkFinite(pm.positions, name); !s) return s.error();

  // OpenMesh for the topology: a face that would make an edge or vertex non-manifold gets
  // its own copies of its vertices (as OpenMesh's importer does); a face that repeats a
  // vertex is dropped. Complaints of add_face go to the capture, not to stderr.
  OmMesh om;
  size_t repeated = 0;
  std::vector<uint32_t> om_face_material;  // per OpenMesh face, in the order they were added
  {
    OmMessageCapture capture;
    om.reserve(pm.positions.size(), 3 * pm.positions.size(), pm.faceCount());
    for (const glm::vec3& p : pm.positions) om.add_vertex(OmMesh::Point(p.x, p.y, p.z));
    std::vector<OmMesh::VertexHandle> handles;
    std::vector<uint32_t> scratch;
    const bool materials = pm.face_materials.size() == pm.faceCount();
    for (size_t f = 0; f < pm.faceCount(); ++f) {
      const std::span<const uint32_t> poly(pm.corners.data() + pm.face_start[f], pm.face_start[f + 1] - pm.face_start[f]);
      if (repeatsVertex(poly, scratch)) {
        ++repeated;
        continue;
      }
      handles.clear();
      for (uint32_t v : poly) handles.emplace_back(static_cast<int>(v));
      bool added = om.add_face(handles).is_valid();
      if (!added) {
        for (auto& h : handles) h = om.add_vertex(OmMesh::Point(om.point(h)));
        added = om.add_face(handles).is_valid();
      }
      if (added && materials) om_face_material.push_back(pm.face_materials[f]);
    }
    (void)capture.text();
  }

  TriMesh mesh;
  mesh.positions.reserve(om.n_vertices());
  for (const auto vh : om.vertices()) {
    const auto& p = om.point(vh);
    mesh.positions.emplace_back(p[0], p[1], p[2]);
  }
  mesh.faces.reserve(om.n_faces());
  std::vector<uint32_t> poly;
  for (const auto fh : om.faces()) {
    poly.clear();
    for (const auto vh : om.fv_range(fh)) poly.push_back(static_cast<uint32_t>(vh.idx()));
    for (size_t k = 1; k + 1 < poly.size(); ++k) {
      mesh.faces.push_back({poly[0], poly[k], poly[k + 1]});
      if (om_face_material.size() == om.n_faces()) mesh.face_materials.push_back(om_face_material[fh.idx()]);
    }
  }
  if (mesh.faces.empty() && repeated > 0)
    return Error::runtime(name + ": no usable faces (every face repeats a vertex)");
  if (Status s = validateMesh(mesh, name); !s) return s.error();
  mesh.marked_edges = pm.marked_edges;
  return mesh;
}

Status saveOff(const std::filesystem::path& path, const TriMesh& mesh) {
  return writeFileAtomically(path, [&](std::ostream& out) -> Status {
    out << "OFF\n" << mesh.positions.size() << ' ' << mesh.faces.size() << " 0\n";
    out << std::setprecision(9);
    for (const auto& p : mesh.positions) out << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const auto& f : mesh.faces) out << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
    return {};
  });
}

}  // namespace lodline
