// OpenGL context backends behind one small interface (docs/design.md §6): EGL on Mesa's
// surfaceless platform (headless default), OSMesa (headless fallback) and GLFW (window,
// see glfw_window.h). A context is current on the creating thread after creation.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/result.h"

namespace lodline {

enum class ContextBackend { kAuto, kEgl, kOsMesa };

/// Parses "auto", "egl" or "osmesa".
Result<ContextBackend> parseContextBackend(const std::string& name);
const char* backendName(ContextBackend b);

/// A current OpenGL ≥ 3.3 core context with glad loaded. Move-only via unique_ptr.
class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual ContextBackend backend() const = 0;
  /// currentContextDescription() of this context.
  std::string description() const;
};

/// GL_VERSION and GL_RENDERER of the current context, e.g. "4.5 (Core Profile) Mesa 22.3.6
/// / llvmpipe".
std::string currentContextDescription();

/// Creates a headless context. kAuto tries EGL surfaceless, then OSMesa; the error names
/// every backend tried and why each failed.
Result<std::unique_ptr<GlContext>> createHeadlessContext(ContextBackend which);

// Backend factories (each in its own translation unit: GL/osmesa.h clashes with glad).
Result<std::unique_ptr<GlContext>> createEglContext();
Result<std::unique_ptr<GlContext>> createOsMesaContext();

}  // namespace lodline
