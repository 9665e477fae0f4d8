#version 410 core
// Screen-space adaptive tessellation levels. Each outer level is computed only from the boundary
// curve of that edge (its Bezier control polygon, projected), with expressions symmetric under
// reversal of the edge, so two patches sharing an edge get the same level (no cracks).
// T-junction edges (Patch::edgeLevelDelta d != 0, patch.h): a coarse edge faces 2^d finer edges, so
// their levels come from integers only (transitionEdgeSegments in patch_extraction.h, mirrored
// here): 2^clamp(k - level, d, 6) on the coarse side, 2^clamp(k - level, 0, 6 + d) on a fine side,
// k = u_transitionDensity. With equal spacing the fine vertices are then exactly the coarse ones.
// Levels and culling use the control points relative to the eye (vc_fromEye, the same bits in
// every patch that shares them); evaluation gets them in the patch's frame (patch_frame.glsl).
// A drawn item (patch_renderer.cpp) may be a group of a ring row's sectors, and the edges on its
// link circles may have levels the draw selection agreed for both sides (circleLevel,
// pipeline/draw_selection.h); those replace the rules above there.
#include "common/patch_eval.glsl"
#include "common/patch_frame.glsl"

layout(vertices = 16) out;

in vec3 vc_controlPoint[];
in vec3 vc_fromEye[];
flat in int vc_patchIndex[];
flat in int vc_itemIndex[];
out vec3 tc_controlPoint[];
out vec3 tc_fromEye[];
// (kind, ring index) of the patch. The per-patch texel's x (patch_frame.glsl's patchKindRing)
// packs (patch_renderer.cpp): bits 0-7 PatchKind, 8-15 level, then Patch::edgeLevelDelta of edges
// 0..3 (patch.h order: 0 v = 0, 1 u = 1, 2 v = 1, 3 u = 0) as signed 4-bit fields at bits 16 + 4s.
// The evaluation stages get the plain kind.
patch out ivec2 tc_kindRing;
patch out ivec4 tc_jumps;  // Patch::edgeLevelDelta (patch.h edge order), for the watertight edges
patch out int tc_patchIndex;
patch out vec3 tc_originFromEye;  // the patch's frame (PatchFrame) for patch.tese
patch out mat3 tc_axes;
// A group of a ring row's sectors drawn as one primitive (pipeline/draw_selection.h): (the row's
// first entry in u_rowSlots, the first sector, sectors in the row, log2 of the sectors in the
// group); x = -1 for a lone patch.
patch out ivec4 tc_group;

uniform vec2 u_viewportSize;         // pixels
uniform float u_tessPixels;          // target edge length in pixels
uniform float u_maxTessLevel;
uniform float u_fixedTessLevel;      // > 0: use this level everywhere (probes, comparisons)
uniform int u_transitionDensity;     // k: 2^k segments per level-0 parameter unit on T-junctions
uniform float u_nearDepth;           // the near plane's distance (perspective), w's floor below
// Drawn items (patch_renderer.cpp, DrawItem; patch.vert): per item two RGBA32I texels, (slot, row
// start, sector, sectors in the row) and (packed: bits 0-7 log2 of the group's sectors, 8-15 and
// 16-23 the exponent + 1 of the segments of the group's edges u = 0 and u = 1, 0 for the patch's
// own rule); u_useItems = 0: every primitive is a lone patch with its own rules.
uniform int u_useItems;
uniform isamplerBuffer u_drawItems;
uniform isamplerBuffer u_rowSlots;  // per row its slots in sector order

// Projected points are clamped to a frame half a viewport beyond each border, so an edge's level
// follows its length on and near the screen: in close-ups, the parts of patches beside or behind
// the eye (w below the near plane's distance is clamped to it, then to the frame; an absolute
// floor would flatten close-ups of deep poles, 1e-6 from the eye, to level 1) do not all go to the
// highest level.
// The clamp is per point, so two patches sharing an edge still measure it alike.
vec2 toPixels(vec3 fromEye) {
  vec4 clip = u_viewRotationProjection * vec4(fromEye, 1.0);
  float w = max(clip.w, u_nearDepth);
  return clamp(clip.xy / w, vec2(-2.0), vec2(2.0)) * 0.5 * u_viewportSize;
}

// Edge curve with B-spline control points e0..e3 over its middle span -> projected length of its
// Bezier polygon (docs/patches.md, B-spline basis and Bezier form), summed symmetrically in
// e0..e3 <-> e3..e0.
float projectedCurveLength(vec3 e0, vec3 e1, vec3 e2, vec3 e3) {
  vec2 b0 = toPixels(((e0 + e2) + 4.0 * e1) / 6.0);
  vec2 b1 = toPixels((2.0 * e1 + e2) / 3.0);
  vec2 b2 = toPixels((e1 + 2.0 * e2) / 3.0);
  vec2 b3 = toPixels(((e1 + e3) + 4.0 * e2) / 6.0);
  return (distance(b0, b1) + distance(b2, b3)) + distance(b1, b2);
}

// B-spline control point k of the curve along a patch edge: the surface's B-spline at the edge
// knot, a row/column average (a + c) + 4 b in the same order from both neighbouring patches.
vec3 edgePoint(int a, int b, int c) {
  return ((vc_fromEye[a] + vc_fromEye[c]) + 4.0 * vc_fromEye[b]) / 6.0;
}

// The same from the group's last sector (patch.tesc's `last`: the patch itself when alone).
vec3 lastEdgePoint(vec3 last[16], int a, int b, int c) { return ((last[a] + last[c]) + 4.0 * last[b]) / 6.0; }

float levelFor(float pixels) {
  if (u_fixedTessLevel > 0.0) return u_fixedTessLevel;
  return clamp(ceil(pixels / u_tessPixels), 1.0, u_maxTessLevel);
}

// Level of a T-junction edge with level jump d != 0 of a patch of `level` (see the top).
float transitionLevel(int level, int d) {
  int wanted = u_transitionDensity - level;
  int exponent = d > 0 ? min(max(wanted, d), 6) : min(max(wanted, 0), max(6 + d, 0));
  return float(1 << exponent);
}

// Outer level of an edge: the T-junction rule where it has a level jump, else adaptive.
float edgeLevel(float pixels, int level, int d) {
  if (d != 0 && u_fixedTessLevel <= 0.0) return transitionLevel(level, d);
  return levelFor(pixels);
}

// All 16 control points outside one clip plane: the patch (inside their hull) is invisible.
bool outsideFrustum() {
  ivec3 below = ivec3(0), above = ivec3(0);
  for (int k = 0; k < 16; ++k) {
    vec4 clip = u_viewRotationProjection * vec4(vc_fromEye[k], 1.0);
    below += ivec3(lessThan(clip.xyz, vec3(-clip.w)));
    above += ivec3(greaterThan(clip.xyz, vec3(clip.w)));
  }
  return any(equal(below, ivec3(16))) || any(equal(above, ivec3(16)));
}

// Level of a circle edge the draw selection set (2^exponent), else `own`.
float circleLevel(int exponent, float own) { return exponent >= 0 ? float(1 << exponent) : own; }

void main() {
  tc_controlPoint[gl_InvocationID] = vc_controlPoint[gl_InvocationID];
  tc_fromEye[gl_InvocationID] = vc_fromEye[gl_InvocationID];
  if (gl_InvocationID != 0) return;
  ivec2 kindRing = patchKindRing(vc_patchIndex[0]);
  int kindLevelJumps = kindRing.x;
  int kind = kindLevelJumps & 0xFF, level = (kindLevelJumps >> 8) & 0xFF;
  tc_kindRing = ivec2(kind, kindRing.y);
  tc_patchIndex = vc_patchIndex[0];
  ivec4 group = ivec4(-1, 0, 1, 0);
  int innerExponent = -1, outerExponent = -1;
  if (vc_itemIndex[0] >= 0) {
    ivec4 place = texelFetch(u_drawItems, 2 * vc_itemIndex[0]);
    int itemBits = texelFetch(u_drawItems, 2 * vc_itemIndex[0] + 1).x;
    if (place.y >= 0) group = ivec4(place.yzw, itemBits & 0xFF);
    innerExponent = ((itemBits >> 8) & 0xFF) - 1;
    outerExponent = ((itemBits >> 16) & 0xFF) - 1;
  }
  tc_group = group;
  // The group's edge v = 1 is its last sector's, shared with the next group's first sector: its
  // level from that sector's points (the same bits as there).
  int sectors = 1 << group.w;
  vec3 last[16];
  for (int k = 0; k < 16; ++k) last[k] = vc_fromEye[k];
  if (sectors > 1) {
    int lastSlot = texelFetch(u_rowSlots, group.x + (group.y + sectors - 1) % group.z).x;
    vec3 unusedLocal[16];
    fetchPatchPoints(lastSlot, kind, unusedLocal, last);
  }

  // Quads: outer[0] is the edge u = 0, [1] v = 0, [2] u = 1, [3] v = 1.
  float outer0, outer1, outer2, outer3;
  tc_jumps = ivec4(0);
  if (kind == kPatchPoleCap) {
    // Pole edge u = 0 is a point; the radial edges v = 0, 1 run from p0 to the boundary curve's
    // ends; the edge u = 1 is the boundary curve b0..b3 shared with the innermost ring.
    vec3 start = ((vc_fromEye[6] + vc_fromEye[8]) + 4.0 * vc_fromEye[7]) / 6.0;
    vec3 end = ((last[7] + last[9]) + 4.0 * last[8]) / 6.0;
    vec2 pole = toPixels(vc_fromEye[0]);
    outer0 = 1.0;
    outer1 = levelFor(1.5 * distance(pole, toPixels(start)));
    outer3 = levelFor(1.5 * distance(pole, toPixels(end)));
    outer2 = circleLevel(outerExponent, levelFor(projectedCurveLength(vc_fromEye[6], vc_fromEye[7], vc_fromEye[8], vc_fromEye[9])));
  } else if (u_fixedTessLevel <= 0.0 && sectors == 1 && outsideFrustum()) {
    outer0 = outer1 = outer2 = outer3 = 0.0;  // discards the patch (groups: culled on the CPU)
  } else {
    ivec4 jump = patchJumps(kindLevelJumps);
    tc_jumps = jump;
    // GL edge u = 0 is patch edge 3, v = 0 is 0, u = 1 is 1, v = 1 is 2.
    outer0 = edgeLevel(projectedCurveLength(edgePoint(0, 1, 2), edgePoint(4, 5, 6),
                                            edgePoint(8, 9, 10), edgePoint(12, 13, 14)), level, jump[3]);
    outer2 = edgeLevel(projectedCurveLength(edgePoint(1, 2, 3), edgePoint(5, 6, 7),
                                            edgePoint(9, 10, 11), edgePoint(13, 14, 15)), level, jump[1]);
    outer1 = edgeLevel(projectedCurveLength(edgePoint(0, 4, 8), edgePoint(1, 5, 9),
                                            edgePoint(2, 6, 10), edgePoint(3, 7, 11)), level, jump[0]);
    outer3 = edgeLevel(projectedCurveLength(lastEdgePoint(last, 4, 8, 12), lastEdgePoint(last, 5, 9, 13),
                                            lastEdgePoint(last, 6, 10, 14), lastEdgePoint(last, 7, 11, 15)), level, jump[2]);
    outer0 = circleLevel(innerExponent, outer0);
    outer2 = circleLevel(outerExponent, outer2);
  }
  // The frame, for the evaluation, only for patches that are drawn (close-ups cull most).
  if (outer0 > 0.0) {
    PatchFrame frame = patchFrame(vc_patchIndex[0]);
    tc_originFromEye = frame.originFromEye;
    tc_axes = frame.axes;
  }
  gl_TessLevelOuter[0] = outer0;
  gl_TessLevelOuter[1] = outer1;
  gl_TessLevelOuter[2] = outer2;
  gl_TessLevelOuter[3] = outer3;
  gl_TessLevelInner[0] = max(outer1, outer3);  // along u
  gl_TessLevelInner[1] = max(outer0, outer2);  // along v
}
