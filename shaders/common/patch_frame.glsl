// Relative-to-eye drawing (patch_renderer.cpp, "Precision"). A float holds 24 bits: a model of
// size 1 refined to level 20 has patches of 1e-6, which float coordinates in world axes would
// round to a few bits, and a camera 1e-6 from them could not be placed at all. So nothing on the
// GPU is in world coordinates:
//  - each patch is evaluated in its own frame (origin at the patch, z along its normal; computed
//    in double on the CPU), so its control points keep 24 bits relative to the patch's size and
//    the heights that curvature comes from keep 24 bits relative to themselves;
//  - the frame's origin and the shared control points are double values split into float hi + lo
//    parts (relative to the model centre), and subtracting the eye's hi and lo first gives their
//    position relative to the eye to float precision of that (small) difference;
//  - u_viewRotationProjection is the projection times the view's rotation only.
// A point of a patch is then originFromEye + axes * local, in world axes, relative to the eye.
// Positions of B-spline patches are taken from the control points relative to the eye instead
// (positionFromEye): shared with the neighbours, so that a shared edge is placed alike from both.

uniform vec3 u_eyeHi, u_eyeLo;  // eye - model centre = hi + lo
uniform mat4 u_viewRotationProjection;
// Per patch, 5 RGB32F texels: origin hi, origin lo (relative to the model centre), the frame's
// axes x, y, z in world coordinates (columns of the rotation local -> world).
uniform samplerBuffer u_patchFrames;
// Per patch, one RG32I texel: (kind, level and edge level jumps packed as patch.tesc reads them;
// ring index).
uniform isamplerBuffer u_patchKinds;

ivec2 patchKindRing(int patchIndex) { return texelFetch(u_patchKinds, patchIndex).xy; }

// Patch::edgeLevelDelta of edges 0..3 (patch.h order) from the packed kind texel (bitfieldExtract
// of an int sign-extends).
ivec4 patchJumps(int kindLevelJumps) {
  return ivec4(bitfieldExtract(kindLevelJumps, 16, 4), bitfieldExtract(kindLevelJumps, 20, 4),
               bitfieldExtract(kindLevelJumps, 24, 4), bitfieldExtract(kindLevelJumps, 28, 4));
}

// Per slot its 16 control points as (GPU form, world hi, world lo), RGB32F texels: the vertex
// buffer itself, from which patch.tesc and patch.tese fetch the other sectors of a group
// (pipeline/draw_selection.h).
uniform samplerBuffer u_patchPoints;

// hi + lo (relative to the model centre) minus the eye: differences of nearby floats are exact,
// so the result is as precise as a float of its own size. `precise` keeps the compiler from
// reassociating the sum (which would round at the size of the model instead).
vec3 relativeToEye(vec3 hi, vec3 lo) {
  precise vec3 d = (hi - u_eyeHi) + (lo - u_eyeLo);
  return d;
}

// A control point relative to the eye as patch.vert passes it on: a cap's vector and parameter
// slots (all but p0 and b_j: 0, 6..9) as they are, in hi (patch_renderer.cpp, capSharedSlot; their
// lo texels carry the cap's f_j, fetchCapSecond). One function for every stage, so that a point
// fetched in patch.tese is the same bits as patch.vert's.
vec3 sharedPointFromEye(vec3 hi, vec3 lo, int kind, int slot) {
  bool capData = kind == 3 && slot != 0 && (slot < 6 || slot > 9);  // kind 3: kPatchPoleCap
  return capData ? hi : relativeToEye(hi, lo);
}

// A PoleCap's f_{j-1..j+2} (the ring's second radial derivative, patch.h): in the cap's GPU form
// (its frame, as forward differences; for patch_eval.glsl's evaluatePoleCap) from the lo texels of
// slots 12..15, and as world vectors (for capPositionFromEye) from those of slots 1..4.
void fetchCapSecond(int patchIndex, out vec3 local[4], out vec3 world[4]) {
  int base = 48 * patchIndex;
  for (int k = 0; k < 4; ++k) {
    local[k] = texelFetch(u_patchPoints, base + 3 * (12 + k) + 2).xyz;
    world[k] = texelFetch(u_patchPoints, base + 3 * (1 + k) + 2).xyz;
  }
}

// Patch `patchIndex`'s control points: in its frame (for evaluation) and relative to the eye.
void fetchPatchPoints(int patchIndex, int kind, out vec3 local[16], out vec3 fromEye[16]) {
  int base = 48 * patchIndex;
  for (int k = 0; k < 16; ++k) {
    local[k] = texelFetch(u_patchPoints, base + 3 * k).xyz;
    fromEye[k] = sharedPointFromEye(texelFetch(u_patchPoints, base + 3 * k + 1).xyz,
                                    texelFetch(u_patchPoints, base + 3 * k + 2).xyz, kind, k);
  }
}

struct PatchFrame {
  vec3 originFromEye;  // the frame's origin relative to the eye, world axes
  mat3 axes;           // local -> world rotation
};

PatchFrame patchFrame(int patchIndex) {
  int base = 5 * patchIndex;
  PatchFrame frame;
  frame.originFromEye = relativeToEye(texelFetch(u_patchFrames, base).xyz, texelFetch(u_patchFrames, base + 1).xyz);
  frame.axes = mat3(texelFetch(u_patchFrames, base + 2).xyz, texelFetch(u_patchFrames, base + 3).xyz,
                    texelFetch(u_patchFrames, base + 4).xyz);
  return frame;
}

// Position of a PoleCap (patch_eval.glsl, evaluatePoleCap) in world axes relative to the eye, from
// what neighbouring sectors share: p0 and b_j relative to the eye, p1..p5, e_j and (`second`) f_j as
// world vectors, (j, n, R) in slot 10 (patch_renderer.cpp, capSharedSlot). The angle is
// 2 pi (j + v) / n, so a radial edge (v = 0 of sector j, v = 1 of sector j - 1) gets the same
// angle, basis and sums, and the same position bits in both; the pole (u = 0) is p0 in every sector.
vec3 capPositionFromEye(vec3 d[16], vec3 second[4], float u, float v) {
  float n = d[10].y, R = d[10].z;
  float turn = d[10].x + v;  // whole at the edges; the last sector's end is sector 0's start
  if (turn >= n) turn -= n;
  float theta = 6.28318530717958647692 * (turn / n);
  float c = cos(theta), s = sin(theta), r = u * R, x = r * c, y = r * s;
  float c2 = c * c - s * s, s2 = 2.0 * s * c;
  float sv = 1.0 - v;
  vec4 bv = vec4(sv * sv * sv, (3.0 * v - 6.0) * v * v + 4.0, ((-3.0 * v + 3.0) * v + 3.0) * v + 1.0, v * v * v) / 6.0;
  vec3 C = ((bv[0] * d[6] + bv[1] * d[7]) + bv[2] * d[8]) + bv[3] * d[9];
  vec3 E = ((bv[0] * d[12] + bv[1] * d[13]) + bv[2] * d[14]) + bv[3] * d[15];
  vec3 F = ((bv[0] * second[0] + bv[1] * second[1]) + bv[2] * second[2]) + bv[3] * second[3];
  vec3 Q = d[3] + c2 * d[4] + s2 * d[5];
  vec3 T = d[0] + (x * d[1] + y * d[2]) + ((x * x + y * y) * d[3] + (x * x - y * y) * d[4] + (2.0 * x * y) * d[5]);
  vec3 Tb = d[0] + R * (c * d[1] + s * d[2]) + R * R * Q;
  vec3 Tr = c * d[1] + s * d[2] + 2.0 * R * Q;
  float u3 = u * u * u;
  float h = u3 * ((6.0 * u - 15.0) * u + 10.0), g = -u3 * (u - 1.0) * (3.0 * u - 4.0), k = 0.5 * u3 * (u - 1.0) * (u - 1.0);
  return T + (h * (C - Tb) + (R * g) * (E - Tr) + (R * R * k) * (F - 2.0 * Q));
}

// Position of a B-spline patch (patch.h order) from its control points relative to the eye, in the
// uniform B-spline basis, summed relative to its point 5 (a corner of the face) and moved back once:
// the differences to that point are exact or small, so the result carries one rounding at the
// size of its distance to the eye, as little as two patches placing a shared edge can differ by.
vec3 positionFromEye(vec3 fromEye[16], float u, float v) {
  float su = 1.0 - u, sv = 1.0 - v;
  vec4 bu = vec4(su * su * su, (3.0 * u - 6.0) * u * u + 4.0, ((-3.0 * u + 3.0) * u + 3.0) * u + 1.0, u * u * u) / 6.0;
  vec4 bv = vec4(sv * sv * sv, (3.0 * v - 6.0) * v * v + 4.0, ((-3.0 * v + 3.0) * v + 3.0) * v + 1.0, v * v * v) / 6.0;
  vec3 origin = fromEye[5];
  vec3 offset = vec3(0.0);
  for (int j = 0; j < 4; ++j) {
    vec3 row = bu[0] * (fromEye[4 * j] - origin) + bu[1] * (fromEye[4 * j + 1] - origin) +
               bu[2] * (fromEye[4 * j + 2] - origin) + bu[3] * (fromEye[4 * j + 3] - origin);
    offset += bv[j] * row;
  }
  return origin + offset;
}

// Watertight shared edges (docs/shading.md, "Watertight seams"). positionFromEye sums relative to a
// point of its own patch, so two patches place a shared edge apart by a rounding, and sub-pixel
// slivers (C2PS rings at level 12 seen from 1e-3: sectors a tenth of a pixel wide) let single
// background pixels through. A vertex on an edge two patches of one level share is therefore
// computed from what both hold alike: the edge's curve from the three rows of control points
// across it, in the orientation both pick (from its end points' bits), at the parameter of the
// vertex's integer index along the edge; a corner from the 3x3 points around it, in pairs of
// opposite points that rotations and reflections of the patch keep.

bool lexicographicallyBefore(vec3 a, vec3 b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

// t in 0..1 at the nearest of the n + 1 vertices of an edge cut into `segments` n.
float snappedEdgeParameter(float t, float segments) {
  float n = floor(segments + 0.5);
  return floor(t * n + 0.5) / n;
}

// The curve along an edge, from the three rows of control points across it (a and c the outer ones,
// b on the edge's side; both patches hold them, a and c swapped), at parameter t (0..1 from point 0
// to 3) of an edge cut into `segments`. Its B-spline points ((a + c) + 4 b) / 6 are taken relative to
// a point of b (as positionFromEye does: differences of nearby points are exact), the one at index 1
// in the orientation both patches pick from b's end points' bits.
vec3 sharedEdgePosition(vec3 a[4], vec3 b[4], vec3 c[4], float t, float segments) {
  int n = int(segments + 0.5);
  int k = int(t * float(n) + 0.5);
  bool reversed = lexicographicallyBefore(b[3], b[0]) || (b[3] == b[0] && lexicographicallyBefore(b[2], b[1]));
  if (reversed) k = n - k;
  vec3 origin = b[reversed ? 2 : 1];
  vec3 e[4];
  for (int i = 0; i < 4; ++i) {
    int at = reversed ? 3 - i : i;
    e[i] = (((a[at] - origin) + (c[at] - origin)) + 4.0 * (b[at] - origin)) / 6.0;
  }
  float s = float(k) / float(n), r = 1.0 - s;
  vec4 w = vec4(r * r * r, (3.0 * s - 6.0) * s * s + 4.0, ((-3.0 * s + 3.0) * s + 3.0) * s + 1.0, s * s * s) / 6.0;
  return origin + (((w[0] * e[0] + w[1] * e[1]) + w[2] * e[2]) + w[3] * e[3]);
}

// The surface at the knot of control point (i, j) (1 or 2 each): (1, 4, 1) x (1, 4, 1) / 36,
// relative to that point, in pairs of opposite neighbours.
vec3 sharedCornerPosition(vec3 p[16], int i, int j) {
  vec3 centre = p[4 * j + i];
  vec3 sides = ((p[4 * j + i - 1] - centre) + (p[4 * j + i + 1] - centre)) +
               ((p[4 * (j - 1) + i] - centre) + (p[4 * (j + 1) + i] - centre));
  vec3 diagonals = ((p[4 * (j - 1) + i - 1] - centre) + (p[4 * (j + 1) + i + 1] - centre)) +
                   ((p[4 * (j - 1) + i + 1] - centre) + (p[4 * (j + 1) + i - 1] - centre));
  return centre + (4.0 * sides + diagonals) / 36.0;
}

// Row j (0..3) of control points along u, and column i along v.
void patchRow(vec3 p[16], int j, out vec3 row[4]) { for (int i = 0; i < 4; ++i) row[i] = p[4 * j + i]; }
void patchColumn(vec3 p[16], int i, out vec3 column[4]) { for (int j = 0; j < 4; ++j) column[j] = p[4 * j + i]; }

// Position of a B-spline patch at (u, v) with its edges' levels (GL order: outer 0 u = 0, 1 v = 0,
// 2 u = 1, 3 v = 1) and level jumps (patch.h order: 0 v = 0, 1 u = 1, 2 v = 1, 3 u = 0): shared
// edges and corners as above, the inside (and T-junction edges, whose sides hold other curves) as
// positionFromEye.
// `onEdge`: whether (u, v) is on the edge u = 0, v = 0, u = 1, v = 1 that the patch shares (a
// sector inside a group shares only its circle edges and the group's ends, patch.tese).
vec3 watertightPositionFromEye(vec3 p[16], float u, float v, float outer[4], ivec4 jumps, bvec4 onEdge) {
  bool u0 = onEdge.x, v0 = onEdge.y, u1 = onEdge.z, v1 = onEdge.w;
  if ((u0 || u1) && (v0 || v1)) return sharedCornerPosition(p, u0 ? 1 : 2, v0 ? 1 : 2);
  vec3 a[4], b[4], c[4];
  if ((v0 && jumps[0] == 0) || (v1 && jumps[2] == 0)) {
    patchRow(p, v0 ? 0 : 3, a);
    patchRow(p, v0 ? 1 : 2, b);
    patchRow(p, v0 ? 2 : 1, c);
    return sharedEdgePosition(a, b, c, u, outer[v0 ? 1 : 3]);
  }
  if ((u0 && jumps[3] == 0) || (u1 && jumps[1] == 0)) {
    patchColumn(p, u0 ? 0 : 3, a);
    patchColumn(p, u0 ? 1 : 2, b);
    patchColumn(p, u0 ? 2 : 1, c);
    return sharedEdgePosition(a, b, c, v, outer[u0 ? 0 : 2]);
  }
  return positionFromEye(p, u, v);
}

vec3 watertightPositionFromEye(vec3 p[16], float u, float v, float outer[4], ivec4 jumps) {
  return watertightPositionFromEye(p, u, v, outer, jumps, bvec4(u == 0.0, v == 0.0, u == 1.0, v == 1.0));
}
