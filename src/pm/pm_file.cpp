// Progressive mesh cache file (see pm_file.h for the layout). Hoppe 1998, "Efficient
// implementation of progressive meshes", §3 motivates the compact flat-array encoding.
#include "pm/pm_file.h"

#include "core/hash.h"

#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <system_error>
#include <thread>

#include "io/atomic_file.h"
#include "io/input_check.h"

namespace lodline {

namespace {

constexpr char kMagic[8] = {'L', 'O', 'D', 'L', 'P', 'M', '\0', '\x1a'};

struct FileHeader {
  char magic[8];
  uint32_t version;
  uint32_t vertex_count;
  uint32_t face_count;
  uint32_t split_count;
  uint32_t base_face_count;
  uint32_t reserved;
  uint64_t content_hash;
  uint64_t params_hash;
  uint64_t payload_size;
  uint64_t checksum;
};
static_assert(sizeof(FileHeader) == 64, "header layout");
static_assert(sizeof(VertexSplit) == 32, "split layout");

uint64_t payloadSize(uint64_t n, uint64_t nf, uint64_t ns, uint64_t nb) {
  return n * 12 + nf * 12 + ((n + 3) / 4) * 4 + ns * 32 + nb * 4 + nb * 12 + nb * 12;
}

uint64_t checksumOf(FileHeader h, const char* payload, size_t size) {
  h.checksum = 0;
  return hashBytes(payload, size, hashBytes(&h, sizeof(h)));
}

template <class T, class A>
void append(std::string& buf, const std::vector<T, A>& v) {
  buf.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

uint32_t next3(uint32_t i) { return i == 2 ? 0 : i + 1; }
uint32_t prev3(uint32_t i) { return i == 0 ? 2 : i - 1; }

// Replays the whole hierarchy the way AdaptiveMesh applies it (lod/adaptive_mesh.cpp,
// doSplit): from the base mesh, every vertex split in order from the last collapse to the
// first, checking each one's preconditions strictly, and at the end that the fully refined
// mesh is the input mesh face for face: that the records describe a valid sequence of
// half-edge collapses of a manifold neighbourhood, so a damaged file that still passes the
// checksum (or a hostile one) is refused here instead of corrupting the selective
// refinement. It checks every index it follows itself, so it may run on records that
// finalize() (which checks them too) and the checksum have not seen yet: loadPm() runs the
// two at once. O(faces + splits · valence) time.
Status verifyRefinement(const ProgressiveMesh& pm, const std::string& what) {
  const uint32_t n = pm.vertexCount(), nf = pm.faceCount(), nn = pm.nodeCount();
  auto fail = [&](const std::string& msg) { return Status(Error::runtime(what + ": " + msg)); };
  // One 32-byte record per face (corners, neighbours, a visit mark, active): the replay
  // visits faces in no particular order, so one cache line per face matters.
  struct Face {
    std::array<uint32_t, 3> v{kPmNone, kPmNone, kPmNone};
    std::array<uint32_t, 3> nb{kPmNone, kPmNone, kPmNone};
    uint32_t mark = kPmNone;
    uint32_t active = 0;
  };
  static_assert(sizeof(Face) == 32);
  std::vector<Face> face(nf);
  std::vector<uint32_t> incident(nn, 0);  // active faces at each node
  auto corner = [&](uint32_t f, uint32_t v) -> uint32_t {
    const auto& c = face[f].v;
    return c[0] == v ? 0 : c[1] == v ? 1 : c[2] == v ? 2 : 3;
  };
  if (pm.base_corners.size() != pm.base_faces.size() || pm.base_neighbors.size() != pm.base_faces.size())
    return fail("base mesh arrays differ in size");
  for (size_t k = 0; k < pm.base_faces.size(); ++k) {
    if (pm.base_faces[k] >= nf) return fail("base face " + std::to_string(k) + " out of range");
    for (int i = 0; i < 3; ++i)
      if (pm.base_corners[k][i] >= nn || (pm.base_neighbors[k][i] != kPmNone && pm.base_neighbors[k][i] >= nf))
        return fail("base face " + std::to_string(k) + " has a corner or neighbour out of range");
    Face& f = face[pm.base_faces[k]];
    f.v = pm.base_corners[k];
    f.nb = pm.base_neighbors[k];
    f.active = 1;
    if (f.v[0] == f.v[1] || f.v[1] == f.v[2] || f.v[0] == f.v[2])
      return fail("base face " + std::to_string(k) + " repeats a vertex");
    for (uint32_t v : f.v) ++incident[v];
  }
  // Base neighbours: across edge (a, b) of f, g holds edge (b, a) and names f across it.
  for (uint32_t f : pm.base_faces)
    for (uint32_t e = 0; e < 3; ++e) {
      const uint32_t g = face[f].nb[e];
      if (g == kPmNone) continue;
      const uint32_t a = face[f].v[e], b = face[f].v[next3(e)];
      const uint32_t j = corner(g, b);
      if (j == 3 || face[g].v[next3(j)] != a || face[g].nb[j] != f)
        return fail("base neighbours inconsistent at face " + std::to_string(f));
    }
  // Faces around `s` from `from` to `to`, crossing edge (previous corner, s) as
  // AdaptiveMesh's collectFan does, each checked to share that edge and to be new (not
  // marked `mark` or `avoid`); false on a break, a repeat or a wrong edge.
  std::vector<uint32_t> fan_u, fan_t;
  auto fan = [&](uint32_t s, uint32_t from, uint32_t to, uint32_t mark, uint32_t avoid, std::vector<uint32_t>& out) {
    out.clear();
    uint32_t f = from;
    for (;;) {
      Face& F = face[f];
      const uint32_t i = corner(f, s);
      if (i == 3 || F.mark == mark || F.mark == avoid) return false;
      F.mark = mark;
      out.push_back(f);
      if (f == to) return true;
      const uint32_t x = F.v[prev3(i)];
      const uint32_t g = F.nb[prev3(i)];
      if (g == kPmNone || !face[g].active) return false;
      const uint32_t j = corner(g, s);
      if (j == 3 || face[g].v[next3(j)] != x || face[g].nb[j] != f) return false;
      f = g;
    }
  };
  // Sets the neighbour of f across the edge at `e` from `from` to `to`, insisting that this
  // is the first entry equal to `from` (AdaptiveMesh relinks the first one).
  auto relink = [&](uint32_t f, uint32_t e, uint32_t from, uint32_t to) {
    auto& nb = face[f].nb;
    for (uint32_t k = 0; k < 3; ++k)
      if (nb[k] == from) {
        if (k != e) return false;
        nb[k] = to;
        return true;
      }
    return false;
  };
  // The records a split reads are scattered over the face array: fetch those of a split a
  // few ahead while this one is checked (finalize() has checked every index).
  constexpr uint32_t kAhead = 6;
  auto prefetch = [&](uint32_t i) {  // (indices not checked yet: clamped into the arrays)
    if (nf == 0) return;
    const VertexSplit& vs = pm.splits[i];
    auto f_at = [&](uint32_t f) { return &face[std::min(f, nf - 1)]; };
    auto v_at = [&](uint32_t v) { return &incident[std::min(v, nn - 1)]; };
    for (uint32_t f : vs.fn) __builtin_prefetch(f_at(f));
    __builtin_prefetch(f_at(vs.fl));
    __builtin_prefetch(f_at(vs.fr));
    __builtin_prefetch(v_at(vs.vt));
    __builtin_prefetch(v_at(vs.vu));
  };
  for (uint32_t i = static_cast<uint32_t>(pm.splits.size()); i-- > 0;) {
    if (i >= kAhead) prefetch(i - kAhead);
    const uint32_t s = n + i;
    const VertexSplit& vs = pm.splits[i];
    auto where = [i] { return "split " + std::to_string(i) + ": "; };  // built only for an error
    if (vs.vt >= s || vs.vu >= s || vs.vt == vs.vu || vs.fl >= nf || vs.fr >= nf || vs.fl == vs.fr ||
        vs.fn[0] >= nf || vs.fn[1] >= nf || vs.fn[2] >= nf || vs.fn[3] >= nf)
      return fail(where() + "a vertex or face index out of range");
    if (incident[s] == 0) return fail(where() + "its vertex is not in the mesh when it is split");
    if (face[vs.fl].active || face[vs.fr].active) return fail(where() + "creates a face that exists");
    for (uint32_t f : vs.fn)
      if (!face[f].active || corner(f, s) == 3) return fail(where() + "a neighbour face is missing or not around the vertex");
    const uint32_t fn_tl = vs.fn[0], fn_ul = vs.fn[1], fn_ur = vs.fn[2], fn_rt = vs.fn[3];
    // The two fans are disjoint: fan_t may not enter a face fan_u marked.
    if (!fan(s, fn_ul, fn_ur, 2 * i, 2 * i, fan_u) || !fan(s, fn_rt, fn_tl, 2 * i + 1, 2 * i, fan_t) ||
        face[fn_ur].nb[prev3(corner(fn_ur, s))] != fn_rt || face[fn_tl].nb[prev3(corner(fn_tl, s))] != fn_ul)
      return fail(where() + "the faces around its vertex do not form the ring it describes");
    if (incident[s] != fan_u.size() + fan_t.size())
      return fail(where() + "its vertex has faces outside the ring (non-manifold)");
    const uint32_t l = face[fn_ul].v[next3(corner(fn_ul, s))], r = face[fn_rt].v[next3(corner(fn_rt, s))];
    if (face[fn_tl].v[prev3(corner(fn_tl, s))] != l || face[fn_ur].v[prev3(corner(fn_ur, s))] != r || l == r)
      return fail(where() + "inconsistent wedge vertices");
    if (incident[vs.vt] != 0 || incident[vs.vu] != 0) return fail(where() + "a child vertex is already in the mesh");
    // Apply it as doSplit does.
    for (uint32_t f : fan_u) face[f].v[corner(f, s)] = vs.vu;
    for (uint32_t f : fan_t) face[f].v[corner(f, s)] = vs.vt;
    if (!relink(fn_tl, prev3(corner(fn_tl, vs.vt)), fn_ul, vs.fl) || !relink(fn_ul, corner(fn_ul, vs.vu), fn_tl, vs.fl) ||
        !relink(fn_ur, prev3(corner(fn_ur, vs.vu)), fn_rt, vs.fr) || !relink(fn_rt, corner(fn_rt, vs.vt), fn_ur, vs.fr))
      return fail(where() + "ambiguous neighbour links");
    Face& fl = face[vs.fl];
    fl.v = {vs.vu, vs.vt, l};
    fl.nb = {vs.fr, fn_tl, fn_ul};
    fl.active = 1;
    Face& fr = face[vs.fr];
    fr.v = {vs.vt, vs.vu, r};
    fr.nb = {vs.fl, fn_ur, fn_rt};
    fr.active = 1;
    incident[vs.vu] = static_cast<uint32_t>(fan_u.size()) + 2;
    incident[vs.vt] = static_cast<uint32_t>(fan_t.size()) + 2;
    incident[s] = 0;
    ++incident[l];
    ++incident[r];
  }
  // Same face, same orientation; the first corner may differ (a split numbers fl and fr
  // from vu and vt).
  auto sameFace = [](const std::array<uint32_t, 3>& a, const std::array<uint32_t, 3>& b) {
    for (uint32_t k = 0; k < 3; ++k)
      if (a[0] == b[k] && a[1] == b[next3(k)] && a[2] == b[prev3(k)]) return true;
    return false;
  };
  for (uint32_t f = 0; f < nf; ++f)
    if (!face[f].active || !sameFace(face[f].v, pm.faces[f]))
      return fail("the fully refined mesh differs from the stored faces (face " + std::to_string(f) + ")");
  return Status::success();
}

}  // namespace

Status savePm(const std::filesystem::path& path, const ProgressiveMesh& pm) {
  FileHeader h{};
  std::memcpy(h.magic, kMagic, 8);
  h.version = kPmFileVersion;
  h.vertex_count = pm.vertexCount();
  h.face_count = pm.faceCount();
  h.split_count = static_cast<uint32_t>(pm.splits.size());
  h.base_face_count = static_cast<uint32_t>(pm.base_faces.size());
  h.content_hash = pm.content_hash;
  h.params_hash = pm.params_hash;
  h.payload_size = payloadSize(h.vertex_count, h.face_count, h.split_count, h.base_face_count);
  std::string payload;
  payload.reserve(h.payload_size);
  append(payload, pm.positions);
  append(payload, pm.faces);
  append(payload, pm.vertex_flags);
  payload.append(((pm.vertex_flags.size() + 3) / 4) * 4 - pm.vertex_flags.size(), '\0');
  append(payload, pm.splits);
  append(payload, pm.base_faces);
  append(payload, pm.base_corners);
  append(payload, pm.base_neighbors);
  if (payload.size() != h.payload_size)
    return Error::runtime(path.string() + ": internal error: inconsistent progressive mesh");
  h.checksum = checksumOf(h, payload.data(), payload.size());
  return writeFileAtomically(path, [&](std::ostream& os) -> Status {
    os.write(reinterpret_cast<const char*>(&h), sizeof(h));
    os.write(payload.data(), static_cast<std::streamsize>(payload.size()));
    return Status::success();
  });
}

Result<ProgressiveMesh> loadPm(const std::filesystem::path& path) {
  const std::string name = path.string();
  if (Status s = checkInputFile(path, "progressive mesh file"); !s) return s.error();
  // The size of the file opened, not of the path: a writer may rename a new cache over the
  // path at any moment (writeFileAtomically), and the open file stays the old one.
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error::runtime(name + ": cannot open progressive mesh file");
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  in.seekg(0, std::ios::beg);
  if (end < 0 || !in) return Error::runtime(name + ": cannot read progressive mesh file");
  const uint64_t file_size = static_cast<uint64_t>(end);
  if (file_size < sizeof(FileHeader))
    return Error::runtime(name + ": truncated progressive mesh file (" +
                          std::to_string(file_size) + " bytes, header needs 64)");
  FileHeader h;
  in.read(reinterpret_cast<char*>(&h), sizeof(h));
  if (!in) return Error::runtime(name + ": cannot read header");
  if (std::memcmp(h.magic, kMagic, 8) != 0)
    return Error::runtime(name + ": not a lodline progressive mesh file (bad magic)");
  if (h.version != kPmFileVersion)
    return Error::runtime(name + ": progressive mesh file version " + std::to_string(h.version) +
                          " is not supported (expected " + std::to_string(kPmFileVersion) + ")");
  const uint64_t expect =
      payloadSize(h.vertex_count, h.face_count, h.split_count, h.base_face_count);
  if (h.payload_size != expect)
    return Error::runtime(name + ": corrupt header (payload size does not match the counts)");
  if (file_size - sizeof(FileHeader) < expect)
    return Error::runtime(name + ": truncated progressive mesh file (" +
                          std::to_string(file_size) + " bytes, expected " +
                          std::to_string(expect + sizeof(FileHeader)) + ")");
  if (file_size - sizeof(FileHeader) > expect)
    return Error::runtime(name + ": trailing bytes after the progressive mesh data");
  // Straight into the arrays (no copy of the payload).
  ProgressiveMesh pm;
  bool read_ok = true;
  auto read = [&](auto& v, size_t count) {
    v.resize(count);
    const size_t bytes = count * sizeof(v[0]);
    if (!read_ok || bytes == 0) return;
    in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(bytes));
    read_ok = static_cast<bool>(in);
  };
  read(pm.positions, h.vertex_count);
  read(pm.faces, h.face_count);
  read(pm.vertex_flags, h.vertex_count);
  std::vector<char> pad;
  read(pad, ((h.vertex_count + 3) / 4) * 4 - h.vertex_count);
  read(pm.splits, h.split_count);
  read(pm.base_faces, h.base_face_count);
  read(pm.base_corners, h.base_face_count);
  read(pm.base_neighbors, h.base_face_count);
  if (!read_ok) return Error::runtime(name + ": read error");
  pm.content_hash = h.content_hash;
  pm.params_hash = h.params_hash;
  // The checksum and finalize() (index checks, the hierarchy's derived arrays) on a second
  // thread while this one replays the refinement (verifyRefinement(), which checks the indices
  // it follows itself): the replay is most of a load (1.1M faces: about 185 of 270 ms, the
  // other two 60), and the two read the records and write disjoint members. The errors are
  // reported in the order the checks had when they ran one after the other.
  bool checksum_ok = false;
  Status finalized = Status::success();
  std::exception_ptr thrown;  // (std::bad_alloc, as from the loads before)
  auto runChecks = [&] {
    try {
      FileHeader unsummed = h;
      unsummed.checksum = 0;
      StreamingHash sum(hashBytes(&unsummed, sizeof(unsummed)));
      auto add = [&](const auto& v) {
        if (!v.empty()) sum.update(v.data(), v.size() * sizeof(v[0]));
      };
      add(pm.positions);
      add(pm.faces);
      add(pm.vertex_flags);
      add(pad);
      add(pm.splits);
      add(pm.base_faces);
      add(pm.base_corners);
      add(pm.base_neighbors);
      checksum_ok = sum.finish() == h.checksum;
      if (checksum_ok) finalized = pm.finalize(name);
    } catch (...) {
      thrown = std::current_exception();
    }
  };
  std::thread checks;
  try {
    checks = std::thread(runChecks);
  } catch (const std::system_error&) {  // no thread to be had: one after the other
    runChecks();
  }
  struct Join {
    std::thread& t;
    ~Join() {
      if (t.joinable()) t.join();
    }
  };
  Status replayed = Status::success();
  {
    Join join{checks};
    replayed = verifyRefinement(pm, name);
  }
  if (thrown) std::rethrow_exception(thrown);
  if (!checksum_ok) return Error::runtime(name + ": checksum mismatch (file corrupt)");
  if (!finalized.ok()) return finalized.error();
  if (!replayed.ok()) return replayed.error();
  return pm;
}

std::filesystem::path pmCachePath(const std::filesystem::path& cache_dir, uint64_t content_hash) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%016llx.lpm", static_cast<unsigned long long>(content_hash));
  return cache_dir / buf;
}

Result<ProgressiveMesh> loadOrBuildPm(const TriMesh& mesh, uint64_t content_hash,
                                      const std::filesystem::path& cache_dir,
                                      const PmBuildParams& params, const PmProgress& progress,
                                      std::string* note) {
  const std::filesystem::path path = pmCachePath(cache_dir, content_hash);
  const uint64_t params_hash = buildParamsHash(params);
  removeStaleTemporaries(path);  // left by a build that was killed while writing
  std::string why = "no cache";
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) {
    Result<ProgressiveMesh> cached = loadPm(path);
    if (cached.ok()) {
      const ProgressiveMesh& pm = cached.value();
      // The header's hashes name the model; the arrays must then be the model's (a file
      // whose header was copied from another cache would otherwise pass).
      if (pm.content_hash == content_hash && pm.params_hash == params_hash && pm.positions == mesh.positions &&
          pm.faces == mesh.faces) {
        if (note) *note = "loaded progressive mesh cache " + path.string();
        return cached;
      }
      why = "cache stale (different model or build parameters)";
    } else {
      why = "cache unreadable (" + cached.error().message + ")";
    }
  }
  Result<ProgressiveMesh> built = buildProgressiveMesh(mesh, params, progress);
  if (!built.ok()) return built;
  built.value().content_hash = content_hash;
  std::filesystem::create_directories(cache_dir, ec);
  Status saved = ec ? Status(Error::runtime(cache_dir.string() + ": " + ec.message()))
                    : savePm(path, built.value());
  if (note) {
    *note = why + ", rebuilt progressive mesh";
    if (saved.ok()) *note += " and wrote " + path.string();
    else *note += "; could not write the cache: " + saved.error().message;
  }
  return built;
}

}  // namespace lodline
