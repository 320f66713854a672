// Bounded mesh readers (see mesh_reader.h). Format references: Geomview's OFF description
// (with OpenMesh's little-endian binary variant), Wavefront's OBJ appendix, Turk's PLY
// description, 3D Systems' STL description.
#include "io/mesh_reader.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>
#include <unordered_map>

namespace lodline {
namespace {

// Indices are 32-bit; kPmNone-style sentinels sit at the top of the range.
constexpr uint64_t kMaxCount = 0xfffffff0ull;

// A file's word in an error: printable ASCII only (a message must stay one clean line),
// at most 24 characters.
std::string printable(std::string_view token) {
  std::string out;
  for (size_t i = 0; i < token.size() && i < 24; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    out.push_back(c >= 0x20 && c < 0x7f ? static_cast<char>(c) : '?');
  }
  if (token.size() > 24) out += "...";
  return out;
}
std::string quote(std::string_view token) {
  std::string out(1, '\'');  // append(): GCC 12 warns falsely on "'" + std::string (PR 105329)
  return out.append(printable(token)).append(1, '\'');
}

// A double narrowed to float without undefined behaviour: out of range gives ±inf (refused
// later by validateMesh as non-finite), NaN stays NaN.
float toFloat(double d) {
  if (std::isnan(d)) return std::numeric_limits<float>::quiet_NaN();
  if (d > std::numeric_limits<float>::max()) return std::numeric_limits<float>::infinity();
  if (d < -std::numeric_limits<float>::max()) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(d);
}

bool parseFloat(std::string_view t, float& out) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  if (t.empty()) return false;
  double d = 0.0;
  const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), d);
  if (p != t.data() + t.size()) return false;
  if (ec == std::errc::result_out_of_range) {
    // Overflow gives ±inf (refused later as non-finite); underflow is zero.
    const bool negative = t[0] == '-';
    const bool tiny = t.find_first_of("eE") != std::string_view::npos &&
                      t.find('-', t.find_first_of("eE")) != std::string_view::npos;
    out = tiny ? 0.0f : (negative ? -1.0f : 1.0f) * std::numeric_limits<float>::infinity();
    return true;
  }
  if (ec != std::errc()) return false;
  out = toFloat(d);
  return true;
}

bool parseInt(std::string_view t, long long& out) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  if (t.empty()) return false;
  const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), out);
  return ec == std::errc() && p == t.data() + t.size();
}

// Cursor over text. Line numbers are computed only for errors.
class Text {
 public:
  explicit Text(std::string_view s) : s_(s) {}

  bool eof() const { return pos_ >= s_.size(); }
  size_t pos() const { return pos_; }
  size_t remaining() const { return s_.size() - std::min(pos_, s_.size()); }
  /// 1-based line of byte `at` (default: the cursor).
  size_t lineAt(size_t at) const {
    return 1 + static_cast<size_t>(std::count(s_.begin(), s_.begin() + static_cast<std::ptrdiff_t>(std::min(at, s_.size())), '\n'));
  }
  size_t line() const { return lineAt(pos_); }
  void seek(size_t at) { pos_ = std::min(at, s_.size()); }

  /// Next word, skipping white space, line ends and `comment`-to-end-of-line comments
  /// (comment 0: none). Empty at the end.
  std::string_view word(char comment) {
    for (;;) {
      while (pos_ < s_.size() && isSpace(s_[pos_])) ++pos_;
      if (pos_ < s_.size() && comment != 0 && s_[pos_] == comment) {
        skipLine();
        continue;
      }
      break;
    }
    return take();
  }
  /// Next word on the current line (not crossing a line end or a comment); empty if none.
  std::string_view wordOnLine(char comment) {
    while (pos_ < s_.size() && isBlank(s_[pos_])) ++pos_;
    if (pos_ >= s_.size() || s_[pos_] == '\n' || (comment != 0 && s_[pos_] == comment)) return {};
    return take();
  }
  /// Moves past the next line end.
  void skipLine() {
    const size_t nl = s_.find('\n', pos_);
    pos_ = nl == std::string_view::npos ? s_.size() : nl + 1;
  }
  /// The rest of the current line (without the line end) and moves past it.
  std::string_view restOfLine() {
    const size_t nl = s_.find('\n', pos_);
    const size_t end = nl == std::string_view::npos ? s_.size() : nl;
    std::string_view out = s_.substr(pos_, end - pos_);
    pos_ = nl == std::string_view::npos ? s_.size() : nl + 1;
    if (!out.empty() && out.back() == '\r') out.remove_suffix(1);
    return out;
  }

 private:
  static bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
  static bool isSpace(char c) { return isBlank(c) || c == '\n'; }
  std::string_view take() {
    const size_t start = pos_;
    while (pos_ < s_.size() && !isSpace(s_[pos_])) ++pos_;
    return s_.substr(start, pos_ - start);
  }
  std::string_view s_;
  size_t pos_ = 0;
};

// Little-endian (or big-endian) reads from a byte range with bounds checks by the caller.
class Bytes {
 public:
  Bytes(std::string_view s, size_t pos, bool big_endian) : s_(s), pos_(pos), big_(big_endian) {}
  size_t remaining() const { return s_.size() - std::min(pos_, s_.size()); }
  size_t pos() const { return pos_; }
  void skip(size_t n) { pos_ += n; }
  template <class T>
  T get() {
    unsigned char b[sizeof(T)];
    std::memcpy(b, s_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    if (big_) std::reverse(b, b + sizeof(T));
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }

 private:
  std::string_view s_;
  size_t pos_;
  bool big_;
};

class Reader {
 public:
  Reader(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  Result<PolygonMesh> off();
  Result<PolygonMesh> obj();
  Result<PolygonMesh> ply();
  Result<PolygonMesh> stl();

 private:
  Error error(const std::string& what) const { return Error::runtime(name_ + ": " + what); }
  Error errorAtLine(size_t line, const std::string& what) const {
    return error("line " + std::to_string(line) + ": " + what);
  }
  /// Error at the line holding byte `at` (counted only when there is an error).
  Error errorAt(size_t at, const std::string& what) const {
    return errorAtLine(Text(bytes_).lineAt(at), what);
  }
  void beginFace() {
    if (mesh_.face_start.empty()) mesh_.face_start.push_back(0);
  }
  void endFace() { mesh_.face_start.push_back(static_cast<uint32_t>(mesh_.corners.size())); }
  Result<PolygonMesh> finish() {
    if (mesh_.face_start.empty()) mesh_.face_start.push_back(0);
    return std::move(mesh_);
  }

  Result<PolygonMesh> offBinary(size_t data_start, bool normals, bool colours, bool texcoords);
  Result<PolygonMesh> stlBinary(uint32_t triangles);
  Result<PolygonMesh> stlAscii();
  uint32_t stlVertex(const glm::vec3& p);

  std::string_view bytes_;
  const std::string& name_;
  PolygonMesh mesh_;
  struct BitsHash {
    size_t operator()(const std::array<uint32_t, 3>& b) const {
      return static_cast<size_t>((uint64_t{b[0]} * 0x9e3779b97f4a7c15ull) ^ (uint64_t{b[1]} * 0xc2b2ae3d27d4eb4full) ^
                                 (uint64_t{b[2]} * 0x165667b19e3779f9ull));
    }
  };
  std::unordered_map<std::array<uint32_t, 3>, uint32_t, BitsHash> stl_vertices_;
};

// ---- OFF ----

Result<PolygonMesh> Reader::off() {
  Text t(bytes_);
  const std::string_view magic = t.word('#');
  std::string_view m = magic;
  bool texcoords = false, colours = false, normals = false;
  if (m.substr(0, 2) == "ST") {
    texcoords = true;
    m.remove_prefix(2);
  }
  if (m.substr(0, 1) == "C") {
    colours = true;
    m.remove_prefix(1);
  }
  if (m.substr(0, 1) == "N") {
    normals = true;
    m.remove_prefix(1);
  }
  if (m == "4OFF" || m == "nOFF" || m == "4nOFF")
    return error("OFF variant " + quote(magic) + " (vertex dimension other than 3) is not supported");
  if (m != "OFF")
    return error("not an OFF file (starts with " + quote(magic) + ", expected OFF, COFF, NOFF or STOFF)");
  if (t.wordOnLine('#') == "BINARY") {
    t.skipLine();
    return offBinary(t.pos(), normals, colours, texcoords);
  }
  long long nv = -1, nf = -1;
  const std::string_view wv = t.word('#');
  const std::string_view wf = t.word('#');
  if (!parseInt(wv, nv) || !parseInt(wf, nf))
    return errorAt(t.pos(), "malformed OFF header (expected vertex, face and edge counts, found " +
                                (wv.empty() ? std::string("the end of the file")
                                            : quote(wv) + (wf.empty() ? std::string() : " " + quote(wf))) +
                                ")");
  if (nv < 0 || nf < 0) return errorAt(t.pos(), "malformed OFF header (negative counts)");
  (void)t.wordOnLine('#');  // the edge count, unused
  t.skipLine();
  // Each vertex needs ≥ 6 bytes ("0 0 0\n"), each face ≥ 2 (a count and a line end; a
  // real one far more); the last line may lack its line end.
  const long double need = 6.0L * nv + 2.0L * nf;
  if (static_cast<uint64_t>(nv) > kMaxCount || static_cast<uint64_t>(nf) > kMaxCount ||
      need > static_cast<long double>(t.remaining()) + 1.0L)
    return error("truncated OFF file (header announces " + std::to_string(nv) + " vertices and " +
                 std::to_string(nf) + " faces, the file has only " + std::to_string(bytes_.size()) + " bytes)");
  mesh_.positions.reserve(static_cast<size_t>(nv));
  mesh_.face_start.reserve(static_cast<size_t>(nf) + 1);
  mesh_.corners.reserve(3 * static_cast<size_t>(nf));
  for (long long i = 0; i < nv; ++i) {
    glm::vec3 p;
    for (int c = 0; c < 3; ++c) {
      const std::string_view w = t.word('#');
      if (w.empty())
        return error("truncated OFF file (vertex " + std::to_string(i) + " of " + std::to_string(nv) + " missing)");
      if (!parseFloat(w, p[c]))
        return errorAt(t.pos(), "vertex " + std::to_string(i) + ": coordinate " + quote(w) + " is not a number");
    }
    mesh_.positions.push_back(p);
    t.skipLine();  // normal, colour, texture coordinates
  }
  beginFace();
  for (long long f = 0; f < nf; ++f) {
    const std::string_view wk = t.word('#');
    long long k = 0;
    if (wk.empty())
      return error("truncated OFF file (face " + std::to_string(f) + " of " + std::to_string(nf) + " missing)");
    const size_t at = t.pos();
    if (!parseInt(wk, k)) return errorAt(at, "face " + std::to_string(f) + ": vertex count " + quote(wk) + " is not a number");
    if (k < 3)
      return errorAt(at, "face " + std::to_string(f) + " has " + std::to_string(k) + " vertices (at least 3 needed)");
    if (static_cast<unsigned long long>(k) > t.remaining() / 2 + 1)
      return errorAt(at, "face " + std::to_string(f) + " announces " + std::to_string(k) +
                             " vertices, more than the rest of the file holds");
    for (long long c = 0; c < k; ++c) {
      const std::string_view w = t.word('#');
      long long v = -1;
      if (w.empty()) return error("truncated OFF file (face " + std::to_string(f) + " incomplete)");
      if (!parseInt(w, v)) return errorAt(t.pos(), "face " + std::to_string(f) + ": vertex index " + quote(w) + " is not a number");
      if (v < 0 || v >= nv)
        return errorAt(t.pos(), "face " + std::to_string(f) + " references vertex " + std::to_string(v) +
                                    ", out of range (" + std::to_string(nv) + " vertices)");
      mesh_.corners.push_back(static_cast<uint32_t>(v));
    }
    endFace();
    t.skipLine();  // a face colour after the indices
  }
  return finish();
}

Result<PolygonMesh> Reader::offBinary(size_t data_start, bool normals, bool colours, bool texcoords) {
  Bytes b(bytes_, data_start, false);
  if (b.remaining() < 12) return error("truncated binary OFF file (no counts after the header)");
  const uint32_t nv = b.get<uint32_t>(), nf = b.get<uint32_t>();
  (void)b.get<uint32_t>();
  const uint64_t vertex_bytes = 12 + (normals ? 12 : 0) + (colours ? 12 : 0) + (texcoords ? 8 : 0);
  if (nv > kMaxCount || nf > kMaxCount || uint64_t{nv} * vertex_bytes + uint64_t{nf} * 16 > b.remaining())
    return error("truncated binary OFF file (header announces " + std::to_string(nv) + " vertices and " +
                 std::to_string(nf) + " faces, the file has only " + std::to_string(bytes_.size()) + " bytes)");
  mesh_.positions.reserve(nv);
  for (uint32_t i = 0; i < nv; ++i) {
    glm::vec3 p;
    for (int c = 0; c < 3; ++c) p[c] = b.get<float>();
    b.skip(vertex_bytes - 12);
    mesh_.positions.push_back(p);
  }
  mesh_.face_start.reserve(uint64_t{nf} + 1);
  mesh_.corners.reserve(uint64_t{nf} * 3);
  beginFace();
  for (uint32_t f = 0; f < nf; ++f) {
    if (b.remaining() < 4) return error("truncated binary OFF file (face " + std::to_string(f) + " missing)");
    const uint32_t k = b.get<uint32_t>();
    if (k < 3) return error("face " + std::to_string(f) + " has " + std::to_string(k) + " vertices (at least 3 needed)");
    if (uint64_t{k} * 4 > b.remaining())
      return error("truncated binary OFF file (face " + std::to_string(f) + " announces " + std::to_string(k) +
                   " vertices, more than the rest of the file holds)");
    for (uint32_t c = 0; c < k; ++c) {
      const uint32_t v = b.get<uint32_t>();
      if (v >= nv)
        return error("face " + std::to_string(f) + " references vertex " + std::to_string(v) + ", out of range (" +
                     std::to_string(nv) + " vertices)");
      mesh_.corners.push_back(v);
    }
    endFace();
  }
  return finish();
}

// ---- OBJ ----

Result<PolygonMesh> Reader::obj() {
  Text t(bytes_);
  struct PendingEdge {
    long long a, b;
    size_t line;
  };
  std::vector<long long> raw;  // corners: ≥ 0 resolved 0-based index, checked at the end
  std::vector<size_t> raw_line;
  std::vector<PendingEdge> edges;
  // Material index by usemtl name, in order of first use ("": faces before any usemtl).
  std::unordered_map<std::string, uint32_t> materials{{"", 0}};
  uint32_t material = 0;
  std::vector<uint32_t> face_material;
  beginFace();
  size_t line = 0;
  // Resolves an OBJ index token ("7", "-2", "7/1/3", "7//3") against the vertices so far.
  auto index = [&](std::string_view tok, long long& out) -> std::optional<Error> {
    const std::string_view num = tok.substr(0, tok.find('/'));
    long long i = 0;
    if (!parseInt(num, i) || i == 0) return errorAtLine(line, "vertex reference " + quote(tok) + " is not an index");
    out = i < 0 ? static_cast<long long>(mesh_.positions.size()) + i : i - 1;
    if (out < 0)
      return errorAtLine(line, "vertex reference " + quote(tok) + " out of range (" +
                                   std::to_string(mesh_.positions.size()) + " vertices so far)");
    return std::nullopt;
  };
  while (!t.eof()) {
    ++line;
    const std::string_view key = t.wordOnLine('#');
    if (key == "v") {
      glm::vec3 p;
      for (int c = 0; c < 3; ++c) {
        const std::string_view w = t.wordOnLine('#');
        if (w.empty()) return errorAtLine(line, "vertex has fewer than 3 coordinates");
        if (!parseFloat(w, p[c])) return errorAtLine(line, "vertex coordinate " + quote(w) + " is not a number");
      }
      if (mesh_.positions.size() >= kMaxCount) return errorAtLine(line, "too many vertices");
      mesh_.positions.push_back(p);
    } else if (key == "f" || key == "fo") {
      size_t k = 0;
      for (std::string_view w = t.wordOnLine('#'); !w.empty(); w = t.wordOnLine('#')) {
        long long v = 0;
        if (auto e = index(w, v)) return *e;
        raw.push_back(v);
        raw_line.push_back(line);
        ++k;
      }
      if (k < 3) return errorAtLine(line, "face has " + std::to_string(k) + " vertices (at least 3 needed)");
      if (raw.size() >= kMaxCount) return errorAtLine(line, "too many face corners");
      mesh_.face_start.push_back(static_cast<uint32_t>(raw.size()));
      face_material.push_back(material);
    } else if (key == "usemtl") {
      const auto [it, added] = materials.try_emplace(std::string(t.wordOnLine('#')),
                                                      static_cast<uint32_t>(materials.size()));
      material = it->second;
    } else if (key == "l") {
      long long prev = -1;
      for (std::string_view w = t.wordOnLine('#'); !w.empty(); w = t.wordOnLine('#')) {
        long long v = 0;
        if (auto e = index(w, v)) return *e;
        if (prev >= 0 && prev != v) edges.push_back({prev, v, line});
        prev = v;
      }
    }
    t.skipLine();  // other statements (vt, vn, g, o, s, mtllib, ...) are ignored
  }
  const size_t n = mesh_.positions.size();
  mesh_.corners.reserve(raw.size());
  for (size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] >= static_cast<long long>(n))
      return errorAtLine(raw_line[i], "face vertex " + std::to_string(raw[i] + 1) + " out of range (" +
                                          std::to_string(n) + " vertices)");
    mesh_.corners.push_back(static_cast<uint32_t>(raw[i]));
  }
  for (const PendingEdge& e : edges) {
    if (e.a >= static_cast<long long>(n) || e.b >= static_cast<long long>(n))
      return errorAtLine(e.line, "edge vertex " + std::to_string(std::max(e.a, e.b) + 1) + " out of range (" +
                                     std::to_string(n) + " vertices)");
    mesh_.marked_edges.push_back({static_cast<uint32_t>(e.a), static_cast<uint32_t>(e.b)});
  }
  // Kept when the faces use two materials or more.
  if (std::adjacent_find(face_material.begin(), face_material.end(), std::not_equal_to<>()) != face_material.end())
    mesh_.face_materials = std::move(face_material);
  return finish();
}

// ---- PLY ----

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

std::optional<PlyType> plyType(std::string_view s) {
  if (s == "char" || s == "int8") return PlyType::kInt8;
  if (s == "uchar" || s == "uint8") return PlyType::kUint8;
  if (s == "short" || s == "int16") return PlyType::kInt16;
  if (s == "ushort" || s == "uint16") return PlyType::kUint16;
  if (s == "int" || s == "int32") return PlyType::kInt32;
  if (s == "uint" || s == "uint32") return PlyType::kUint32;
  if (s == "float" || s == "float32") return PlyType::kFloat32;
  if (s == "double" || s == "float64") return PlyType::kFloat64;
  return std::nullopt;
}

size_t plySize(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
    case PlyType::kUint8: return 1;
    case PlyType::kInt16:
    case PlyType::kUint16: return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32: return 4;
    case PlyType::kFloat64: return 8;
  }
  return 1;
}

bool plyIsInteger(PlyType t) { return t != PlyType::kFloat32 && t != PlyType::kFloat64; }

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

double plyRead(Bytes& b, PlyType t) {
  switch (t) {
    case PlyType::kInt8: return b.get<int8_t>();
    case PlyType::kUint8: return b.get<uint8_t>();
    case PlyType::kInt16: return b.get<int16_t>();
    case PlyType::kUint16: return b.get<uint16_t>();
    case PlyType::kInt32: return b.get<int32_t>();
    case PlyType::kUint32: return b.get<uint32_t>();
    case PlyType::kFloat32: return b.get<float>();
    case PlyType::kFloat64: return b.get<double>();
  }
  return 0.0;
}

Result<PolygonMesh> Reader::ply() {
  Text t(bytes_);
  if (t.restOfLine() != "ply") return error("not a PLY file (the first line is not 'ply')");
  enum class Format { kAscii, kLittle, kBig } format = Format::kAscii;
  bool have_format = false, ended = false;
  std::vector<PlyElement> elements;
  size_t line = 1;
  while (!t.eof()) {
    ++line;
    Text l(t.restOfLine());
    const std::string_view key = l.word(0);
    if (key.empty() || key == "comment" || key == "obj_info") continue;
    if (key == "end_header") {
      ended = true;
      break;
    }
    if (key == "format") {
      const std::string_view f = l.word(0), version = l.word(0);
      if (f == "ascii") format = Format::kAscii;
      else if (f == "binary_little_endian") format = Format::kLittle;
      else if (f == "binary_big_endian") format = Format::kBig;
      else return errorAtLine(line, "unknown PLY format " + quote(f));
      if (version != "1.0") return errorAtLine(line, "unsupported PLY version " + quote(version));
      have_format = true;
    } else if (key == "element") {
      const std::string_view name = l.word(0), count = l.word(0);
      long long n = -1;
      if (name.empty() || !parseInt(count, n) || n < 0)
        return errorAtLine(line, "malformed element line (expected 'element NAME COUNT')");
      if (static_cast<uint64_t>(n) > kMaxCount)
        return errorAtLine(line, "element " + quote(name) + " announces " + std::to_string(n) + " items, too many");
      elements.push_back({std::string(name), static_cast<uint64_t>(n), {}});
    } else if (key == "property") {
      if (elements.empty()) return errorAtLine(line, "property before any element");
      PlyProperty p;
      std::string_view type = l.word(0);
      if (type == "list") {
        const std::string_view ct = l.word(0);
        const auto c = plyType(ct);
        if (!c || !plyIsInteger(*c)) return errorAtLine(line, "bad list count type " + quote(ct));
        p.is_list = true;
        p.count_type = *c;
        type = l.word(0);
      }
      const auto ty = plyType(type);
      if (!ty) return errorAtLine(line, "unknown property type " + quote(type));
      p.type = *ty;
      const std::string_view name = l.word(0);
      if (name.empty()) return errorAtLine(line, "property without a name");
      p.name = std::string(name);
      elements.back().properties.push_back(std::move(p));
    } else {
      return errorAtLine(line, "unexpected " + quote(key) + " in the PLY header");
    }
  }
  if (!ended) return error("PLY header has no end_header line");
  if (!have_format) return error("PLY header has no format line");

  // Which element holds what.
  int vertex_el = -1, face_el = -1;
  int px = -1, py = -1, pz = -1, pf = -1;
  for (size_t e = 0; e < elements.size(); ++e) {
    const PlyElement& el = elements[e];
    if (el.name == "vertex" && vertex_el < 0) {
      vertex_el = static_cast<int>(e);
      for (size_t k = 0; k < el.properties.size(); ++k) {
        const PlyProperty& p = el.properties[k];
        if (p.is_list) continue;
        if (p.name == "x") px = static_cast<int>(k);
        if (p.name == "y") py = static_cast<int>(k);
        if (p.name == "z") pz = static_cast<int>(k);
      }
    } else if (el.name == "face" && face_el < 0) {
      face_el = static_cast<int>(e);
      for (size_t k = 0; k < el.properties.size(); ++k) {
        const PlyProperty& p = el.properties[k];
        if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index") && pf < 0) pf = static_cast<int>(k);
      }
    }
  }
  if (vertex_el < 0) return error("PLY file has no vertex element");
  if (px < 0 || py < 0 || pz < 0) return error("PLY vertex element lacks an x, y or z property");
  if (face_el >= 0 && pf < 0 && elements[face_el].count > 0)
    return error("PLY face element has no vertex_indices list");

  // Counts against the file size, before anything is allocated: a binary item needs its
  // fixed-size properties and list counts, an ASCII one ≥ 2 bytes per property.
  const size_t data_start = t.pos();
  const long double available = static_cast<long double>(bytes_.size() - data_start) + 1.0L;
  long double need = 0.0L;
  for (const PlyElement& el : elements) {
    long double item = 0.0L;
    for (const PlyProperty& p : el.properties)
      item += format == Format::kAscii ? 2.0L : static_cast<long double>(plySize(p.is_list ? p.count_type : p.type));
    need += item * static_cast<long double>(el.count);
  }
  if (need > available)
    return error("truncated PLY file (the header announces " + std::to_string(elements[vertex_el].count) +
                 " vertices" + (face_el >= 0 ? " and " + std::to_string(elements[face_el].count) + " faces" : std::string()) +
                 ", the file has only " + std::to_string(bytes_.size()) + " bytes)");

  const uint64_t nv = elements[vertex_el].count;
  mesh_.positions.reserve(nv);
  if (face_el >= 0) {
    mesh_.face_start.reserve(elements[face_el].count + 1);
    mesh_.corners.reserve(3 * elements[face_el].count);
  }
  beginFace();
  std::vector<double> values;
  Text text(bytes_);
  text.seek(data_start);
  Bytes bin(bytes_, data_start, format == Format::kBig);
  // Reads one scalar of type `ty`; false at the end of the data or on a malformed token.
  std::string_view bad_token;
  auto scalar = [&](PlyType ty, double& out) -> bool {
    if (format != Format::kAscii) {
      if (bin.remaining() < plySize(ty)) return false;
      out = plyRead(bin, ty);
      return true;
    }
    const std::string_view w = text.word(0);
    if (w.empty()) return false;
    if (plyIsInteger(ty)) {
      long long i = 0;
      if (!parseInt(w, i)) {
        bad_token = w;
        return false;
      }
      out = static_cast<double>(i);
    } else {
      float f = 0.0f;
      if (!parseFloat(w, f)) {
        bad_token = w;
        return false;
      }
      out = f;
    }
    return true;
  };
  auto where = [&](const PlyElement& el, uint64_t i) {
    std::string s = printable(el.name) + " " + std::to_string(i);
    if (format == Format::kAscii) s = "line " + std::to_string(text.line()) + ": " + s;
    return s;
  };
  auto dataError = [&](const PlyElement& el, uint64_t i) {
    if (!bad_token.empty()) return error(where(el, i) + ": " + quote(bad_token) + " is not a number");
    return error("truncated PLY file (" + printable(el.name) + " " + std::to_string(i) + " of " + std::to_string(el.count) +
                 " incomplete)");
  };
  for (size_t e = 0; e < elements.size(); ++e) {
    const PlyElement& el = elements[e];
    const bool is_vertex = static_cast<int>(e) == vertex_el, is_face = static_cast<int>(e) == face_el;
    if (el.properties.empty()) continue;  // items without properties occupy no bytes
    for (uint64_t i = 0; i < el.count; ++i) {
      glm::vec3 p(0.0f);
      for (size_t k = 0; k < el.properties.size(); ++k) {
        const PlyProperty& prop = el.properties[k];
        double v = 0.0;
        if (!prop.is_list) {
          if (!scalar(prop.type, v)) return dataError(el, i);
          if (is_vertex && static_cast<int>(k) == px) p.x = toFloat(v);
          if (is_vertex && static_cast<int>(k) == py) p.y = toFloat(v);
          if (is_vertex && static_cast<int>(k) == pz) p.z = toFloat(v);
          continue;
        }
        double count = 0.0;
        if (!scalar(prop.count_type, count)) return dataError(el, i);
        const size_t item = format == Format::kAscii ? 2 : plySize(prop.type);
        const size_t left = format == Format::kAscii ? text.remaining() + 1 : bin.remaining();
        if (count < 0.0 || count * static_cast<double>(item) > static_cast<double>(left))
          return error(where(el, i) + ": list of " + std::to_string(static_cast<long long>(count)) +
                       " items, more than the rest of the file holds");
        const bool corners = is_face && static_cast<int>(k) == pf;
        if (corners && count < 3)
          return error(where(el, i) + " has " + std::to_string(static_cast<long long>(count)) +
                       " vertices (at least 3 needed)");
        for (uint64_t c = 0; c < static_cast<uint64_t>(count); ++c) {
          if (!scalar(prop.type, v)) return dataError(el, i);
          if (!corners) continue;
          if (!(v >= 0.0 && v < static_cast<double>(nv)) || v != std::floor(v))
            return error(where(el, i) + " references vertex " + std::to_string(static_cast<long long>(v)) +
                         ", out of range (" + std::to_string(nv) + " vertices)");
          mesh_.corners.push_back(static_cast<uint32_t>(v));
        }
        if (corners) endFace();
      }
      if (is_vertex) mesh_.positions.push_back(p);
    }
  }
  return finish();
}

// ---- STL ----

uint32_t Reader::stlVertex(const glm::vec3& p) {
  // Identical positions (bit for bit, -0 counted as +0) are one vertex, numbered in order
  // of first appearance.
  std::array<uint32_t, 3> bits;
  for (int c = 0; c < 3; ++c) {
    const float v = p[c] == 0.0f ? 0.0f : p[c];
    std::memcpy(&bits[c], &v, 4);
  }
  const auto [it, inserted] = stl_vertices_.try_emplace(bits, static_cast<uint32_t>(mesh_.positions.size()));
  if (inserted) mesh_.positions.push_back(p);
  return it->second;
}

Result<PolygonMesh> Reader::stlBinary(uint32_t triangles) {
  Bytes b(bytes_, 84, false);
  mesh_.face_start.reserve(uint64_t{triangles} + 1);
  mesh_.corners.reserve(uint64_t{triangles} * 3);
  beginFace();
  for (uint32_t f = 0; f < triangles; ++f) {
    b.skip(12);  // normal
    for (int c = 0; c < 3; ++c) {
      glm::vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = b.get<float>();
      mesh_.corners.push_back(stlVertex(p));
    }
    b.skip(2);  // attribute byte count
    endFace();
  }
  return finish();
}

Result<PolygonMesh> Reader::stlAscii() {
  Text t(bytes_);
  (void)t.word(0);  // "solid"
  t.skipLine();     // and its name
  beginFace();
  bool in_facet = false;
  size_t corners = 0, facet_at = 0;
  for (std::string_view w = t.word(0); !w.empty(); w = t.word(0)) {
    if (w == "facet") {
      if (in_facet) return errorAt(t.pos(), "facet inside a facet (missing endfacet)");
      in_facet = true;
      corners = 0;
      facet_at = t.pos();
    } else if (w == "vertex") {
      if (!in_facet) return errorAt(t.pos(), "vertex outside a facet");
      glm::vec3 p;
      for (int c = 0; c < 3; ++c) {
        const std::string_view n = t.word(0);
        if (!parseFloat(n, p[c])) return errorAt(t.pos(), "vertex coordinate " + quote(n) + " is not a number");
      }
      if (++corners > 3) return errorAt(t.pos(), "facet with more than 3 vertices");
      mesh_.corners.push_back(stlVertex(p));
    } else if (w == "endfacet") {
      if (!in_facet) return errorAt(t.pos(), "endfacet without facet");
      if (corners != 3) return errorAt(facet_at, "facet has " + std::to_string(corners) + " vertices (3 expected)");
      in_facet = false;
      endFace();
    } else if (w == "solid" || w == "endsolid") {
      t.skipLine();  // the solid's name
    }
    // normal and its numbers, outer, loop, endloop: nothing to keep.
  }
  if (in_facet) return errorAt(facet_at, "truncated STL file (facet not ended)");
  return finish();
}

Result<PolygonMesh> Reader::stl() {
  if (bytes_.size() >= 84) {
    uint32_t n = 0;
    std::memcpy(&n, bytes_.data() + 80, 4);
    if (84 + 50 * uint64_t{n} == bytes_.size()) return stlBinary(n);
  }
  Text t(bytes_);
  if (t.word(0) == "solid") return stlAscii();
  if (bytes_.size() >= 84) {
    uint32_t n = 0;
    std::memcpy(&n, bytes_.data() + 80, 4);
    return error("not an STL file (not ASCII, and as binary STL the header announces " + std::to_string(n) +
                 " triangles, which need " + std::to_string(84 + 50 * uint64_t{n}) + " bytes, but the file has " +
                 std::to_string(bytes_.size()) + ")");
  }
  return error("not an STL file (too short for binary STL and does not start with 'solid')");
}

}  // namespace

Result<PolygonMesh> parsePolygonMesh(std::string_view bytes, std::string_view extension, const std::string& name) {
  Reader r(bytes, name);
  if (extension == ".off") return r.off();
  if (extension == ".obj") return r.obj();
  if (extension == ".ply") return r.ply();
  if (extension == ".stl") return r.stl();
  return Error::runtime(name + ": unsupported file type " + quote(extension) + " (expected .off, .obj, .ply or .stl)");
}

}  // namespace lodline
