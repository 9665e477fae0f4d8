#version 410 core
// Patch boundaries: 4 isolines (one per edge) with a fixed number of segments.
layout(vertices = 16) out;

in vec3 vc_controlPoint[];
flat in ivec2 vc_kindRing[];
out vec3 tc_controlPoint[];
flat out ivec2 tc_kindRing[];
uniform float u_boundarySegments;

void main() {
  tc_controlPoint[gl_InvocationID] = vc_controlPoint[gl_InvocationID];
  // x packs the kind with the level and edge jumps (patch.tesc): keep the kind only.
  tc_kindRing[gl_InvocationID] = ivec2(vc_kindRing[gl_InvocationID].x & 0xFF, vc_kindRing[gl_InvocationID].y);
  if (gl_InvocationID == 0) {
    gl_TessLevelOuter[0] = 4.0;  // number of isolines
    gl_TessLevelOuter[1] = u_boundarySegments;
  }
}
