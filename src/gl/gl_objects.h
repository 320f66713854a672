// Move-only RAII owners of OpenGL objects (docs/design.md §6). Each must be destroyed while the
// context that created it is current.
#pragma once

#include <utility>

#include <glad/gl.h>

namespace lodline {

template <void (*Delete)(GLuint)>
class GlHandle {
 public:
  GlHandle() = default;
  explicit GlHandle(GLuint id) : id_(id) {}
  ~GlHandle() { reset(); }
  GlHandle(GlHandle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  GlHandle& operator=(GlHandle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  GlHandle(const GlHandle&) = delete;
  GlHandle& operator=(const GlHandle&) = delete;

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_) Delete(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

namespace gldetail {
inline void deleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
inline void deleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
inline void deleteTexture(GLuint id) { glDeleteTextures(1, &id); }
inline void deleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
inline void deleteRenderbuffer(GLuint id) { glDeleteRenderbuffers(1, &id); }
inline void deleteProgram(GLuint id) { glDeleteProgram(id); }
inline void deleteShader(GLuint id) { glDeleteShader(id); }
}  // namespace gldetail

using GlBuffer = GlHandle<gldetail::deleteBuffer>;
using GlVertexArray = GlHandle<gldetail::deleteVertexArray>;
using GlTexture = GlHandle<gldetail::deleteTexture>;
using GlFramebuffer = GlHandle<gldetail::deleteFramebuffer>;
using GlRenderbuffer = GlHandle<gldetail::deleteRenderbuffer>;
using GlProgram = GlHandle<gldetail::deleteProgram>;
using GlShader = GlHandle<gldetail::deleteShader>;

inline GlBuffer makeBuffer() { GLuint id = 0; glGenBuffers(1, &id); return GlBuffer(id); }
inline GlVertexArray makeVertexArray() { GLuint id = 0; glGenVertexArrays(1, &id); return GlVertexArray(id); }
inline GlTexture makeTexture() { GLuint id = 0; glGenTextures(1, &id); return GlTexture(id); }
inline GlFramebuffer makeFramebuffer() { GLuint id = 0; glGenFramebuffers(1, &id); return GlFramebuffer(id); }
inline GlRenderbuffer makeRenderbuffer() { GLuint id = 0; glGenRenderbuffers(1, &id); return GlRenderbuffer(id); }

}  // namespace lodline
