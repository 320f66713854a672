#version 330 core
// Line segments in pixels (origin top-left, y down), already split into visible and hidden
// runs by the presenter: no depth test. Per-endpoint opacity (fading of weak lines).
layout(location = 0) in vec2 a_pixel;
layout(location = 1) in float a_alpha;

uniform vec2 u_viewport;  // width, height in pixels

out float v_alpha;

void main() {
  v_alpha = a_alpha;
  gl_Position = vec4(a_pixel.x / u_viewport.x * 2.0 - 1.0, 1.0 - a_pixel.y / u_viewport.y * 2.0, 0.0, 1.0);
}
