#version 330 core
// Faces of the shaded style: per-pixel Blinn–Phong, the model the chamfer highlights
// (chamfer.frag; Wei, Shi, Yong 2014) integrate over each rounded edge, so the highlights
// continue the faces' shading. Normals are crease-aware corner normals (smooth within the
// sharp-edge angle, flat across sharp edges).
in vec3 v_normal_eye;
in vec3 v_position_eye;

uniform vec3 u_light_eye;     // unit vector towards the light, eye space
uniform vec3 u_ambient;
uniform vec3 u_diffuse;
uniform vec3 u_specular;
uniform float u_shininess;
uniform bool u_orthographic;  // view direction +Z

out vec4 frag_color;

void main() {
  vec3 n = normalize(v_normal_eye);
  // Two-sided: a back face seen through a hole is shaded like its front.
  if (!gl_FrontFacing) n = -n;
  vec3 view = u_orthographic ? vec3(0.0, 0.0, 1.0) : normalize(-v_position_eye);
  vec3 h = normalize(u_light_eye + view);
  float nl = max(dot(n, u_light_eye), 0.0);
  float nh = max(dot(n, h), 0.0);
  vec3 color = u_ambient + u_diffuse * nl + u_specular * pow(nh, u_shininess);
  frag_color = vec4(clamp(color, 0.0, 1.0), 1.0);
}
