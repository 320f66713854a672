// The viewer's control panel (Dear ImGui, Debian's libimgui-dev): the parameters of
// detail control (T, t_c/t_s, geomorphs, detail map, per-object factors), temporal
// smoothing, line kinds and thresholds, style and chamfer highlights, live frame statistics,
// and "save view". It only issues ImGui calls and edits a ViewerSession; the platform and
// renderer backends (GLFW + OpenGL 3 in the window, OpenGL 3 alone in headless tests) are
// set up by the caller.
#pragma once

#include <array>
#include <string>

#include <imgui.h>

#include "app/viewer_session.h"

namespace lodline {

struct PanelState {
  bool visible = true;                        ///< H toggles the panel
  std::array<char, 1024> detail_map{};        ///< detail-map path being edited
  float detail_map_scale = 8.0f;
  std::array<char, 1024> save_path{};         ///< where "save view" writes
  std::string message;                        ///< last result or error, shown in the panel
  int stroke_kind = -1;                       ///< line kind the stroke fields edit (-1: all)
  float fps = 0.0f;                           ///< measured by the caller
  /// Screen rectangle of the T slider as last drawn (min x, min y, max x, max y), so tests
  /// and scripted demos can drag it with real mouse input.
  std::array<float, 4> target_area_slider{};
  /// The panel's right edge in framebuffer pixels as last drawn (the viewer frames the scene
  /// to its right); before the first draw, where the panel first appears.
  float right_px = 436.0f;
};

/// Fills the text fields from the session (call once after creating it).
void initPanel(const ViewerSession& session, PanelState& state);

/// Draws the panel; call between ImGui::NewFrame() and ImGui::Render(). Edits go straight to
/// `session`; `width`×`height` is the framebuffer (the size a saved view renders at).
void drawPanel(ViewerSession& session, PanelState& state, int width, int height);

}  // namespace lodline
