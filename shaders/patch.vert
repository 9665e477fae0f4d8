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
// The patch's slot in the buffers, and the drawn item it is part of (-1: drawn alone, the slots in
// order). A plain draw's gl_VertexID is slot * 16 + k (counting from the buffer start in every run
// of a multi-draw, where gl_PrimitiveID restarts); an item draw's is item * 16 + k, the item's
// texels (patch.tesc's u_drawItems) name the slot and its points come from u_patchPoints.
flat out int vc_patchIndex;
flat out int vc_itemIndex;

uniform int u_useItems;
uniform isamplerBuffer u_drawItems;

void main() {
  int k = gl_VertexID % 16;
  vec3 local = a_localPoint, hi = a_pointHi, lo = a_pointLo;
  vc_patchIndex = gl_VertexID / 16;
  vc_itemIndex = -1;
  if (u_useItems != 0) {
    vc_itemIndex = gl_VertexID / 16;
    vc_patchIndex = texelFetch(u_drawItems, 2 * vc_itemIndex).x;
    int texel = 48 * vc_patchIndex + 3 * k;
    local = texelFetch(u_patchPoints, texel).xyz;
    hi = texelFetch(u_patchPoints, texel + 1).xyz;
    lo = texelFetch(u_patchPoints, texel + 2).xyz;
  }
  vc_controlPoint = local;
  vc_fromEye = sharedPointFromEye(hi, lo, patchKindRing(vc_patchIndex).x & 0xFF, k);
}
