#version 410 core
// Patch boundaries: 4 isolines (one per edge) with a fixed number of segments.
#include "common/patch_frame.glsl"

layout(vertices = 16) out;

in vec3 vc_controlPoint[];
flat in int vc_patchIndex[];
out vec3 tc_controlPoint[];
patch out ivec2 tc_kindRing;  // (kind, ring index)
patch out vec3 tc_originFromEye;  // the patch's frame (patch_frame.glsl)
patch out mat3 tc_axes;
patch out vec3 tc_capSecond[4];  // a cap's f_j in its GPU form (patch_frame.glsl, fetchCapSecond)
uniform float u_boundarySegments;

void main() {
  tc_controlPoint[gl_InvocationID] = vc_controlPoint[gl_InvocationID];
  if (gl_InvocationID == 0) {
    // x packs the kind with the level and edge jumps (patch.tesc): keep the kind only.
    ivec2 kindRing = patchKindRing(vc_patchIndex[0]);
    tc_kindRing = ivec2(kindRing.x & 0xFF, kindRing.y);
    PatchFrame frame = patchFrame(vc_patchIndex[0]);
    tc_originFromEye = frame.originFromEye;
    tc_axes = frame.axes;
    vec3 secondLocal[4], secondWorld[4];
    if (tc_kindRing.x == 3) fetchCapSecond(vc_patchIndex[0], secondLocal, secondWorld);  // kPatchPoleCap
    for (int k = 0; k < 4; ++k) tc_capSecond[k] = secondLocal[k];
    gl_TessLevelOuter[0] = 4.0;  // number of isolines
    gl_TessLevelOuter[1] = u_boundarySegments;
  }
}
