// Headless OpenGL through Mesa's OSMesa (software, fallback when EGL is unavailable).
// Kept in its own file: GL/osmesa.h includes GL/gl.h, which clashes with glad.
// libOSMesa is loaded when first asked for (dlopen), not linked: it pulls in LLVM (~120 MB),
// which a program that renders through EGL, e.g. on a GPU machine, never needs
// (scripts/gpu_bench_bundle.sh ships without it).
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <string>
#include <vector>

#include "gl/context.h"

// glad's loader entry point, declared here without including glad/gl.h.
extern "C" {
typedef void (*GLADapiproc)(void);
typedef GLADapiproc (*GLADloadfunc)(const char* name);
int gladLoadGL(GLADloadfunc load);
}

namespace lodline {
namespace {

// The entry points lodline uses, from the loaded library.
struct OsMesaApi {
  decltype(&OSMesaCreateContextAttribs) create = nullptr;
  decltype(&OSMesaMakeCurrent) make_current = nullptr;
  decltype(&OSMesaDestroyContext) destroy = nullptr;
  decltype(&OSMesaGetProcAddress) get_proc = nullptr;
};

// Loads libOSMesa. The handle is not closed again: Mesa and LLVM cannot be unloaded safely,
// and a second dlopen of a loaded library only counts a reference.
Result<OsMesaApi> loadOsMesa() {
  void* lib = nullptr;
  std::string why;
  for (const char* name : {"libOSMesa.so.8", "libOSMesa.so"}) {
    lib = dlopen(name, RTLD_NOW | RTLD_LOCAL);
    if (lib) break;
    if (const char* e = dlerror(); e && why.empty()) why = e;
  }
  if (!lib) return Error::runtime("cannot load libOSMesa (" + why + ")");
  OsMesaApi api;
  api.create = reinterpret_cast<decltype(api.create)>(dlsym(lib, "OSMesaCreateContextAttribs"));
  api.make_current = reinterpret_cast<decltype(api.make_current)>(dlsym(lib, "OSMesaMakeCurrent"));
  api.destroy = reinterpret_cast<decltype(api.destroy)>(dlsym(lib, "OSMesaDestroyContext"));
  api.get_proc = reinterpret_cast<decltype(api.get_proc)>(dlsym(lib, "OSMesaGetProcAddress"));
  if (!api.create || !api.make_current || !api.destroy || !api.get_proc)
    return Error::runtime("libOSMesa lacks OSMesaCreateContextAttribs, OSMesaMakeCurrent, OSMesaDestroyContext or "
                          "OSMesaGetProcAddress");
  return api;
}

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext(const OsMesaApi& api, OSMesaContext ctx) : api_(api), ctx_(ctx), buffer_(4) {
    // OSMesa needs a bound colour buffer to make the context current; rendering itself goes
    // into FBOs, so a 1×1 buffer suffices.
    ok_ = api_.make_current(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1);
  }
  ~OsMesaContext() override { api_.destroy(ctx_); }
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;
  ContextBackend backend() const override { return ContextBackend::kOsMesa; }
  bool current() const { return ok_; }
  void makeCurrent() override { api_.make_current(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1); }

 private:
  OsMesaApi api_;
  OSMesaContext ctx_;
  std::vector<unsigned char> buffer_;
  bool ok_ = false;
};

}  // namespace

Result<std::unique_ptr<GlContext>> createOsMesaContext() {
  auto api = loadOsMesa();
  if (!api) return api.error();
  OSMesaContext ctx = nullptr;
  for (const int minor : {5, 3}) {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, minor == 5 ? 4 : 3,
                           OSMESA_CONTEXT_MINOR_VERSION, minor, 0};
    ctx = api->create(attribs, nullptr);
    if (ctx) break;
  }
  if (!ctx) return Error::runtime("OSMesaCreateContextAttribs (OpenGL 4.5/3.3 core) failed");
  auto context = std::make_unique<OsMesaContext>(*api, ctx);
  if (!context->current()) return Error::runtime("OSMesaMakeCurrent failed");
  if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(api->get_proc)))
    return Error::runtime("could not load OpenGL functions through OSMesa");
  return std::unique_ptr<GlContext>(std::move(context));
}

}  // namespace lodline
