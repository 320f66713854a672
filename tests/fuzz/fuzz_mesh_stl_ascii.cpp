// Fuzz target: ASCII STL meshes through loadMesh and the render pipeline (mesh_pipeline.h). The
// fixed "solid " keeps the fuzzer on the ASCII reader.
#include "mesh_pipeline.h"

LODLINE_FUZZ_TARGET(mesh_stl_ascii) { lodline::fuzz::runMeshInput(".stl", "solid ", data, size); }
