#version 410 core
// Evaluates the patch at the tessellation coordinate: position, normal, K, H (patch_eval.glsl), in
// the patch's own frame, then places it relative to the eye (patch_frame.glsl).
// PROBE: point mode, outputs captured by transform feedback (GPU-vs-CPU tests, readback).
#include "common/patch_eval.glsl"
#include "common/patch_frame.glsl"
#include "common/surface_varyings.glsl"

#ifdef PROBE
layout(quads, equal_spacing, ccw, point_mode) in;
out vec4 probe_uvKH;            // (u, v, K, H)
out vec4 probe_positionPatch;   // (position relative to the eye, as drawn; patch index)
#else
layout(quads, equal_spacing, ccw) in;
out SurfaceData { SURFACE_DATA_MEMBERS } te_out;
#endif

in vec3 tc_controlPoint[];
in vec3 tc_fromEye[];
patch in ivec2 tc_kindRing;
patch in int tc_patchIndex;
patch in vec3 tc_originFromEye;
patch in mat3 tc_axes;

void main() {
  vec3 cp[16];
  for (int k = 0; k < 16; ++k) cp[k] = tc_controlPoint[k];
  float u = gl_TessCoord.x, v = gl_TessCoord.y;
  // Derivatives, K and H are the same in any frame (rotation and translation): evaluate locally.
  int kind = tc_kindRing.x;
  SurfacePoint s = evaluatePatch(cp, kind, u, v);
  // The position: a cap's from its frame; a B-spline patch's from the points shared with its
  // neighbours (watertight edges, see positionFromEye).
  vec3 fromEye;
  if (kind == kPatchPoleCap) {
    vec3 shared[16];
    for (int k = 0; k < 16; ++k) shared[k] = tc_fromEye[k];
    fromEye = capPositionFromEye(shared, u, v);
  } else {
    vec3 points[16];
    for (int k = 0; k < 16; ++k) points[k] = tc_fromEye[k];
    fromEye = positionFromEye(points, u, v);
  }
#ifdef PROBE
  probe_uvKH = vec4(u, v, s.gaussian, s.mean);
  probe_positionPatch = vec4(fromEye, float(tc_patchIndex));
#else
  te_out.position = fromEye;
  te_out.normal = tc_axes * s.normal;
  te_out.curvature = vec2(s.gaussian, s.mean);
  te_out.uv = vec2(u, v);
  te_out.kindRing = tc_kindRing;
#endif
  gl_Position = u_viewRotationProjection * vec4(fromEye, 1.0);
}
