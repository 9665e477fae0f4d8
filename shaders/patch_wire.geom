#version 410 core
// Adds barycentric coordinates to each tessellated triangle for the wireframe overlay.
#include "common/surface_varyings.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in SurfaceData { SURFACE_DATA_MEMBERS } te_out[];
out SurfaceData { SURFACE_DATA_MEMBERS } gs_out;
noperspective out vec3 g_barycentric;

void main() {
  for (int k = 0; k < 3; ++k) {
    gs_out.position = te_out[k].position;
    gs_out.normal = te_out[k].normal;
    gs_out.curvature = te_out[k].curvature;
    gs_out.uv = te_out[k].uv;
    gs_out.kindRing = te_out[k].kindRing;
    g_barycentric = vec3(k == 0, k == 1, k == 2);
    gl_Position = gl_in[k].gl_Position;
    EmitVertex();
  }
  EndPrimitive();
}
