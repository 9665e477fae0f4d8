#version 410 core
// Pass-through of the 16 control points of a patch (GL_PATCHES, 16 vertices per patch).
layout(location = 0) in vec3 a_position;   // relative to the model centre (see patch_eval.glsl)
layout(location = 1) in ivec2 a_kindRing;  // (PatchKind, ring index), the same on all 16

out vec3 vc_controlPoint;
flat out ivec2 vc_kindRing;
// The patch's index in the buffer: gl_VertexID counts from the buffer start in every run of a
// multi-draw, where gl_PrimitiveID restarts (patch_renderer.cpp draws runs of patches).
flat out int vc_patchIndex;

void main() {
  vc_controlPoint = a_position;
  vc_kindRing = a_kindRing;
  vc_patchIndex = gl_VertexID / 16;
}
