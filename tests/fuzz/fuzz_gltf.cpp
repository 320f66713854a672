// Fuzz target: glTF 2.0 JSON files (.gltf with embedded base64 buffers) through loadGltf, and
// each accepted node's mesh checked as the scene loader uses it.
#include "gltf_check.h"
#include "harness.h"

LODLINE_FUZZ_TARGET(gltf) { lodline::fuzz::runGltfInput(".gltf", data, size); }
