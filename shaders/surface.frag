#version 330 core
// The surface pass of the coherence measure (export/coherence.h): each pixel gets the world
// position of the nearest surface and the object's id + 1 (0 stays background). Meshes are
// uploaded in world space, so the eye-space position maps back with the inverse view.
in vec3 v_position_eye;

uniform mat4 u_view_inverse;
uniform float u_object;  // object id + 1

out vec4 frag_surface;

void main() { frag_surface = vec4((u_view_inverse * vec4(v_position_eye, 1.0)).xyz, u_object); }
