// Fuzz target: binary glTF (.glb: header, JSON chunk, BIN chunk) through loadGltf.
#include "gltf_check.h"
#include "harness.h"

LODLINE_FUZZ_TARGET(glb) { lodline::fuzz::runGltfInput(".glb", data, size); }
