// Shared helpers for the test executables.
#pragma once

#include <filesystem>
#include <string>

#include "core/mesh.h"
#include "core/render_params.h"

namespace lodline::test {

/// A frame and the style of its one object: what a single-model render needs.
struct Look {
  FrameParams frame;
  ObjectStyle style;
};

/// Path of a CGAL demo mesh (data/meshes/NAME, extracted by scripts/setup.sh), or an empty
/// path when it is not there (tests then GTEST_SKIP with a message).
std::filesystem::path dataMesh(const std::string& name);

/// Runs `command` through the shell with EGL_PLATFORM=surfaceless, stderr merged into
/// `output` (optional); returns the exit status (128 + signal when killed).
int runCommand(const std::string& command, std::string* output = nullptr);

/// Runs the built `lodline` binary with `args` (as runCommand).
int runLodline(const std::string& args, std::string* output = nullptr);

/// A fresh empty directory under the system temp dir, removed by the destructor.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace lodline::test

#include <array>
#include <cstdint>
#include <vector>

namespace lodline::test {

/// One mesh node of a test glTF file: positions and triangle indices (uint32), placed by
/// translation/rotation (quaternion x, y, z, w)/scale, optionally the child of `parent`.
struct GltfTestNode {
  std::vector<std::array<float, 3>> positions;
  std::vector<uint32_t> indices;
  std::array<float, 3> translation{0, 0, 0};
  std::array<float, 4> rotation{0, 0, 0, 1};
  std::array<float, 3> scale{1, 1, 1};
  int parent = -1;
  std::string name;
};

/// Writes a glTF 2.0 file of `nodes` (one mesh each): `.gltf` with the buffer embedded as a
/// base64 data URI, or binary `.glb`, by `path`'s extension.
void writeGltf(const std::filesystem::path& path, const std::vector<GltfTestNode>& nodes);

/// A cube of half-size 1 with 24 vertices (4 per face, as glTF exporters write hard edges).
GltfTestNode gltfCube();

/// A PNG whose header claims w x h 8-bit grey pixels, followed by a stub of pixel data (the
/// file is 76 bytes whatever it claims): for the readers' size limits.
std::string pngHeaderOnly(uint32_t w, uint32_t h);

/// `m` as the text of an ASCII OFF file.
std::string offText(const TriMesh& m);

/// `m` with its vertices renumbered and its faces reordered at random (seeded), as a refined
/// mesh's file may store them; marked edges and face materials follow.
TriMesh shuffledMesh(TriMesh m, unsigned seed);

}  // namespace lodline::test
