// Fuzz target: the progressive-mesh cache reader (loadPm), and a cache it accepts driven the
// way `render` drives one (selective refinement at the default view, then fully refined and
// coarsened).
//
// Random bytes almost never pass the header and checksum checks, so the harness repairs what
// a hostile writer could forge: the first input byte picks the mode, the rest is the file.
//   mode bit 0 = 0: only the checksum is recomputed (header and size checks are fuzzed);
//   mode bit 0 = 1: the payload size field is set from the counts and the payload padded or
//                   cut to that size (at most 1 MiB) before the checksum is recomputed, so
//                   the fuzzer reaches the structural checks (finalize) and the LOD code.
#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <string>

#include "core/camera.h"
#include "frame/lod_drawing.h"
#include "harness.h"
#include "io/load_mesh.h"
#include "lod/adaptive_mesh.h"
#include "core/hash.h"
#include "pm/pm_file.h"
#include "pm/progressive_mesh.h"

namespace {

constexpr size_t kHeader = 64;

uint32_t u32At(const std::string& b, size_t at) {
  uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

// Mirrors the layout documented in pm_file.h.
std::string repair(const uint8_t* data, size_t size) {
  if (size == 0) return {};
  const bool consistent = data[0] & 1;
  std::string b(reinterpret_cast<const char*>(data + 1), size - 1);
  if (b.size() < kHeader) return b;
  if (consistent) {
    const uint64_t n = u32At(b, 12), nf = u32At(b, 16), ns = u32At(b, 20), nb = u32At(b, 24);
    const uint64_t payload = n * 12 + nf * 12 + ((n + 3) / 4) * 4 + ns * 32 + nb * 28;
    if (payload <= (1u << 20)) {
      std::memcpy(b.data() + 48, &payload, 8);
      b.resize(kHeader + payload, '\0');
    }
  }
  std::memset(b.data() + 56, 0, 8);
  const uint64_t sum =
      lodline::hashBytes(b.data() + kHeader, b.size() - kHeader, lodline::hashBytes(b.data(), kHeader));
  std::memcpy(b.data() + 56, &sum, 8);
  return b;
}

}  // namespace

LODLINE_FUZZ_TARGET(pm_cache) {
  using namespace lodline;
  const std::string bytes = repair(data, size);
  const fuzz::InputFile input(".lpm", bytes, nullptr, 0);
  Result<ProgressiveMesh> pm = loadPm(input.path());
  if (!pm) {
    fuzz::expectCleanError(pm.error(), input.path());
    return;
  }
  // A cache is only used for a model with the same arrays (loadOrBuildPm checks them), and
  // a model's mesh passed validateMesh.
  TriMesh full{pm->positions, pm->faces, {}};
  if (!validateMesh(full, "cache").ok()) return;
  (void)pm->baseMesh();
  {
    AdaptiveMesh lod(*pm);
    lod.fullyRefine();
    TriMesh out;
    std::vector<uint32_t> ids;
    lod.exportCompact(out, ids);
    lod.fullyCoarsen();
    lod.exportCompact(out, ids);
  }
  auto shared = std::make_shared<const ProgressiveMesh>(std::move(pm.value()));
  LodDrawing drawing(std::move(full), std::move(shared));
  const Camera camera = orbitCamera(drawing.bounds(), OrbitView{}, 35.0f, 1.5f);
  std::array<bool, kLineKindCount> enabled;
  enabled.fill(true);
  Result<int> steps = drawing.converge(camera, 96, 64, DetailParams{}, 1.0f / 30.0f, 6, enabled);
  if (!steps) fuzz::fail("converge failed on an accepted cache: " + steps.error().message);
}
