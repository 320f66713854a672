// Headless OpenGL through EGL on Mesa's surfaceless platform (EGL_MESA_platform_surfaceless)
// or, where that is missing (NVIDIA's driver without a display), on an EGL device
// (EGL_EXT_platform_device): no display, no window; rendering goes into FBOs. Sequence
// measured to work on Debian 12 / Mesa 22.3 (docs/design.md §7).
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <string>

#include <glad/gl.h>

#include "gl/context.h"

namespace lodline {
namespace {

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const std::string l = std::string(" ") + list + " ";
  return l.find(std::string(" ") + name + " ") != std::string::npos;
}

std::string eglErrorString(EGLint e) {
  switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error " + std::to_string(e);
  }
}

class EglContext final : public GlContext {
 public:
  EglContext(EGLDisplay dpy, EGLContext ctx) : dpy_(dpy), ctx_(ctx) {}
  // The display is not terminated: EGL displays are one per platform and device, shared by
  // every context of the process, and eglTerminate would end the others too.
  ~EglContext() override {
    if (eglGetCurrentContext() == ctx_) eglMakeCurrent(dpy_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy_, ctx_);
  }
  void makeCurrent() override {
    if (eglGetCurrentContext() != ctx_) eglMakeCurrent(dpy_, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx_);
  }
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;
  ContextBackend backend() const override { return ContextBackend::kEgl; }

 private:
  EGLDisplay dpy_;
  EGLContext ctx_;
};

// A core-profile context on `dpy` (initialised here; left initialised on failure, since other
// contexts of the process may use the same display).
Result<std::unique_ptr<GlContext>> contextOn(EGLDisplay dpy) {
  EGLint major = 0, minor = 0;
  if (!eglInitialize(dpy, &major, &minor))
    return Error::runtime("eglInitialize failed: " + eglErrorString(eglGetError()));
  if (!eglBindAPI(EGL_OPENGL_API)) {
    return Error::runtime("eglBindAPI(EGL_OPENGL_API) failed: " + eglErrorString(eglGetError()));
  }
  // Core profile without the forward-compatible flag, so glLineWidth > 1 works (docs/design.md §7).
  EGLContext ctx = EGL_NO_CONTEXT;
  for (const EGLint minor_version : {5, 3}) {
    const EGLint minor_for_major = minor_version;
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, minor_for_major == 5 ? 4 : 3,
                              EGL_CONTEXT_MINOR_VERSION, minor_for_major,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_NONE};
    ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (ctx != EGL_NO_CONTEXT) break;
  }
  if (ctx == EGL_NO_CONTEXT) {
    const std::string err = eglErrorString(eglGetError());
    return Error::runtime("eglCreateContext (OpenGL 4.5/3.3 core) failed: " + err);
  }
  if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    const std::string err = eglErrorString(eglGetError());
    eglDestroyContext(dpy, ctx);
    return Error::runtime("eglMakeCurrent failed: " + err);
  }
  auto context = std::make_unique<EglContext>(dpy, ctx);
  if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(eglGetProcAddress)))
    return Error::runtime("could not load OpenGL functions through EGL");
  return std::unique_ptr<GlContext>(std::move(context));
}

}  // namespace

Result<std::unique_ptr<GlContext>> createEglContext(EglPlatform platform) {
  // LODLINE_EGL_PLATFORM=device|surfaceless overrides kAuto (e.g. to run the device path,
  // which a GPU machine takes, on Mesa's software device: scripts/gpu_bench_bundle.sh).
  if (const char* env = std::getenv("LODLINE_EGL_PLATFORM"); env && platform == EglPlatform::kAuto) {
    if (std::string(env) == "device") platform = EglPlatform::kDevice;
    else if (std::string(env) == "surfaceless") platform = EglPlatform::kSurfaceless;
  }
  const char* client_exts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_platform_display) return Error::runtime("eglGetPlatformDisplayEXT is missing");
  std::string why;
  if (platform != EglPlatform::kDevice) {
    if (!hasExtension(client_exts, "EGL_MESA_platform_surfaceless")) {
      why = "EGL_MESA_platform_surfaceless is not supported by this libEGL";
    } else {
      EGLDisplay dpy = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      if (dpy == EGL_NO_DISPLAY) {
        why = "no surfaceless EGL display";
      } else {
        auto ctx = contextOn(dpy);
        if (ctx) return ctx;
        why = "surfaceless: " + ctx.error().message;
      }
    }
    if (platform == EglPlatform::kSurfaceless) return Error::runtime(why);
  }
  // EGL devices (a GPU without a display, or Mesa's software device).
  auto fail = [&](const std::string& msg) {
    return Error::runtime(why.empty() ? msg : why + "; then " + msg);
  };
  if (!hasExtension(client_exts, "EGL_EXT_platform_device"))
    return fail("EGL_EXT_platform_device is not supported by this libEGL");
  if (!hasExtension(client_exts, "EGL_EXT_device_enumeration") && !hasExtension(client_exts, "EGL_EXT_device_base"))
    return fail("EGL_EXT_device_enumeration is not supported by this libEGL");
  auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  if (!query_devices) return fail("eglQueryDevicesEXT is missing");
  EGLDeviceEXT devices[16];
  EGLint count = 0;
  if (!query_devices(16, devices, &count) || count == 0) return fail("no EGL device");
  std::string device_errors;
  for (EGLint i = 0; i < count; ++i) {
    EGLDisplay dpy = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
    if (dpy == EGL_NO_DISPLAY) continue;
    auto ctx = contextOn(dpy);
    if (ctx) return ctx;
    device_errors += (device_errors.empty() ? "" : "; ") + std::string("device ") + std::to_string(i) + ": " +
                     ctx.error().message;
  }
  return fail(std::to_string(count) + " EGL device(s), none gave a context" +
              (device_errors.empty() ? std::string() : " (" + device_errors + ")"));
}

}  // namespace lodline
