#version 410 core
// Pass-through of the 16 control points of a patch (GL_PATCHES, 16 vertices per patch), in the
// patch's own frame for evaluation and relative to the eye for the tessellation levels
// (common/patch_frame.glsl).
#include "common/patch_frame.glsl"

layout(location = 0) in vec3 a_localPoint;  // the patch's GPU form (patch_eval.glsl), in its frame
// The control point in world coordinates relative to the model centre, as a double split hi + lo.
// A point shared by neighbouring patches has the same hi, lo in each, so its position relative to
// the eye, and with it the level of a shared edge, is the same bits on both sides. (Zero for the
// vector and parameter slots of a cap.)
layout(location = 2) in vec3 a_pointHi;
layout(location = 3) in vec3 a_pointLo;

out vec3 vc_controlPoint;
out vec3 vc_fromEye;
// The patch's index in the buffer: gl_VertexID counts from the buffer start in every run of a
// multi-draw, where gl_PrimitiveID restarts (patch_renderer.cpp draws runs of patches).
flat out int vc_patchIndex;

const int kPoleCapKind = 3;  // patch_eval.glsl's kPatchPoleCap

void main() {
  vc_controlPoint = a_localPoint;
  vc_patchIndex = gl_VertexID / 16;
  // A cap's vector and parameter slots (all but p0 and b_j: 0, 6..9) hold world vectors and
  // (j, n, R) as they are (patch_renderer.cpp, capSharedSlot).
  int slot = gl_VertexID % 16;
  bool capData = (patchKindRing(vc_patchIndex).x & 0xFF) == kPoleCapKind && slot != 0 && (slot < 6 || slot > 9);
  vc_fromEye = capData ? a_pointHi + a_pointLo : relativeToEye(a_pointHi, a_pointLo);
}
