#version 330 core
// Faces: position and smoothed normal per vertex, transformed to eye space.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_view;
uniform mat4 u_projection;

out vec3 v_normal_eye;
out vec3 v_position_eye;

void main() {
  vec4 p = u_view * vec4(a_position, 1.0);
  v_position_eye = p.xyz;
  v_normal_eye = mat3(u_view) * a_normal;
  gl_Position = u_projection * p;
}
