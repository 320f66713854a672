// Shared body of the mesh fuzz targets: a mesh file goes the way `lodline render` takes it —
// loadMesh, then (when accepted) the progressive mesh build and a few detail-controlled
// frames at the default view — so a file the reader accepts but the pipeline cannot handle
// is a finding too.
#pragma once

#include <string_view>

#include "harness.h"

namespace lodline::fuzz {

/// Writes `prefix` + data as a file with `extension` and runs it through the pipeline.
void runMeshInput(std::string_view extension, std::string_view prefix, const uint8_t* data, size_t size);

}  // namespace lodline::fuzz
