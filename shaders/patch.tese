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
patch in ivec4 tc_jumps;
patch in int tc_patchIndex;
patch in vec3 tc_originFromEye;
patch in mat3 tc_axes;
patch in ivec4 tc_group;  // patch.tesc: a group of a row's sectors (x >= 0), one primitive

uniform isamplerBuffer u_rowSlots;  // per row its slots in sector order (patch.tesc)

// The step across a T-junction edge the vertex is on (patch.h edge order of `jumps`), else 0.
vec3 tJunctionOverlap(SurfacePoint s, mat3 axes, float u, float v, bvec4 onEdge, ivec4 jumps, float distanceToEye) {
  vec3 outward = vec3(0.0);
  if (onEdge.x && jumps[3] != 0) outward -= s.du;
  if (onEdge.z && jumps[1] != 0) outward += s.du;
  if (onEdge.y && jumps[0] != 0) outward -= s.dv;
  if (onEdge.w && jumps[2] != 0) outward += s.dv;
  float size = length(outward);
  return size > 0.0 ? (1e-6 * distanceToEye / size) * (axes * outward) : vec3(0.0);
}

void main() {
  vec3 cp[16], points[16];
  for (int k = 0; k < 16; ++k) cp[k] = tc_controlPoint[k], points[k] = tc_fromEye[k];
  float u = gl_TessCoord.x, v = gl_TessCoord.y;
  // Derivatives, K and H are the same in any frame (rotation and translation): evaluate locally.
  int kind = tc_kindRing.x;
  float outer[4] = float[4](gl_TessLevelOuter[0], gl_TessLevelOuter[1], gl_TessLevelOuter[2], gl_TessLevelOuter[3]);
  // A vertex on an edge at exactly k / n along it (llvmpipe places them within ~2^-16 of that), the
  // parameter watertightPositionFromEye evaluates the shared edge at.
  if (kind != kPatchPoleCap) {
    if (v == 0.0 || v == 1.0) u = snappedEdgeParameter(u, outer[v == 0.0 ? 1 : 3]);
    if (u == 0.0 || u == 1.0) v = snappedEdgeParameter(v, outer[u == 0.0 ? 0 : 2]);
  }
  // A group of g sectors (pipeline/draw_selection.h): v runs over all of them; the vertex is
  // evaluated in sector s = floor(v g) at v g - s (exact: g and the circle levels are powers of two),
  // from that sector's own points. Its circle edges then have outer / g segments per sector, the
  // same as the sectors across the circle; only the group's ends are radial edges shared.
  // Only the program for groups (SECTOR_GROUPS, patch_renderer.cpp) has this path: llvmpipe runs
  // a shader with it, even where no vertex takes it, 20% slower (a Catmull-Clark close-up).
  int patchIndex = tc_patchIndex;
  ivec4 jumps = tc_jumps;
  mat3 axes = tc_axes;
  float sectorV = v;
  bvec4 onEdge = bvec4(u == 0.0, v == 0.0, u == 1.0, v == 1.0);
#ifdef SECTOR_GROUPS
  int sectors = tc_group.x >= 0 ? 1 << tc_group.w : 1;
  if (sectors > 1) {
    float scaled = v * float(sectors);
    int s = min(int(floor(scaled)), sectors - 1);
    sectorV = scaled - float(s);
    bool onCircle = onEdge.x || onEdge.z;
    onEdge.y = sectorV == 0.0 && (s == 0 || onCircle);
    onEdge.w = sectorV == 1.0;
    outer[0] /= float(sectors);
    outer[2] /= float(sectors);
    if (s > 0) {
      patchIndex = texelFetch(u_rowSlots, tc_group.x + (tc_group.y + s) % tc_group.z).x;
      fetchPatchPoints(patchIndex, kind, cp, points);
      axes = patchFrame(patchIndex).axes;
      jumps = kind == kPatchPoleCap ? ivec4(0) : patchJumps(patchKindRing(patchIndex).x);
    }
  }
#endif
  vec3 secondLocal[4], secondWorld[4];  // a cap's f_j (patch_frame.glsl)
  if (kind == kPatchPoleCap) fetchCapSecond(patchIndex, secondLocal, secondWorld);
  SurfacePoint s = evaluatePatch(cp, secondLocal, kind, u, sectorV);
  // The position: a cap's from its frame; a B-spline patch's from the points shared with its
  // neighbours, its shared edges and corners alike on both sides (patch_frame.glsl).
  vec3 fromEye;
  if (kind == kPatchPoleCap) fromEye = capPositionFromEye(points, secondWorld, u, sectorV);
  else if (kind == kPatchEndCap) fromEye = positionFromEye(points, u, sectorV);
  else fromEye = watertightPositionFromEye(points, u, sectorV, outer, jumps, onEdge);
  // A T-junction edge's vertices are the same parameters on both sides but computed from each
  // side's own points (another level's), so they meet to a rounding (~6e-8 of their distance to
  // the eye), where a pixel centre can fall through (seen once in 12 close-ups, a seam between
  // level 7 and 8 at 600x450). Each side reaches 1e-6 of that distance (about 1e-3 pixel) across
  // the edge: the two overlap instead.
  if (kind != kPatchPoleCap) fromEye += tJunctionOverlap(s, axes, u, sectorV, onEdge, jumps, length(fromEye));
#ifdef PROBE
  probe_uvKH = vec4(u, v, s.gaussian, s.mean);
  probe_positionPatch = vec4(fromEye, float(patchIndex));
#else
  te_out.position = fromEye;
  te_out.normal = axes * s.normal;
  te_out.curvature = vec2(s.gaussian, s.mean);
  te_out.uv = vec2(u, v);
  te_out.kindRing = tc_kindRing;
#endif
  gl_Position = u_viewRotationProjection * vec4(fromEye, 1.0);
}
