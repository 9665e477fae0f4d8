#version 410 core
// Boundary curves coloured by patch kind or ring index (palettes uploaded as uniforms).
flat in ivec2 be_kindRing;
out vec4 o_color;
uniform bool u_colorByRing;
uniform vec3 u_kindColors[5];
uniform vec3 u_ringColors[8];
uniform vec3 u_noRingColor;

void main() {
  vec3 color;
  if (u_colorByRing) color = be_kindRing.y < 0 ? u_noRingColor : u_ringColors[be_kindRing.y % 8];
  else color = u_kindColors[clamp(be_kindRing.x, 0, 4)];
  o_color = vec4(color, 1.0);
}
