// The windowed context backend (viewer only): a GLFW 3.3 window with an OpenGL 3.3+ core
// context (4.5 where available) and glad loaded. GLFW_INCLUDE_NONE keeps GLFW's GL header
// out of the way of glad.
#pragma once

#include <memory>
#include <string>

#include <GLFW/glfw3.h>

#include "core/result.h"

namespace lodline {

class GlfwWindow {
 public:
  /// Opens a window of `width`×`height` screen units with `samples`× multisampling.
  static Result<GlfwWindow> create(int width, int height, const std::string& title, int samples);
  ~GlfwWindow();
  GlfwWindow(GlfwWindow&& o) noexcept;
  GlfwWindow& operator=(GlfwWindow&& o) noexcept;
  GlfwWindow(const GlfwWindow&) = delete;
  GlfwWindow& operator=(const GlfwWindow&) = delete;

  GLFWwindow* handle() const { return window_; }

 private:
  GlfwWindow() = default;
  GLFWwindow* window_ = nullptr;
};

}  // namespace lodline
