// GLSL programs from the files in shaders/ (embedded into the binary at build time, and
// checked by glslangValidator then). Compile/link failures come back as errors naming the
// shader file and the driver's log.
#pragma once

#include <string>
#include <string_view>

#include "core/result.h"
#include "gl/gl_objects.h"

namespace lodline {

/// Source of an embedded shader file by name ("toon.frag"); empty if there is none.
std::string_view embeddedShader(std::string_view name);

/// Compiles and links the named vertex and fragment shader files.
Result<GlProgram> loadProgram(std::string_view vert_name, std::string_view frag_name);

}  // namespace lodline
