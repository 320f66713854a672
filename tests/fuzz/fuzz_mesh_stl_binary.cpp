// Fuzz target: binary STL meshes (80-byte header, triangle count, 50-byte facets) through
// loadMesh and the render pipeline (mesh_pipeline.h).
#include "mesh_pipeline.h"

LODLINE_FUZZ_TARGET(mesh_stl_binary) { lodline::fuzz::runMeshInput(".stl", "", data, size); }
