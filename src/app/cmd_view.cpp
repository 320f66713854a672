// `lodline view MODEL|SCENE`: the interactive viewer. Same parameters and same drawing code as
// `render` (ViewerSession), with a Dear ImGui panel for the parameters and live statistics.
//
// Mouse (outside the panel): left-drag orbits, right- or middle-drag pans, wheel zooms.
// Keys: arrows orbit, +/- (or PageUp/PageDown) zoom, T toggles toon/lines, 1-4 toggle
// contour/suggestive/crease/boundary lines, [ and ] halve/double the target triangle area
// (detail control), G toggles geomorphs, H hides/shows the panel, C starts/stops recording the
// camera to a path file (lodline-path.json, replayable with --play or `capture --path`), R
// resets the view, P saves lodline-view.png, S saves the view as lodline-view.json, Esc or Q
// quits. --play FILE.json plays a camera path (looping).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include <glad/gl.h>

#include "app/commands.h"
#include "app/model.h"
#include "app/options.h"
#include "core/timer.h"
#include "frame/camera_path.h"
#include "io/atomic_file.h"
#include "io/image.h"

#ifdef LODLINE_HAVE_VIEWER
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "app/viewer_panel.h"
#include "app/viewer_session.h"
#include "gl/glfw_window.h"
#endif

namespace lodline {
namespace {

// Bound to the command's options: a scene's settings are written into these while loading.
struct ViewCommandOptions {
  ViewOptions view;
  DetailOptions detail;
  std::string play;
  int exit_after = 0;     ///< frames; 0: run until closed
  std::string snapshot;   ///< window image (panel included) written at exit
};

}  // namespace

#ifdef LODLINE_HAVE_VIEWER
namespace {

struct WindowState {
  ViewerSession* session = nullptr;
  PanelState panel;
  bool dragging_orbit = false, dragging_pan = false;
  // A press waits for the next ImGui frame, which knows whether the cursor is over the panel
  // (a press in the same event batch as a jump onto the panel would otherwise orbit too).
  bool pending_orbit = false, pending_pan = false;
  double last_x = 0.0, last_y = 0.0;
  bool screenshot = false, save_view = false;
  // Camera-path recording (key C).
  bool recording = false;
  bool toggle_recording = false;
  std::vector<CameraKey> recorded;
  Stopwatch record_clock;
};

WindowState& stateOf(GLFWwindow* w) { return *static_cast<WindowState*>(glfwGetWindowUserPointer(w)); }

void onKey(GLFWwindow* w, int key, int, int action, int) {
  if (action == GLFW_RELEASE || ImGui::GetIO().WantCaptureKeyboard) return;
  WindowState& s = stateOf(w);
  ViewerSession& v = *s.session;
  switch (key) {
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q: glfwSetWindowShouldClose(w, GLFW_TRUE); break;
    case GLFW_KEY_LEFT: v.orbit(-5.0f, 0.0f); break;
    case GLFW_KEY_RIGHT: v.orbit(5.0f, 0.0f); break;
    case GLFW_KEY_UP: v.orbit(0.0f, 5.0f); break;
    case GLFW_KEY_DOWN: v.orbit(0.0f, -5.0f); break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
    case GLFW_KEY_PAGE_UP: v.zoom(1.0f / 1.15f); break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
    case GLFW_KEY_PAGE_DOWN: v.zoom(1.15f); break;
    case GLFW_KEY_T: v.setStyleAll(v.defaultStyle().style == Style::kToon ? Style::kLines : Style::kToon); break;
    case GLFW_KEY_1:
    case GLFW_KEY_2:
    case GLFW_KEY_3:
    case GLFW_KEY_4: {
      const int k = key - GLFW_KEY_1;
      const bool on = !v.defaultStyle().lines.kinds[k].enabled;
      v.defaultStyle().lines.kinds[k].enabled = on;
      for (auto& o : v.scene().objects()) o.style.lines.kinds[k].enabled = on;
      for (auto& o : v.description().objects) o.style.erase("lines");
      v.touch();
      break;
    }
    case GLFW_KEY_LEFT_BRACKET: v.detail().target_area = std::max(0.25f, v.detail().target_area * 0.5f); break;
    case GLFW_KEY_RIGHT_BRACKET: v.detail().target_area = std::min(4096.0f, v.detail().target_area * 2.0f); break;
    case GLFW_KEY_G: v.detail().geomorphs = !v.detail().geomorphs; break;
    case GLFW_KEY_H: s.panel.visible = !s.panel.visible; break;
    case GLFW_KEY_R: v.resetView(); break;
    case GLFW_KEY_P: s.screenshot = true; break;
    case GLFW_KEY_S: s.save_view = true; break;
    case GLFW_KEY_C: s.toggle_recording = true; break;
    default: break;
  }
}

void onMouseButton(GLFWwindow* w, int button, int action, int) {
  WindowState& s = stateOf(w);
  const bool down = action == GLFW_PRESS;
  glfwGetCursorPos(w, &s.last_x, &s.last_y);
  const bool left = button == GLFW_MOUSE_BUTTON_LEFT;
  if (down) {
    (left ? s.pending_orbit : s.pending_pan) = true;
  } else {
    (left ? s.dragging_orbit : s.dragging_pan) = false;
    (left ? s.pending_orbit : s.pending_pan) = false;
  }
}

// After ImGui::NewFrame(): presses not on the panel start dragging the camera.
void takePendingPresses(WindowState& s) {
  const bool panel = ImGui::GetIO().WantCaptureMouse;
  if (s.pending_orbit && !panel) s.dragging_orbit = true;
  if (s.pending_pan && !panel) s.dragging_pan = true;
  s.pending_orbit = s.pending_pan = false;
}

void onCursor(GLFWwindow* w, double x, double y) {
  WindowState& s = stateOf(w);
  const double dx = x - s.last_x, dy = y - s.last_y;
  s.last_x = x;
  s.last_y = y;
  if (s.dragging_orbit) {
    s.session->orbit(-static_cast<float>(dx) * 0.4f, static_cast<float>(dy) * 0.4f);
  } else if (s.dragging_pan) {
    int width = 1, height = 1;
    glfwGetWindowSize(w, &width, &height);
    s.session->pan(static_cast<float>(dx), static_cast<float>(dy), width, height);
  }
}

void onScroll(GLFWwindow* w, double, double dy) {
  if (ImGui::GetIO().WantCaptureMouse) return;
  stateOf(w).session->zoom(static_cast<float>(std::pow(1.1, -dy)));
}

// Starts or stops recording; on stop, writes the keys as lodline-path.json.
void toggleRecording(WindowState& s) {
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
    std::cerr << "lodline: wrote lodline-path.json (" << s.recorded.size() << " keys, " << s.recorded.back().time
              << " s)\n";
}

Image readFramebuffer(int width, int height) {
  Image img(width, height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
  Image flipped(width, height);
  for (int y = 0; y < height; ++y)
    std::copy_n(img.pixel(0, height - 1 - y), static_cast<size_t>(width) * 4, flipped.pixel(0, y));
  return flipped;
}

int runView(CLI::App& cmd, ViewCommandOptions& o) {
  auto loaded = loadInput(cmd, o.view, o.detail);
  if (!loaded) return reportError(loaded.error());
  if (o.exit_after < 0) return reportError(Error::usage("--exit-after: must be >= 0 frames"));
  if (!o.snapshot.empty() && o.exit_after == 0) return reportError(Error::usage("--snapshot needs --exit-after N"));
  if (!o.snapshot.empty())
    if (Status st = checkWritable(o.snapshot); !st) return reportError(st.error());
  std::optional<CameraPath> play;
  if (!o.play.empty()) {
    auto path = loadCameraPath(o.play);
    if (!path) return reportError(path.error());
    play = std::move(path.value());
  }
  const FrameParams frame = (*loaded)->view.frame;
  const std::string title = "lodline - " + (*loaded)->view.model.filename().string();
  // Single-sampled: frames are drawn (multisampled) offscreen by the presenter and copied in.
  auto window = GlfwWindow::create(frame.width, frame.height, title, 1);
  if (!window) return reportError(window.error());
  GLFWwindow* w = window->handle();
  WindowState s;
  glfwSetWindowUserPointer(w, &s);
  // Ours first: ImGui's backend chains to them.
  glfwSetKeyCallback(w, onKey);
  glfwSetMouseButtonCallback(w, onMouseButton);
  glfwSetCursorPosCallback(w, onCursor);
  glfwSetScrollCallback(w, onScroll);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  ImGui::StyleColorsLight();
  ImGui_ImplGlfw_InitForOpenGL(w, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  int status = 0;
  {
    auto session = ViewerSession::create(std::move(loaded.value()), o.view);
    if (!session) {
      status = reportError(session.error());
    } else {
      ViewerSession& v = **session;
      s.session = &v;
      if (play) v.play(std::move(play));
      initPanel(v, s.panel);
      Stopwatch fps_clock, frame_clock;
      int frames = 0, total_frames = 0;
      while (!glfwWindowShouldClose(w)) {
        glfwPollEvents();
        int fb_w = 1, fb_h = 1;
        glfwGetFramebufferSize(w, &fb_w, &fb_h);
        if (fb_w <= 0 || fb_h <= 0) {
          glfwWaitEvents();
          continue;
        }
        const float dt = std::min(0.1f, static_cast<float>(frame_clock.lap() / 1000.0));
        if (v.playing()) v.advancePlayback(dt);
        if (s.toggle_recording) toggleRecording(s);
        if (s.recording) {
          const Camera cam = v.camera(fb_w, fb_h);
          const double t = s.record_clock.elapsed() / 1000.0;
          // Keys every 0.1 s (times must increase strictly).
          if (s.recorded.empty() || t - s.recorded.back().time >= 0.1)
            s.recorded.push_back({t, cam.eye, cam.target, cam.up, cam.fov_deg});
        }
        // Frame the scene in the part of the window the panel leaves free.
        v.setInset(s.panel.visible ? static_cast<int>(s.panel.right_px) : 0);
        if (Status st = v.frame(fb_w, fb_h, dt); !st) {
          status = reportError(st.error());
          break;
        }
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        v.draw();
        if (s.screenshot) {  // the drawing, without the panel
          if (Status st = writePng("lodline-view.png", readFramebuffer(fb_w, fb_h)); !st) reportError(st.error());
          else std::cerr << "lodline: saved lodline-view.png\n";
          s.screenshot = false;
        }
        if (s.save_view) {
          if (Status st = v.saveView("lodline-view.json", fb_w, fb_h); !st) reportError(st.error());
          else std::cerr << "lodline: saved lodline-view.json (lodline render lodline-view.json -o view.png)\n";
          s.save_view = false;
        }
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        takePendingPresses(s);
        drawPanel(v, s.panel, fb_w, fb_h);
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        ++total_frames;
        const bool last = o.exit_after > 0 && total_frames >= o.exit_after;
        if (last && !o.snapshot.empty()) {
          if (Status st = writePng(o.snapshot, readFramebuffer(fb_w, fb_h)); !st) status = reportError(st.error());
        }
        glfwSwapBuffers(w);
        ++frames;
        if (fps_clock.elapsed() > 500.0) {
          s.panel.fps = static_cast<float>(frames * 1000.0 / fps_clock.lap());
          frames = 0;
          char buf[256];
          const ObjectReport& r = v.report().total;
          std::snprintf(buf, sizeof(buf), "%s - %.1f fps - %llu faces (T %.3g px^2) - %llu line segments", title.c_str(),
                        static_cast<double>(s.panel.fps), static_cast<unsigned long long>(r.faces_drawn),
                        v.detail().target_area, static_cast<unsigned long long>(r.line_segments));
          glfwSetWindowTitle(w, buf);
        }
        if (last) break;
      }
    }
  }  // GL objects die here, before ImGui's and the window's context
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  return status;
}

}  // namespace
#endif

Command addViewCommand(CLI::App& parent) {
  auto o = std::make_shared<ViewCommandOptions>();
  CLI::App* cmd = parent.add_subcommand(
      "view",
      "Open a model or scene in an interactive window with a control panel.\n"
      "  Mouse: left-drag orbit, right/middle-drag pan, wheel zoom.\n"
      "  Keys: arrows orbit, +/- zoom, T toon/lines, 1-4 toggle contour/suggestive/crease/boundary,\n"
      "        [ ] halve/double the target triangle area, G geomorphs on/off, H hide/show the panel,\n"
      "        C start/stop recording the camera to lodline-path.json, R reset view,\n"
      "        P save lodline-view.png, S save the view as lodline-view.json, Esc/Q quit.");
  addViewOptions(*cmd, o->view);
  addDetailOptions(*cmd, o->detail);
  cmd->add_option("--play", o->play, "Play a camera path file (.json, e.g. one recorded with C), looping");
  cmd->add_option("--exit-after", o->exit_after, "Close after this many frames (0: stay open)")->capture_default_str();
  cmd->add_option("--snapshot", o->snapshot, "With --exit-after: write the last frame, panel included, to this PNG");
#ifdef LODLINE_HAVE_VIEWER
  return {cmd, [o, cmd] { return runView(*cmd, *o); }};
#else
  // The callback keeps the options alive: CLI11 writes into them while parsing.
  return {cmd, [o] {
            (void)o;
            return reportError(Error::runtime("this build has no viewer (built with LODLINE_BUILD_VIEWER=OFF)"));
          }};
#endif
}

}  // namespace lodline
