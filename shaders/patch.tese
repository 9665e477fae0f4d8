#version 410 core
// Evaluates the patch at the tessellation coordinate: position, normal, K, H (patch_eval.glsl).
// PROBE: point mode, outputs captured by transform feedback (GPU-vs-CPU tests, readback).
#include "common/patch_eval.glsl"
#include "common/surface_varyings.glsl"

#ifdef PROBE
layout(quads, equal_spacing, ccw, point_mode) in;
out vec4 probe_uvKH;            // (u, v, K, H)
out vec4 probe_positionPatch;   // (position relative to the centre, patch index)
#else
layout(quads, equal_spacing, ccw) in;
out SurfaceData { SURFACE_DATA_MEMBERS } te_out;
#endif

in vec3 tc_controlPoint[];
flat in ivec2 tc_kindRing[];
patch in int tc_patchIndex;
uniform mat4 u_modelViewProjection;

void main() {
  vec3 cp[16];
  for (int k = 0; k < 16; ++k) cp[k] = tc_controlPoint[k];
  float u = gl_TessCoord.x, v = gl_TessCoord.y;
  SurfacePoint s = evaluatePatchLocally(cp, tc_kindRing[0].x, u, v);
#ifdef PROBE
  probe_uvKH = vec4(u, v, s.gaussian, s.mean);
  probe_positionPatch = vec4(s.position, float(tc_patchIndex));
#else
  te_out.position = s.position;
  te_out.normal = s.normal;
  te_out.curvature = vec2(s.gaussian, s.mean);
  te_out.uv = vec2(u, v);
  te_out.kindRing = tc_kindRing[0];
#endif
  gl_Position = u_modelViewProjection * vec4(s.position, 1.0);
}
