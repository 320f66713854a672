#include "io/load_mesh.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <sstream>
#include <system_error>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include "io/atomic_file.h"

namespace lodline {
namespace {

struct OmTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3f;
};
using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<OmTraits>;

// Routes OpenMesh's omerr/omlog into a string during a read, so its complaints become part
// of our one-line error instead of stray stderr output. OpenMesh's multiplexing stream
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

size_t countOccurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

// Cheap sanity check of an OFF header against the file size, so that a hostile header
// ("OFF 2000000000 1 0") is refused before OpenMesh reserves memory for it.
Status checkOffHeader(const std::filesystem::path& path, uintmax_t file_size) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  in >> magic;
  if (magic.find("OFF") == std::string::npos) return {};  // let OpenMesh judge
  if (magic.find("BINARY") != std::string::npos) return {};
  long long nv = -1, nf = -1, ne = -1;
  // Skip comments between the magic and the counts.
  while (in >> std::ws && in.peek() == '#') {
    std::string line;
    std::getline(in, line);
  }
  in >> nv >> nf >> ne;
  if (!in) return Error::runtime(path.string() + ": malformed OFF header (expected vertex, face and edge counts)");
  if (nv < 0 || nf < 0) return Error::runtime(path.string() + ": malformed OFF header (negative counts)");
  // Each vertex needs ≥ 6 bytes ("0 0 0\n"), each face ≥ 8 ("3 0 1 2\n").
  const long double need = 6.0L * nv + 8.0L * nf;
  if (need > static_cast<long double>(file_size))
    return Error::runtime(path.string() + ": truncated OFF file (header announces " +
                          std::to_string(nv) + " vertices and " + std::to_string(nf) +
                          " faces, the file has only " + std::to_string(file_size) + " bytes)");
  return {};
}

// OBJ polylines ("l a b c ...", 1-based or negative indices) mark sharp edges: OpenMesh's
// reader ignores them, so they are read here. Vertices keep the order of the "v" lines.
Status readObjMarkedEdges(const std::filesystem::path& path, size_t vertex_count, std::vector<EdgeKey>& out) {
  std::ifstream in(path);
  std::string line;
  size_t line_no = 0, v_count = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.size() > 1 && line[0] == 'v' && (line[1] == ' ' || line[1] == '\t')) ++v_count;
    if (line.size() < 2 || line[0] != 'l' || (line[1] != ' ' && line[1] != '\t')) continue;
    std::istringstream ls(line.substr(2));
    std::string tok;
    long long prev = -1;
    while (ls >> tok) {
      long long idx = 0;
      try {
        idx = std::stoll(tok.substr(0, tok.find('/')));
      } catch (const std::exception&) {
        return Error::runtime(path.string() + ": line " + std::to_string(line_no) + ": bad index '" + tok + "'");
      }
      const long long resolved = idx < 0 ? static_cast<long long>(v_count) + idx : idx - 1;
      if (idx == 0 || resolved < 0 || resolved >= static_cast<long long>(vertex_count))
        return Error::runtime(path.string() + ": line " + std::to_string(line_no) + ": edge vertex " + tok +
                              " out of range (" + std::to_string(vertex_count) + " vertices)");
      if (prev >= 0 && prev != resolved)
        out.push_back({static_cast<uint32_t>(prev), static_cast<uint32_t>(resolved)});
      prev = resolved;
    }
  }
  return {};
}

}  // namespace

Status validateMesh(const TriMesh& mesh, const std::string& what) {
  if (mesh.positions.empty()) return Error::runtime(what + ": no vertices");
  if (mesh.faces.empty()) return Error::runtime(what + ": no faces");
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return Error::runtime(what + ": vertex " + std::to_string(i) +
                            " has a non-finite coordinate (NaN or inf)");
  }
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
  return {};
}

Result<TriMesh> loadMesh(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return Error::runtime(name + ": no such file");
  if (std::filesystem::is_directory(path, ec)) return Error::runtime(name + ": is a directory, not a mesh file");
  const std::string ext = lowerExtension(path);
  if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl")
    return Error::runtime(name + ": unsupported file type '" + ext +
                          "' (expected .off, .obj, .ply or .stl)");
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) return Error::runtime(name + ": cannot open for reading");
  }
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size == 0) return Error::runtime(name + ": empty file");
  if (ext == ".off")
    if (Status s = checkOffHeader(path, size); !s) return s.error();

  OmMesh om;
  std::string messages;
  bool ok = false;
  {
    OmMessageCapture capture;
    try {
      OpenMesh::IO::Options opt;
      ok = OpenMesh::IO::read_mesh(om, name, opt);
    } catch (const std::exception& e) {
      return Error::runtime(name + ": cannot read mesh (" + e.what() + ")");
    }
    messages = capture.text();
  }
  const size_t bad_index = countOccurrences(messages, "invalid vertex index");
  if (bad_index > 0)
    return Error::runtime(name + ": " + std::to_string(bad_index) +
                          " face(s) reference vertex indices out of range (" +
                          std::to_string(om.n_vertices()) + " vertices)");
  if (!ok) {
    std::string why = messages;
    std::replace(why.begin(), why.end(), '\n', ' ');
    while (!why.empty() && why.back() == ' ') why.pop_back();
    return Error::runtime(name + ": cannot read mesh" + (why.empty() ? "" : " (" + why + ")"));
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
    for (size_t k = 1; k + 1 < poly.size(); ++k) mesh.faces.push_back({poly[0], poly[k], poly[k + 1]});
  }
  if (mesh.faces.empty() && countOccurrences(messages, "equal vertices") > 0)
    return Error::runtime(name + ": no usable faces (every face repeats a vertex)");
  if (Status s = validateMesh(mesh, name); !s) return s.error();
  if (ext == ".obj")
    if (Status s = readObjMarkedEdges(path, mesh.positions.size(), mesh.marked_edges); !s) return s.error();
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

Result<uint64_t> hashFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error::runtime(path.string() + ": cannot open for reading");
  uint64_t h = 1469598103934665603ull;
  std::vector<char> buf(1 << 16);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    const std::streamsize n = in.gcount();
    for (std::streamsize i = 0; i < n; ++i) {
      h ^= static_cast<unsigned char>(buf[static_cast<size_t>(i)]);
      h *= 1099511628211ull;
    }
  }
  return h;
}

}  // namespace lodline
