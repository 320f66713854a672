#include "gl/shader.h"

#include <string>
#include <vector>

namespace lodline {

Result<GlShader> compileShader(GLenum type, std::string_view name) {
  const std::string_view src = embeddedShader(name);
  if (src.empty()) return Error::runtime(std::string(name) + ": no such shader");
  GlShader shader(glCreateShader(type));
  const char* ptr = src.data();
  const GLint len = static_cast<GLint>(src.size());
  glShaderSource(shader.id(), 1, &ptr, &len);
  glCompileShader(shader.id());
  GLint ok = 0;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint log_len = 0;
    glGetShaderiv(shader.id(), GL_INFO_LOG_LENGTH, &log_len);
    std::string log(static_cast<size_t>(std::max(log_len, 1)), '\0');
    glGetShaderInfoLog(shader.id(), log_len, nullptr, log.data());
    return Error::runtime("shaders/" + std::string(name) + ": compile failed: " + log);
  }
  return shader;
}

Result<GlProgram> loadProgram(std::string_view vert_name, std::string_view frag_name) {
  auto vs = compileShader(GL_VERTEX_SHADER, vert_name);
  if (!vs) return vs.error();
  auto fs = compileShader(GL_FRAGMENT_SHADER, frag_name);
  if (!fs) return fs.error();
  GlProgram program(glCreateProgram());
  glAttachShader(program.id(), vs->id());
  glAttachShader(program.id(), fs->id());
  glLinkProgram(program.id());
  GLint ok = 0;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint log_len = 0;
    glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &log_len);
    std::string log(static_cast<size_t>(std::max(log_len, 1)), '\0');
    glGetProgramInfoLog(program.id(), log_len, nullptr, log.data());
    return Error::runtime("shaders/" + std::string(vert_name) + " + " + std::string(frag_name) +
                          ": link failed: " + log);
  }
  return program;
}

}  // namespace lodline
