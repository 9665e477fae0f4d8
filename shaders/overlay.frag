#version 410 core
in vec3 v_color;
out vec4 o_color;
uniform bool u_roundPoints;  // pole markers: round, shaded discs
uniform float u_alpha;       // < 1: blended (the control net's hidden parts)

void main() {
  vec3 color = v_color;
  if (u_roundPoints) {
    vec2 d = gl_PointCoord * 2.0 - 1.0;
    float r2 = dot(d, d);
    if (r2 > 1.0) discard;
    color *= 0.55 + 0.45 * sqrt(1.0 - r2);  // a sphere-like shading
    if (r2 > 0.7) color = vec3(0.0);       // dark rim, visible on any background
  }
  o_color = vec4(color, u_alpha);
}
