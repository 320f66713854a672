#include "gl/context.h"

#include <glad/gl.h>

namespace lodline {

Result<ContextBackend> parseContextBackend(const std::string& name) {
  if (name == "auto") return ContextBackend::kAuto;
  if (name == "egl") return ContextBackend::kEgl;
  if (name == "osmesa") return ContextBackend::kOsMesa;
  return Error::usage("--context: unknown backend '" + name + "' (expected auto, egl or osmesa)");
}

const char* backendName(ContextBackend b) {
  switch (b) {
    case ContextBackend::kAuto: return "auto";
    case ContextBackend::kEgl: return "egl";
    case ContextBackend::kOsMesa: return "osmesa";
  }
  return "?";
}

std::string GlContext::description() const { return currentContextDescription(); }

std::string currentContextDescription() {
  auto str = [](GLenum e) {
    const GLubyte* s = glGetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return str(GL_VERSION) + " / " + str(GL_RENDERER);
}

Result<std::unique_ptr<GlContext>> createHeadlessContext(ContextBackend which) {
  if (which == ContextBackend::kEgl) return createEglContext();
  if (which == ContextBackend::kOsMesa) return createOsMesaContext();
  auto egl = createEglContext();
  if (egl) return egl;
  auto osmesa = createOsMesaContext();
  if (osmesa) return osmesa;
  return Error::runtime("no OpenGL context could be created: tried egl (" + egl.error().message +
                        "), then osmesa (" + osmesa.error().message + ")");
}

}  // namespace lodline
