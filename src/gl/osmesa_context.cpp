// Headless OpenGL through Mesa's OSMesa (software, fallback when EGL is unavailable).
// Kept in its own file: GL/osmesa.h includes GL/gl.h, which clashes with glad.
#include <GL/osmesa.h>

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

class OsMesaContext final : public GlContext {
 public:
  explicit OsMesaContext(OSMesaContext ctx) : ctx_(ctx), buffer_(4) {
    // OSMesa needs a bound colour buffer to make the context current; rendering itself goes
    // into FBOs, so a 1×1 buffer suffices.
    ok_ = OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1);
  }
  ~OsMesaContext() override { OSMesaDestroyContext(ctx_); }
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;
  ContextBackend backend() const override { return ContextBackend::kOsMesa; }
  bool current() const { return ok_; }

 private:
  OSMesaContext ctx_;
  std::vector<unsigned char> buffer_;
  bool ok_ = false;
};

}  // namespace

Result<std::unique_ptr<GlContext>> createOsMesaContext() {
  OSMesaContext ctx = nullptr;
  for (const int minor : {5, 3}) {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, minor == 5 ? 4 : 3,
                           OSMESA_CONTEXT_MINOR_VERSION, minor, 0};
    ctx = OSMesaCreateContextAttribs(attribs, nullptr);
    if (ctx) break;
  }
  if (!ctx) return Error::runtime("OSMesaCreateContextAttribs (OpenGL 4.5/3.3 core) failed");
  auto context = std::make_unique<OsMesaContext>(ctx);
  if (!context->current()) return Error::runtime("OSMesaMakeCurrent failed");
  if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(OSMesaGetProcAddress)))
    return Error::runtime("could not load OpenGL functions through OSMesa");
  return std::unique_ptr<GlContext>(std::move(context));
}

}  // namespace lodline
