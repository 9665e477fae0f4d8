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

// hi + lo (relative to the model centre) minus the eye: differences of nearby floats are exact,
// so the result is as precise as a float of its own size. `precise` keeps the compiler from
// reassociating the sum (which would round at the size of the model instead).
vec3 relativeToEye(vec3 hi, vec3 lo) {
  precise vec3 d = (hi - u_eyeHi) + (lo - u_eyeLo);
  return d;
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
// what neighbouring sectors share: p0 and b_j relative to the eye, p1..p5 and e_j as world vectors,
// (j, n, R) in slot 10 and the Taylor order in slot 11 (patch_renderer.cpp, capSharedSlot). The angle is 2 pi (j + v) / n, so a
// radial edge (v = 0 of sector j, v = 1 of sector j - 1) gets the same angle, basis and sums, and the
// same position bits in both; the pole (u = 0) is p0 in every sector.
vec3 capPositionFromEye(vec3 d[16], float u, float v) {
  if (d[11].x < 1.5) d[3] = d[4] = d[5] = vec3(0.0);  // BPS: the tangent plane only (taylorOrder 1)
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
  vec3 T = d[0] + (x * d[1] + y * d[2]) + ((x * x + y * y) * d[3] + (x * x - y * y) * d[4] + (2.0 * x * y) * d[5]);
  vec3 Tb = d[0] + R * (c * d[1] + s * d[2]) + R * R * (d[3] + c2 * d[4] + s2 * d[5]);
  vec3 Tr = c * d[1] + s * d[2] + 2.0 * R * (d[3] + c2 * d[4] + s2 * d[5]);
  float h = u * u * u * (4.0 - 3.0 * u), g = u * u * u * (u - 1.0);
  return T + (h * (C - Tb) + (R * g) * (E - Tr));
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
