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
  /// Makes this context current on the calling thread (several contexts may live in one
  /// process, e.g. two Python renderers: each makes its own current before drawing).
  virtual void makeCurrent() = 0;
  /// currentContextDescription() of this context.
  std::string description() const;
};

/// GL_VERSION and GL_RENDERER of the current context, e.g. "4.5 (Core Profile) Mesa 22.3.6
/// / llvmpipe".
std::string currentContextDescription();

/// Creates a headless context. kAuto tries EGL surfaceless, then OSMesa; the error names
/// every backend tried and why each failed.
Result<std::unique_ptr<GlContext>> createHeadlessContext(ContextBackend which);

/// The EGL platform of a headless context: Mesa's surfaceless platform
/// (EGL_MESA_platform_surfaceless), or an EGL device (EGL_EXT_platform_device, the first one
/// that gives a context) — what NVIDIA's driver offers on a machine without a display. kAuto
/// tries surfaceless, then the devices, unless LODLINE_EGL_PLATFORM (device or surfaceless)
/// names one.
enum class EglPlatform { kAuto, kSurfaceless, kDevice };

// Backend factories (each in its own translation unit: GL/osmesa.h clashes with glad).
Result<std::unique_ptr<GlContext>> createEglContext(EglPlatform platform = EglPlatform::kAuto);
Result<std::unique_ptr<GlContext>> createOsMesaContext();

}  // namespace lodline
