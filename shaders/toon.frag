#version 330 core
// Toon shading (Lake, Marshall, Harris, Blackstein 2000, "Stylized rendering techniques for
// scalable real-time 3D animation" §3): the diffuse term max(n·l, 0) indexes a 1D ramp of a
// few flat tones, so shading changes in hard steps instead of smoothly.
in vec3 v_normal_eye;
in vec3 v_position_eye;

uniform sampler2D u_ramp;     // 1D ramp stored as an N×1 texture, nearest filtering
uniform vec3 u_base_color;    // linear-free sRGB base colour of the surface
uniform vec3 u_light_eye;     // unit vector towards the light, eye space

out vec4 frag_color;

void main() {
  vec3 n = normalize(v_normal_eye);
  // Two-sided: a back face seen through a hole is shaded like its front.
  if (!gl_FrontFacing) n = -n;
  float ndotl = clamp(dot(n, u_light_eye), 0.0, 1.0);
  float tone = texture(u_ramp, vec2(ndotl, 0.5)).r;
  frag_color = vec4(u_base_color * tone, 1.0);
}
