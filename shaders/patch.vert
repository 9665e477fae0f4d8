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

void main() {
  vc_controlPoint = a_localPoint;
  vc_fromEye = relativeToEye(a_pointHi, a_pointLo);
  vc_patchIndex = gl_VertexID / 16;
}
