// Command-line options shared by `render`, `view` and `capture` (and the "settings" of scene
// files): they fill the same parameter structs the viewer edits, so a headless render
// reproduces the viewer.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/camera.h"
#include "core/render_params.h"
#include "core/result.h"
#include "frame/scene_builder.h"
#include "lines/lines.h"
#include "present/capture.h"

namespace lodline {

/// Raw option strings, parsed and checked by resolve().
struct ViewOptions {
  std::vector<std::string> models;
  std::string size = "1280x720";
  std::string view;  ///< "AZ,EL,DIST"; empty = default 3/4 view framing the model
  float fov_deg = 35.0f;
  std::string style = "toon";
  float line_width = 0.0f;  ///< contour width in px; 0 = default (others scale with it)
  std::string background = "white";
  int msaa = 4;
  std::string lines = "contour,suggestive,crease,boundary,intersection";
  std::string hidden_lines = "off";  ///< off or COLOUR[:WIDTH][:dash=ON,OFF]
  std::string outline = "complete";  ///< complete (mesh silhouette fills contour gaps) or contour
  std::string contour_creases = "on";  ///< on: the contour runs along silhouette creases; off
  std::string suggestive_at_creases = "off";  ///< off: no suggestive lines in faces at creases
  std::string ridge_estimator = "tensor";      ///< tensor or fit (LineParams::ridge_estimator)
  std::vector<std::string> line_styles;  ///< "KIND=COLOUR[:WIDTH]", repeatable
  std::string stroke_style = "plain";    ///< a preset (plain, ink, pencil, marker) or a .json file
  // Chamfer edge highlights (ChamferParams; Wei, Shi, Yong 2014).
  std::string chamfer = "auto";   ///< auto (with the shaded style), on (also over toon), off
  float chamfer_radius = 0.0f;    ///< r_e, model units; 0 = auto
  float chamfer_k = 0.0f;         ///< K, pixels; 0 = auto (focal length in px)
  float chamfer_angle = 30.0f;    ///< sharp-edge threshold, degrees
  float chamfer_shininess = 32.0f;  ///< Blinn–Phong exponent n
  std::string chamfer_compose = "replace";  ///< replace or alpha (the paper's blend)
  // Line thresholds (LineParams).
  float suggestive_threshold = LineParams{}.suggestive_threshold;
  float suggestive_fade = LineParams{}.suggestive_fade;
  /// "off" or "START,END": fading of fast-sliding suggestive contours, px/s
  /// (LineParams::suggestive_motion_fade_*).
  std::string suggestive_motion_fade = "off";
  float crease_angle = LineParams{}.crease_angle_deg;
  // The level-set kinds (docs/lines.md).
  float isophote_spacing = LineParams{}.isophote_spacing;
  float topo_spacing = LineParams{}.topo_spacing;
  std::string topo_axis = "0,1,0";
  float parabolic_threshold = LineParams{}.parabolic_threshold;
  float ridge_threshold = LineParams{}.ridge_threshold;
  float apparent_ridge_threshold = LineParams{}.apparent_ridge_threshold;
  float principal_highlight_threshold = LineParams{}.principal_highlight_threshold;
};

/// The options of a capture beyond the view and detail ones (`capture` and the Python
/// module's capture iterator).
struct CapturePathOptions {
  std::string path = "orbit";  ///< a built-in path, or a path file (.json)
  double duration = 8.0;       ///< a built-in path's length, s
  std::string frames;          ///< "N" or "A:B"; empty: every frame
  double fps = 30.0;
  std::string stroke_coherence = "on";
  float fade_in = 0.0f;        ///< s; 0: off
};

void addCaptureOptions(CLI::App& cmd, CapturePathOptions& o);

/// Checks `o` and fills request's path (`path`, already resolved with scenePath()), fps,
/// range, stroke coherence and fade-in. Usage errors name the option.
Status resolveCaptureOptions(const CapturePathOptions& o, CameraPath path, CaptureRequest& request);

/// Parses --frames: "N" (frames 0..N-1) or "A:B" (A..B-1); empty: all `total` frames.
Result<FrameRange> parseFrameRange(const std::string& text, int64_t total);

/// Adds the shared options to a subcommand.
void addViewOptions(CLI::App& cmd, ViewOptions& o);

/// Parses and checks the option strings into the frame's parameters and the default style
/// (frame/scene_builder.h); errors are usage errors (exit code 2).
Result<ResolvedView> resolveViewOptions(const ViewOptions& o);

/// Parses "AZ,EL,DIST" (degrees, degrees, bounding-sphere radii > 0).
Result<OrbitView> parseOrbitView(const std::string& s);

/// The style of one scene object: `base` with the object's style keys (render option names:
/// style, lines, line-style, line-width, stroke-style, hidden-lines, chamfer, chamfer-radius) applied, resolved as the
/// command-line options are. Errors name `where` and the key.
Result<ObjectStyle> resolveObjectStyle(const ViewOptions& base, const nlohmann::json& style,
                                       const std::string& where);

/// The render options (long names) that reproduce `frame`, `style`, `detail` and `lines` —
/// the "settings" of a saved view, the inverse of the options above. Paths (the detail map)
/// are written relative to `base_dir`.
nlohmann::json settingsOf(const FrameParams& frame, const ObjectStyle& style, const ResolvedDetail& detail,
                          const LineParams& lines, const std::filesystem::path& base_dir);

}  // namespace lodline
