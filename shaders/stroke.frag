#version 330 core
// Coverage antialiasing of stroke geometry: the fraction of the pixel the stroke covers,
// a 1-px box across its edge and the cap's shape beyond its end, times the brush's ink where
// the style has a brush (tiled along the arc length, stretched across the width). The same
// formulas as strokeCoverage() and brushCoordinates() in src/core/line_buffer.h (the software
// renderer), docs/strokes.md.
in vec2 v_local;
in float v_half_width;
in float v_alpha;
in float v_u;
flat in float v_cap;
uniform vec4 u_color;
uniform sampler2D u_brush;     // one period of the brush, resampled to its size in pixels
uniform float u_brush_period;  // pixels of arc length per brush period; 0 = no brush
out vec4 frag_color;

float coverage() {
  float beyond = max(v_local.x, 0.0);
  if (v_cap < 0.5)
    return clamp(v_half_width + 0.5 - abs(v_local.y), 0.0, 1.0) * clamp(1.0 - v_local.x, 0.0, 1.0);
  float d = v_cap < 1.5 ? length(vec2(beyond, v_local.y)) : max(beyond, abs(v_local.y));
  return clamp(v_half_width + 0.5 - d, 0.0, 1.0);
}

void main() {
  float c = coverage();
  if (c <= 0.0) discard;
  if (u_brush_period > 0.0) {
    vec2 st = vec2(v_u / u_brush_period, clamp(0.5 - 0.5 * v_local.y / v_half_width, 0.0, 1.0));
    c *= texture(u_brush, st).r;
  }
  frag_color = vec4(u_color.rgb, u_color.a * v_alpha * c);
}
