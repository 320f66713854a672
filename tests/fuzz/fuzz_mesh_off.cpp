// Fuzz target: OFF meshes (ASCII, and the "OFF BINARY" variant) through loadMesh and the render
// pipeline (mesh_pipeline.h).
#include "mesh_pipeline.h"

LODLINE_FUZZ_TARGET(mesh_off) { lodline::fuzz::runMeshInput(".off", "", data, size); }
