#version 410 core
// Control net lines and pole markers, per-vertex colour. Positions are doubles split hi + lo
// relative to the model centre and drawn relative to the eye (common/patch_frame.glsl), so a pole
// marker stays on the pole in close-ups.
#include "common/patch_frame.glsl"

layout(location = 0) in vec3 a_positionHi;
layout(location = 1) in vec3 a_color;
layout(location = 2) in vec3 a_positionLo;
out vec3 v_color;
uniform float u_depthBias;  // pulls overlays towards the eye so they win against the surface
uniform float u_pointSize;
uniform vec4 u_colorOverride;  // a > 0: this colour instead of a grey a_color (control net passes)

void main() {
  // Crease edges keep their colour (pipeline/control_net.h: orange to red); the smooth net's grey
  // takes the pass's colour (dark over the surface, light over the background).
  bool grey = abs(a_color.r - a_color.g) < 0.01 && abs(a_color.g - a_color.b) < 0.01;
  v_color = u_colorOverride.a > 0.0 && grey ? u_colorOverride.rgb : a_color;
  gl_Position = u_viewRotationProjection * vec4(relativeToEye(a_positionHi, a_positionLo), 1.0);
  gl_Position.z -= u_depthBias * gl_Position.w;
  gl_PointSize = u_pointSize;
}
