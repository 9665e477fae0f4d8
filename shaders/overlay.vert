#version 410 core
// Control net lines and pole markers: positions relative to the model centre, per-vertex colour.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_color;
out vec3 v_color;
uniform mat4 u_modelViewProjection;
uniform float u_depthBias;  // pulls overlays towards the eye so they win against the surface
uniform float u_pointSize;
uniform vec4 u_colorOverride;  // a > 0: this colour instead of a_color (control net passes)

void main() {
  v_color = u_colorOverride.a > 0.0 ? u_colorOverride.rgb : a_color;
  gl_Position = u_modelViewProjection * vec4(a_position, 1.0);
  gl_Position.z -= u_depthBias * gl_Position.w;
  gl_PointSize = u_pointSize;
}
