// Fuzz target: binary (little-endian) PLY meshes through loadMesh and the render pipeline
// (mesh_pipeline.h). The fixed first two header lines keep the fuzzer on the binary reader.
#include "mesh_pipeline.h"

LODLINE_FUZZ_TARGET(mesh_ply_binary) {
  lodline::fuzz::runMeshInput(".ply", "ply\nformat binary_little_endian 1.0\n", data, size);
}
