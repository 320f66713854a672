// From stroke runs to what the renderers draw (core/line_buffer.h): the visible runs grouped
// by kind as stroke geometry of their kind's width, the hidden runs cut into the hidden
// style's dashes (docs/visibility.md, docs/strokes.md).
#pragma once

#include "core/line_buffer.h"
#include "core/render_params.h"
#include "export/visibility.h"
#include "present/stroke_geometry.h"

namespace lodline {

/// Fills `out` with the strokes of `visible` (per kind, in style.lines' widths, round caps
/// and joins) and, when style.hidden is enabled, of `hidden` cut into dashes of
/// hidden.dash_on pixels every dash_on + dash_off pixels along each run (solid when dash_off
/// is 0; butt caps). Kinds that are not enabled are left out.
void buildScreenLines(const StrokeRuns& visible, const StrokeRuns& hidden, const ObjectStyle& style,
                      ScreenLines& out, StrokeGeometryScratch& scratch);

}  // namespace lodline
