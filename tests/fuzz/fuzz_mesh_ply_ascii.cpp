// Fuzz target: ASCII PLY meshes through loadMesh and the render pipeline (mesh_pipeline.h). The
// fixed first two header lines keep the fuzzer on the ASCII reader.
#include "mesh_pipeline.h"

LODLINE_FUZZ_TARGET(mesh_ply_ascii) { lodline::fuzz::runMeshInput(".ply", "ply\nformat ascii 1.0\n", data, size); }
