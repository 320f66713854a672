// From stroke runs to what the renderers draw (core/line_buffer.h): segments in pixels,
// the visible runs grouped by kind, the hidden runs cut into the hidden style's dashes.
#pragma once

#include "core/line_buffer.h"
#include "core/render_params.h"
#include "export/visibility.h"

namespace lodline {

/// Fills `out` with the segments of `visible` (per kind) and, when `hidden_style` is
/// enabled, of `hidden` cut into dashes of hidden_style.dash_on pixels every
/// dash_on + dash_off pixels along each run (solid when dash_off is 0).
void buildScreenLines(const StrokeRuns& visible, const StrokeRuns& hidden, const HiddenLineStyle& hidden_style,
                      ScreenLines& out);

}  // namespace lodline
