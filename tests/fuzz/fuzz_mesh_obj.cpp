// Fuzz target: OBJ meshes (vertices, polygons, negative indices, `l` sharp-edge lines) through
// loadMesh and the render pipeline (mesh_pipeline.h).
#include "mesh_pipeline.h"

LODLINE_FUZZ_TARGET(mesh_obj) { lodline::fuzz::runMeshInput(".obj", "", data, size); }
