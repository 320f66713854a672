// How a line kind's strokes are drawn beyond its colour and width (docs/strokes.md, "Stroke
// styles"): caps, a width profile along the stroke (tapering), thickness and opacity by depth,
// by line strength and by the stroke's bend, dashes, jitter, a minimum length and a brush
// texture tiled along the stroke. Presets (plain, ink, pencil, marker) and style files are
// read by io/stroke_style_file.h; the presenter applies them (present/screen_lines.h).
// Every default is the `plain` preset, today's look: constant width, round caps, line strength
// as opacity.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/image.h"
#include "core/line_buffer.h"

namespace lodline {

struct StrokeStyle {
  /// How both ends are drawn. Default round.
  StrokeCap cap = StrokeCap::kRound;
  /// Width ramps from `taper_min` of the width up to the full width over this arc length
  /// (px) from the start / towards the end (a smoothstep). Default 0: no taper.
  float taper_in_px = 0.0f;
  float taper_out_px = 0.0f;
  /// Fraction of the width at the very ends of a tapered stroke, in [0, 1]. Default 0.1.
  float taper_min = 0.1f;
  /// Width × (1 + depth_thickness · (1 − 2·d)), d ∈ [0, 1] the point's depth across the
  /// object's bounding sphere (0 nearest): positive makes near strokes thicker and far ones
  /// thinner. In [−1, 1]. Default 0.
  float depth_thickness = 0.0f;
  /// Width × (1 − strength_thickness · (1 − a)), a the line's strength (the suggestive
  /// contours' fade; 1 for other kinds). In [0, 1]. Default 0.
  float strength_thickness = 0.0f;
  /// Width × (1 + curvature_thickness · b), b ∈ [0, 1] the stroke's bend there (turning per
  /// pixel × 8 px, clamped): ink pools in tight turns. In [−1, 4]. Default 0.
  float curvature_thickness = 0.0f;
  /// Opacity × (1 − depth_opacity · d): far strokes fade. In [0, 1]. Default 0.
  float depth_opacity = 0.0f;
  /// Opacity × (1 − strength_opacity · (1 − a)). In [0, 1]. Default 1: weak lines fade (the
  /// suggestive contours' fade, as before styles).
  float strength_opacity = 1.0f;
  /// Opacity × (1 − curvature_opacity · b). In [0, 1]. Default 0.
  float curvature_opacity = 0.0f;
  /// Dash pattern along the stroke, px: `dash_on` drawn, `dash_off` skipped. Default 0, 0:
  /// solid.
  float dash_on = 0.0f;
  float dash_off = 0.0f;
  /// Sideways wobble of the centre line, px (value noise along the arc length with period
  /// `jitter_period_px`, seeded by `seed`). Default 0: none.
  float jitter_px = 0.0f;
  float jitter_period_px = 24.0f;
  uint32_t seed = 1;
  /// Visible runs shorter than this (px) are not drawn. Default 0: all.
  float min_length_px = 0.0f;
  /// Standard deviation (px of arc length) of the Gaussian that smooths each visible and
  /// hidden run in the image before it is drawn, measured and written (corners over 50° and
  /// the ends stay): on a coarse mesh the zero crossings zig-zag from face to face by a pixel
  /// or so, and the zig-zag shifts as the mesh adapts (docs/strokes.md, "Smoothing").
  /// In [0, 16]. Default 3; 0: the runs as found.
  float smoothing_px = 3.0f;
  /// A greyscale brush (its red channel: 255 = full ink, 0 = none) tiled along the stroke
  /// every `brush_period_px` px of arc length and stretched across its width. Default none.
  std::shared_ptr<const Image> brush;
  std::string brush_path;  ///< where `brush` was read from (written back to saved views)
  float brush_period_px = 64.0f;
};

}  // namespace lodline
