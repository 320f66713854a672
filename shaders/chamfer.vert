#version 330 core
// Chamfer edge highlights (Wei, Shi, Yong, "Rendering chamfering structures of sharp
// edges", Visual Computer 2014; docs/design.md §2.2): every sharp edge is a GL_LINES segment whose
// vertices carry both adjacent face normals N1, N2 and the edge radius r_e (0 = use the
// constant u_radius). The fragment shader (chamfer.frag) integrates Blinn–Phong over the arc.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal1;
layout(location = 2) in vec3 a_normal2;
layout(location = 3) in float a_radius;
layout(location = 4) in vec3 a_inward1;  // from the edge into face 1, in its plane
layout(location = 5) in vec3 a_inward2;

uniform mat4 u_view;
uniform mat4 u_projection;

out vec3 v_position_eye;
flat out vec3 v_normal1_eye;
flat out vec3 v_normal2_eye;
out float v_radius;
flat out vec3 v_inward1_eye;
flat out vec3 v_inward2_eye;

void main() {
  vec4 p = u_view * vec4(a_position, 1.0);
  v_position_eye = p.xyz;
  // The view matrix is rigid, so its 3×3 part maps normals.
  v_normal1_eye = mat3(u_view) * a_normal1;
  v_normal2_eye = mat3(u_view) * a_normal2;
  v_radius = a_radius;
  v_inward1_eye = mat3(u_view) * a_inward1;
  v_inward2_eye = mat3(u_view) * a_inward2;
  gl_Position = u_projection * p;
}
