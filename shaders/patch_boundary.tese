#version 410 core
// Patch boundaries as isolines: line k = 0..3 of the isoline tessellation is the edge
// v = 0, u = 1, v = 1, u = 0 respectively, evaluated with the same patch_eval.glsl in the patch's
// frame and placed relative to the eye (patch_frame.glsl).
#include "common/patch_eval.glsl"
#include "common/patch_frame.glsl"

layout(isolines, equal_spacing) in;

in vec3 tc_controlPoint[];
patch in ivec2 tc_kindRing;
patch in vec3 tc_originFromEye;
patch in mat3 tc_axes;
patch in vec3 tc_capSecond[4];
flat out ivec2 be_kindRing;

void main() {
  vec3 cp[16];
  for (int k = 0; k < 16; ++k) cp[k] = tc_controlPoint[k];
  // Isolines give v = k / 4 for line k and t = gl_TessCoord.x along it.
  int edge = int(gl_TessCoord.y * 4.0 + 0.5);
  float t = gl_TessCoord.x;
  vec2 uv = edge == 0 ? vec2(t, 0.0) : edge == 1 ? vec2(1.0, t) : edge == 2 ? vec2(t, 1.0)
                                                                              : vec2(0.0, t);
  vec3 second[4] = tc_capSecond;
  SurfacePoint s = evaluatePatch(cp, second, tc_kindRing.x, uv.x, uv.y);
  be_kindRing = tc_kindRing;
  gl_Position = u_viewRotationProjection * vec4(tc_originFromEye + tc_axes * s.position, 1.0);
}
