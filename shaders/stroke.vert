#version 330 core
// Stroke geometry in pixels (origin top-left, y down; present/stroke_geometry.h): triangles
// extruded from the visible and hidden runs the presenter split, so no depth test. Each
// vertex carries its offset from the stroke's centre line for the coverage in stroke.frag.
layout(location = 0) in vec4 a_pixel_local;  // xy: pixels; zw: offset beyond the end, across
layout(location = 1) in vec4 a_stroke;       // half width (px), opacity, cap (0 butt, 1 round, 2 square), arc length (px)

uniform vec2 u_viewport;  // width, height in pixels

out vec2 v_local;
out float v_half_width;
out float v_alpha;
out float v_u;
flat out float v_cap;

void main() {
  v_local = a_pixel_local.zw;
  v_half_width = a_stroke.x;
  v_alpha = a_stroke.y;
  v_cap = a_stroke.z;
  v_u = a_stroke.w;
  vec2 p = a_pixel_local.xy;
  gl_Position = vec4(p.x / u_viewport.x * 2.0 - 1.0, 1.0 - p.y / u_viewport.y * 2.0, 0.0, 1.0);
}
