// `lodline view MODEL`: the interactive viewer. Same parameters and same drawing code as
// `render`; orbit/pan/zoom with mouse and keys; fps in the window title.
//
// Mouse: left-drag orbits, right- or middle-drag pans, wheel zooms.
// Keys: arrows orbit, +/- (or PageUp/PageDown) zoom, T toggles toon/lines, 1-4 toggle
// contour/suggestive/crease/boundary lines, [ and ] halve/double the target triangle area
// (detail control), G toggles geomorphs, C starts/stops recording the camera to a path file
// (lodline-path.json, replayable with --play or `capture --path`), R resets the view, P
// saves lodline-view.png, Esc or Q quits. --play FILE.json plays a camera path (looping).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include <glad/gl.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "app/commands.h"
#include "app/options.h"
#include "core/timer.h"
#include "app/model.h"
#include "frame/camera_path.h"

#ifdef LODLINE_HAVE_VIEWER
#include "gl/glfw_window.h"
#include "gl/renderer.h"
#endif

namespace lodline {

#ifdef LODLINE_HAVE_VIEWER
namespace {

struct ViewerState {
  OrbitView orbit;
  OrbitView initial;
  glm::vec3 pan{0.0f};
  RenderParams params;
  DetailParams detail;
  float fov_deg = 35.0f;
  bool dirty = true;  // camera or line selection changed: lines must be recomputed
  bool dragging_orbit = false, dragging_pan = false;
  double last_x = 0.0, last_y = 0.0;
  bool screenshot = false;
  Bounds bounds;
  // Camera-path recording (key C) and playback (--play).
  bool recording = false;
  bool toggle_recording = false;
  std::vector<CameraKey> recorded;
  Stopwatch record_clock;
  std::optional<CameraPath> playing;
  Stopwatch play_clock;
};

Camera viewerCamera(const ViewerState& s, float aspect) {
  Bounds shifted = s.bounds;
  shifted.center += s.pan;
  Camera cam = orbitCamera(shifted, s.orbit, s.fov_deg, aspect);
  fitClipPlanes(cam, s.bounds);
  return cam;
}

void zoom(ViewerState& s, float factor) {
  s.orbit.distance = std::clamp(s.orbit.distance * factor, 0.05f, 200.0f);
  s.dirty = true;
}

void onKey(GLFWwindow* w, int key, int, int action, int) {
  if (action == GLFW_RELEASE) return;
  auto& s = *static_cast<ViewerState*>(glfwGetWindowUserPointer(w));
  switch (key) {
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q: glfwSetWindowShouldClose(w, GLFW_TRUE); break;
    case GLFW_KEY_LEFT: s.orbit.azimuth_deg -= 5.0f; s.dirty = true; break;
    case GLFW_KEY_RIGHT: s.orbit.azimuth_deg += 5.0f; s.dirty = true; break;
    case GLFW_KEY_UP: s.orbit.elevation_deg = std::min(89.0f, s.orbit.elevation_deg + 5.0f); s.dirty = true; break;
    case GLFW_KEY_DOWN: s.orbit.elevation_deg = std::max(-89.0f, s.orbit.elevation_deg - 5.0f); s.dirty = true; break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
    case GLFW_KEY_PAGE_UP: zoom(s, 1.0f / 1.15f); break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
    case GLFW_KEY_PAGE_DOWN: zoom(s, 1.15f); break;
    case GLFW_KEY_T:
      s.params.style = s.params.style == Style::kToon ? Style::kLines : Style::kToon;
      break;
    case GLFW_KEY_1:
    case GLFW_KEY_2:
    case GLFW_KEY_3:
    case GLFW_KEY_4: {
      auto& k = s.params.lines.kinds[key - GLFW_KEY_1];
      k.enabled = !k.enabled;
      s.dirty = true;
      break;
    }
    case GLFW_KEY_LEFT_BRACKET: s.detail.target_area = std::max(0.25f, s.detail.target_area * 0.5f); break;
    case GLFW_KEY_RIGHT_BRACKET: s.detail.target_area = std::min(4096.0f, s.detail.target_area * 2.0f); break;
    case GLFW_KEY_G: s.detail.geomorphs = !s.detail.geomorphs; break;
    case GLFW_KEY_R: s.orbit = s.initial; s.pan = glm::vec3(0.0f); s.dirty = true; break;
    case GLFW_KEY_P: s.screenshot = true; break;
    case GLFW_KEY_C: s.toggle_recording = true; break;
    default: break;
  }
}

void onMouseButton(GLFWwindow* w, int button, int action, int) {
  auto& s = *static_cast<ViewerState*>(glfwGetWindowUserPointer(w));
  glfwGetCursorPos(w, &s.last_x, &s.last_y);
  const bool down = action == GLFW_PRESS;
  if (button == GLFW_MOUSE_BUTTON_LEFT) s.dragging_orbit = down;
  if (button == GLFW_MOUSE_BUTTON_RIGHT || button == GLFW_MOUSE_BUTTON_MIDDLE) s.dragging_pan = down;
}

void onCursor(GLFWwindow* w, double x, double y) {
  auto& s = *static_cast<ViewerState*>(glfwGetWindowUserPointer(w));
  const double dx = x - s.last_x, dy = y - s.last_y;
  s.last_x = x;
  s.last_y = y;
  if (s.dragging_orbit) {
    s.orbit.azimuth_deg -= static_cast<float>(dx) * 0.4f;
    s.orbit.elevation_deg = std::clamp(s.orbit.elevation_deg + static_cast<float>(dy) * 0.4f, -89.0f, 89.0f);
    s.dirty = true;
  } else if (s.dragging_pan) {
    int width = 1, height = 1;
    glfwGetWindowSize(w, &width, &height);
    const Camera cam = viewerCamera(s, static_cast<float>(width) / static_cast<float>(height));
    const glm::vec3 fwd = cam.forward();
    const glm::vec3 right = glm::normalize(glm::cross(fwd, cam.up));
    const glm::vec3 up = glm::cross(right, fwd);
    // One pixel moves the target by the size of a pixel at the target's distance.
    const float dist = glm::length(cam.target - cam.eye);
    const float px = 2.0f * dist * std::tan(glm::radians(s.fov_deg) * 0.5f) / static_cast<float>(height);
    s.pan += (-static_cast<float>(dx) * right + static_cast<float>(dy) * up) * px;
    s.dirty = true;
  }
}

void onScroll(GLFWwindow* w, double, double dy) {
  auto& s = *static_cast<ViewerState*>(glfwGetWindowUserPointer(w));
  zoom(s, static_cast<float>(std::pow(1.1, -dy)));
}

// Starts or stops recording; on stop, writes the keys as lodline-path.json.
void toggleRecording(ViewerState& s) {
  s.toggle_recording = false;
  if (!s.recording) {
    s.recorded.clear();
    s.record_clock = Stopwatch();
    s.recording = true;
    std::cerr << "lodline: recording the camera (C again to stop)\n";
    return;
  }
  s.recording = false;
  if (s.recorded.size() < 2) {
    std::cerr << "lodline: recording too short, nothing written\n";
    return;
  }
  if (Status st = saveCameraPath("lodline-path.json", CameraPath(s.recorded)); !st) reportError(st.error());
  else
    std::cerr << "lodline: wrote lodline-path.json (" << s.recorded.size() << " keys, "
              << s.recorded.back().time << " s)\n";
}

int runView(const ViewOptions& o, const DetailOptions& d, const std::string& play) {
  auto resolved = resolveViewOptions(o);
  if (!resolved) return reportError(resolved.error());
  auto detail = resolveDetailOptions(d);
  if (!detail) return reportError(detail.error());
  auto model = loadModel(resolved->model, *detail);
  if (!model) return reportError(model.error());
  LodDrawing& lod_drawing = **model;
  const LineDrawing& drawing = lod_drawing.drawing();

  ViewerState s;
  s.params = resolved->render;
  s.detail = detail->params;
  s.fov_deg = resolved->fov_deg;
  s.bounds = drawing.bounds();
  s.orbit = resolved->orbit;
  if (s.orbit.distance <= 0.0f) {
    const Camera c = orbitCamera(s.bounds, s.orbit, s.fov_deg,
                                 static_cast<float>(s.params.width) / static_cast<float>(s.params.height));
    s.orbit.distance = glm::length(c.eye - c.target) / std::max(s.bounds.radius, 1e-6f);
  }
  s.initial = s.orbit;
  if (!play.empty()) {
    auto path = loadCameraPath(play);
    if (!path) return reportError(path.error());
    s.playing = std::move(path.value());
  }

  auto window = GlfwWindow::create(s.params.width, s.params.height,
                                   "lodline - " + resolved->model.filename().string(), s.params.msaa);
  if (!window) return reportError(window.error());
  GLFWwindow* w = window->handle();
  glfwSetWindowUserPointer(w, &s);
  glfwSetKeyCallback(w, onKey);
  glfwSetMouseButtonCallback(w, onMouseButton);
  glfwSetCursorPosCallback(w, onCursor);
  glfwSetScrollCallback(w, onScroll);
  {
    auto renderer = Renderer::create();
    if (!renderer) return reportError(renderer.error());
    if (s.params.msaa > 1) glEnable(GL_MULTISAMPLE);

    Stopwatch fps_clock, frame_clock;
    float mean_dt = 1.0f / 20.0f;
    int frames = 0;
    while (!glfwWindowShouldClose(w)) {
      glfwPollEvents();
      int fb_w = 1, fb_h = 1;
      glfwGetFramebufferSize(w, &fb_w, &fb_h);
      if (fb_w <= 0 || fb_h <= 0) {
        glfwWaitEvents();
        continue;
      }
      Camera cam = viewerCamera(s, static_cast<float>(fb_w) / static_cast<float>(fb_h));
      if (s.playing) {
        const double duration = std::max(s.playing->duration(), 1e-3);
        cam = s.playing->at(s.playing->keys().front().time + std::fmod(s.play_clock.elapsed() / 1000.0, duration),
                            s.bounds);
        s.dirty = true;
      }
      if (s.toggle_recording) toggleRecording(s);
      if (s.recording) {
        const double t = s.record_clock.elapsed() / 1000.0;
        // Keys every 0.1 s (times must increase strictly).
        if (s.recorded.empty() || t - s.recorded.back().time >= 0.1)
          s.recorded.push_back({t, cam.eye, cam.target, cam.up, cam.fov_deg});
      }
      // Detail control adapts every frame (geomorphs run on while the camera rests); full
      // detail recomputes lines only when the view or the line selection changed.
      const float dt = std::min(0.1f, static_cast<float>(frame_clock.lap() / 1000.0));
      if (s.dirty || lod_drawing.detailControlled()) {
        std::array<bool, kLineKindCount> enabled{};
        for (int k = 0; k < kLineKindCount; ++k) enabled[k] = s.params.lines.kinds[k].enabled;
        // Smoothing at the measured frame rate (Jeong §3.3), from a running mean of dt.
        mean_dt = 0.9f * mean_dt + 0.1f * std::max(dt, 1e-3f);
        const float smooth_w = detail->smoothing.enabled
                            ? smoothingWeight(detail->smoothing.alpha, detail->smoothing.seconds, 1.0f / mean_dt)
                            : 1.0f;
        if (Status st = lod_drawing.frame(cam, fb_w, fb_h, s.detail, dt, enabled, smooth_w); !st)
          return reportError(st.error());
        if (lod_drawing.meshChanged())
          renderer->setMesh(drawing.mesh().positions, drawing.normals(), drawing.mesh().faces,
                            drawing.mesh().marked_edges);
        renderer->setLines(drawing.lines());
        s.dirty = false;
      }
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      renderer->draw(cam, s.params, fb_w, fb_h);
      if (s.screenshot) {
        Image img(fb_w, fb_h);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadBuffer(GL_BACK);
        glReadPixels(0, 0, fb_w, fb_h, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
        Image flipped(fb_w, fb_h);
        for (int y = 0; y < fb_h; ++y)
          std::copy_n(img.pixel(0, fb_h - 1 - y), static_cast<size_t>(fb_w) * 4, flipped.pixel(0, y));
        if (Status st = writePng("lodline-view.png", flipped); !st) reportError(st.error());
        else std::cerr << "lodline: saved lodline-view.png\n";
        s.screenshot = false;
      }
      glfwSwapBuffers(w);
      ++frames;
      if (fps_clock.elapsed() > 500.0) {
        const double fps = frames * 1000.0 / fps_clock.lap();
        frames = 0;
        char title[256];
        if (lod_drawing.lod())
          std::snprintf(title, sizeof(title), "lodline - %s - %.1f fps - %zu faces (T %.3g px^2%s) - %zu line segments",
                        resolved->model.filename().c_str(), fps, renderer->faceCount(), s.detail.target_area,
                        s.detail.geomorphs ? "" : ", no geomorphs", renderer->segmentsDrawn());
        else
          std::snprintf(title, sizeof(title), "lodline - %s - %.1f fps - %zu faces - %zu line segments",
                        resolved->model.filename().c_str(), fps, renderer->faceCount(), renderer->segmentsDrawn());
        glfwSetWindowTitle(w, title);
      }
    }
  }  // GL objects die here, before the window and its context
  return 0;
}

}  // namespace
#endif

Command addViewCommand(CLI::App& parent) {
  struct Opts {
    ViewOptions view;
    DetailOptions detail;
    std::string play;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = parent.add_subcommand(
      "view",
      "Open a model in an interactive window.\n"
      "  Mouse: left-drag orbit, right/middle-drag pan, wheel zoom.\n"
      "  Keys: arrows orbit, +/- zoom, T toon/lines, 1-4 toggle contour/suggestive/crease/boundary,\n"
      "        [ ] halve/double the target triangle area, G geomorphs on/off,\n"
      "        C start/stop recording the camera to lodline-path.json,\n"
      "        R reset view, P save lodline-view.png, Esc/Q quit.");
  addViewOptions(*cmd, o->view);
  addDetailOptions(*cmd, o->detail);
  cmd->add_option("--play", o->play, "Play a camera path file (.json, e.g. one recorded with C), looping");
#ifdef LODLINE_HAVE_VIEWER
  return {cmd, [o] { return runView(o->view, o->detail, o->play); }};
#else
  // The callback keeps the options alive: CLI11 writes into them while parsing.
  return {cmd, [o] {
            (void)o;
            return reportError(Error::runtime("this build has no viewer (built with LODLINE_BUILD_VIEWER=OFF)"));
          }};
#endif
}

}  // namespace lodline
