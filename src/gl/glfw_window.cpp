#include "gl/glfw_window.h"

#include <utility>

#include <glad/gl.h>

namespace lodline {
namespace {

std::string lastGlfwError() {
  const char* msg = nullptr;
  const int code = glfwGetError(&msg);
  if (code == GLFW_NO_ERROR) return "unknown GLFW error";
  return msg ? std::string(msg) : "GLFW error " + std::to_string(code);
}

}  // namespace

Result<GlfwWindow> GlfwWindow::create(int width, int height, const std::string& title, int samples) {
  if (!glfwInit()) return Error::runtime("cannot open a window: " + lastGlfwError() +
                                         " (no display? use `lodline render` for headless output)");
  GlfwWindow w;
  for (const int minor : {5, 3}) {
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, minor == 5 ? 4 : 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, minor);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    // Not forward-compatible: glLineWidth > 1 must keep working (docs/design.md §7).
    glfwWindowHint(GLFW_SAMPLES, samples > 1 ? samples : 0);
    w.window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (w.window_) break;
  }
  if (!w.window_) {
    const std::string err = lastGlfwError();
    glfwTerminate();
    return Error::runtime("cannot open a window with an OpenGL 3.3+ core context: " + err);
  }
  glfwMakeContextCurrent(w.window_);
  glfwSwapInterval(0);
  if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(glfwGetProcAddress)))
    return Error::runtime("could not load OpenGL functions through GLFW");
  return w;
}

GlfwWindow::~GlfwWindow() {
  if (window_) {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
}

GlfwWindow::GlfwWindow(GlfwWindow&& o) noexcept : window_(std::exchange(o.window_, nullptr)) {}

GlfwWindow& GlfwWindow::operator=(GlfwWindow&& o) noexcept {
  if (this != &o) {
    if (window_) {
      glfwDestroyWindow(window_);
      glfwTerminate();
    }
    window_ = std::exchange(o.window_, nullptr);
  }
  return *this;
}

}  // namespace lodline
