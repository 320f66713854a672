// Fuzz target: stroke style files (`--stroke-style FILE.json`, docs/strokes.md) through
// loadStrokeStyle and, when accepted, applied to the default line styles as the commands do.
// A small brush "b.png" lies next to the input, so files that name it get past the reader.
#include <cmath>

#include "harness.h"
#include "io/image.h"
#include "io/stroke_style_file.h"

LODLINE_FUZZ_TARGET(stroke_style) {
  using namespace lodline;
  const fuzz::InputFile input(".json", "", data, size);
  const auto brush = input.path().parent_path() / "b.png";
  if (!std::filesystem::exists(brush)) {
    Image b(6, 3);
    for (size_t i = 0; i < b.rgba.size(); ++i) b.rgba[i] = static_cast<uint8_t>(37 * i);
    (void)writePng(brush, b);
  }
  Result<NamedStrokeStyle> style = loadStrokeStyle(input.path().string());
  if (!style) {
    fuzz::expectCleanError(style.error(), input.path());
    return;
  }
  LineStyles lines;
  applyStrokeStyle(*style, lines);
  for (const LineStyle& l : lines.kinds) {
    const StrokeStyle& s = l.stroke;
    for (float v : {l.width_px, s.taper_in_px, s.taper_out_px, s.taper_min, s.depth_thickness, s.strength_thickness,
                    s.curvature_thickness, s.depth_opacity, s.strength_opacity, s.curvature_opacity, s.dash_on,
                    s.dash_off, s.jitter_px, s.jitter_period_px, s.min_length_px, s.smoothing_px, s.brush_period_px})
      if (!std::isfinite(v)) fuzz::fail("an accepted stroke style has a non-finite field");
    if (!(l.width_px > 0.0f)) fuzz::fail("an accepted stroke style has a width <= 0");
    if (s.brush && (s.brush->width < 4 || s.brush->height != 8 ||
                    s.brush->rgba.size() != static_cast<size_t>(s.brush->width) * 8 * 4))
      fuzz::fail("an accepted brush was not resampled to its period");
  }
}
