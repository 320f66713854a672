#version 330 core
// Faces drawn for hidden-line removal only (the `lines` style): the colour is the
// background, so only the depth buffer matters.
uniform vec4 u_color;
out vec4 frag_color;
void main() { frag_color = u_color; }
