// Patch: the unit the limit surface is made of, on the CPU and (mirrored) on the GPU.
//
// CONTROL-POINT ORDER (the one place it is documented; shaders/common/patch_eval.glsl refers here):
//   cp[4*j + i], i = 0..3 along u, j = 0..3 along v.
//   For a Regular / Boundary / PolarRing / EndCap patch the cp are uniform bicubic B-spline control
//   points; the patch covers the middle knot span (u,v) in [0,1]^2, whose corners
//   (0,0),(1,0),(1,1),(0,1) sit over cp[5], cp[6], cp[10], cp[9], i.e. over the mesh face
//   (v0, v1, v2, v3) in its counter-clockwise order, so x_u x x_v points along the face normal.
//   For a polar ring patch one of u, v runs radially and the other around the pole; turned by
//   Patch::ringTurn (turnedPatch), u runs outwards (link i -> i + 1) and v around.
//
// PoleCap (the Taylor cap closing the hole at a pole, paper (32)), per sector j of n
// (Patch::sector = j, Patch::sectorCount = n):
//   cp[0..5]   = p0..p5 (in the cap's own radial unit: the hole is r <= R = kPoleCapRadius = 2);
//                p3..p5 are zero where the scheme gives the tangent plane only (BPS)
//   cp[6..9]   = B-spline control points b_{j-1..j+2} of the ring's inner boundary curve at r = R:
//                b_j = (q1j + 4 q2j + q3j) / 6
//   cp[12..15] = B-spline control points e_{j-1..j+2} of the ring's first radial derivative at
//                r = R, per unit r: e_j = (q3j - q1j) / 2
//   cp[10], cp[11], capExtra[0], capExtra[1] = B-spline control points f_{j-1..j+2} of the ring's
//                second radial derivative at r = R, per unit r^2: f_j = q1j - 2 q2j + q3j
//                (capSecondPoint reads them in order)
//   (q_ij: point i of column j of the pole's grid at the cap's level, link i at r = i; b, e, f
//   are value, first and second derivative of the ring patches between links 2-3 at link 2; e and
//   f are vectors, not positions.)
//   Parameter: u = r / R in [0,1] (u = 0 is the pole), v in [0,1] along the sector, which covers
//   tau = (j + v) / n turns.
//   Position: T(x,y) + h(u) D0(v) + R g(u) D1(v) + R^2 k(u) D2(v), T = p0 + p1 x + p2 y
//   + p3 (x^2+y^2) + p4 (x^2-y^2) + 2 p5 x y, (x,y) = r (cos 2 pi tau, sin 2 pi tau); on the circle
//   r = R the mismatches D0 = C(v) - T, D1 = E(v) - dT/dr, D2 = F(v) - d2T/dr2 with C, E, F the
//   B-splines of b, e, f. Quintic blends
//     h(u) = u^3 (6u^2 - 15u + 10),  g(u) = -u^3 (u - 1)(3u - 4),  k(u) = u^3 (u - 1)^2 / 2,
//   with h(1) = 1, g'(1) = 1, k''(1) = 1 and every other value, first and second derivative at
//   u = 1 zero: position and first and second radial derivatives at u = 1 are the ring's (C2
//   across the seam). h, g, k vanish to second order at u = 0 (factor u^3), so the value, normal and
//   curvature at the pole are exactly those of the Taylor expansion. The blend is
//   r^3 A(v) + r^4 B(v) + r^5 C(v) (homogeneous in r), so the cap is a polynomial of degree 5 in u.
// EDGES (edgeLevelDelta): edge s runs from corner s to corner s+1 of the parameter square, i.e.
//   s = 0: v = 0, s = 1: u = 1, s = 2: v = 1, s = 3: u = 0 (for a face-based patch: the face's side
//   from vertex s to vertex s+1; for a PoleCap: 0 and 2 radial, 1 the boundary with the ring, 3 the
//   pole). edgeLevelDelta[s] = d > 0: the surface across the edge is made of patches d levels finer
//   (this patch is the coarse side of a T-junction; where the finer side mixes levels, the largest
//   difference); d < 0: the patch across is |d| levels coarser (this is a fine side); 0: same level,
//   a mesh boundary, or no level jump in parameter (RTS/BPS radial levels keep the columns).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh/poly_mesh.h"

namespace polarview {

enum class PatchKind : uint8_t {
  Regular = 0,    // face with a regular 4x4 neighbourhood (Catmull-Clark region)
  Boundary = 1,   // regular face on a boundary: missing points mirrored (OpenSubdiv's rule)
  PolarRing = 2,  // face of a polar spline ring (paper (6)-(8))
  PoleCap = 3,    // Taylor cap at a pole (layout above)
  EndCap = 4,     // face next to an extraordinary vertex left after the last level
};
const char* patchKindName(PatchKind kind);

struct Patch {
  std::array<Point, 16> cp{};
  // The positions among cp (isPositionPoint) are relative to `origin`: a feature-adaptive
  // refinement keeps each part of a level in a frame of its own (adaptive_refiner.h, Precision), so
  // a patch at level 20 keeps double precision relative to its own size. Vectors (a PoleCap's
  // p1..p5, e_j and f_j) are not. Zero for patches of the uniform refinement.
  Point origin{0.0};
  PatchKind kind = PatchKind::Regular;
  uint8_t level = 0;   // refinement level the patch was extracted at
  int32_t ring = -1;   // polar ring index m (PolarRing, PoleCap); -1 otherwise
  int32_t pole = -1;   // index of the pole (in the scheme's pole list) it belongs to; -1 otherwise
  int32_t face = -1;   // face index at `level` it was made from (-1 for caps)
  // Where in its pole's grid at `level` it lies, -1 otherwise. A PolarRing's face is between links
  // `link` and link + 1 (links 1..5 around the pole) and is the sector-th of its row in the order its
  // v runs once turned by ringTurn quarter turns (the parameter square turned so that u runs
  // outwards: the turned patch's (u', v') is the patch's (1 - v', u') applied ringTurn times). A
  // PoleCap: link 0, sector j. The viewer draws runs of sub-pixel sectors of one row as one
  // primitive by these (pipeline/draw_selection.h).
  int32_t sector = -1;
  int16_t link = -1;
  int8_t ringTurn = 0;
  std::array<int8_t, 4> edgeLevelDelta{};  // per edge (order above): level jump to the neighbour
  int32_t sectorCount = 0;                 // PoleCap: n, the sectors of its pole; 0 otherwise
  // PoleCap: f_{j+1}, f_{j+2} (layout above: a cap needs 18 vectors); zero for every other kind.
  std::array<Point, 2> capExtra{};
};

inline constexpr double kPoleCapRadius = 2.0;  // R: a cap covers r <= R, inside link 2

// f_{j-1+k} (k = 0..3) of a PoleCap: the ring's second radial derivative (layout above). [O(1)]
inline const Point& capSecondPoint(const Patch& cap, int k) {
  return k < 2 ? cap.cp[size_t(10 + k)] : cap.capExtra[size_t(k - 2)];
}
inline Point& capSecondPoint(Patch& cap, int k) { return k < 2 ? cap.cp[size_t(10 + k)] : cap.capExtra[size_t(k - 2)]; }

// Differential quantities of a patch at one parameter (u,v).
struct SurfacePoint {
  Point position{}, du{}, dv{}, duu{}, duv{}, dvv{};
  Point normal{};           // unit, along du x dv
  double gaussian = 0.0;    // K
  double mean = 0.0;        // H (sign: positive where the surface bends towards the normal)
};

// Evaluates position (absolute: origin added), first and second derivatives, normal, K and H.
// [O(1)]
SurfacePoint evaluatePatch(const Patch& patch, double u, double v);

// Whether cp[k] of a patch of this kind is a position (relative to Patch::origin): all 16 of a
// B-spline patch; p0 and b_j (cp[0], cp[6..9]) of a PoleCap. [O(1)]
bool isPositionPoint(PatchKind kind, int k);
// The patch with its origin added to its positions and then zero (absolute coordinates, rounded
// there): for writers and comparisons that do not need the precision. [O(1)]
Patch withAbsolutePositions(const Patch& patch);
// The same B-spline patch with its parameter square turned `turns` quarter turns (any integer):
// the result at (u', v') is the patch at turnedParameter(u', v', turns); cp and edgeLevelDelta
// follow, orientation (x_u x x_v) is kept. A PoleCap is returned as it is. [O(1)]
Patch turnedPatch(const Patch& patch, int turns);
// Which of the patch's control points is control point k of turnedPatch(patch, turns), turns in
// 0..3: one quarter turn maps (i', j') to (3 - j', i'). A table: uploads and the viewer's draw
// selection read every ring patch through it. [O(1)]
inline constexpr std::array<std::array<int8_t, 16>, 4> kTurnedControlIndex = [] {
  std::array<std::array<int8_t, 16>, 4> table{};
  for (int turns = 0; turns < 4; ++turns)
    for (int c = 0; c < 16; ++c) {
      int k = c;
      for (int t = 0; t < turns; ++t) k = 4 * (k % 4) + (3 - k / 4);
      table[size_t(turns)][size_t(c)] = int8_t(k);
    }
  return table;
}();
inline int turnedControlIndex(int k, int turns) { return kTurnedControlIndex[size_t(((turns % 4) + 4) % 4)][size_t(k)]; }
// (u, v) of a patch for (u', v') of turnedPatch(patch, turns): (1 - v', u') applied `turns` times.
void turnedParameter(double* u, double* v, int turns);

}  // namespace polarview
