// The limit surface as Bezier patches in BezierView's .bv format (the viewer of J. Peters' SurfLab,
// University of Florida; format as its FORMAT.txt and loader src/load.c read it).
//
// FILE LAYOUT. A .bv file is a sequence of segments, each a patch kind on its own line followed by
// the patch data; "Group <id> <name>" lines put the segments after them into the group <name> (one
// whitespace-free token; BezierView uses <id> as the group's colour index, modulo its palette). The
// file has no comments: BezierView would read one as a patch kind. Everything is written as kind 5,
// the general tensor-product Bezier patch:
//     5
//     deg_u deg_v
//     (deg_u + 1) (deg_v + 1) lines "x y z", row-major: b(i, j), i = 0..deg_u (the row, along u),
//     j = 0..deg_v (the column, along v), j fastest.
// BezierView takes the normal of a row-major patch as d/di x d/dj (its evalPN: (b10 - b00) x
// (b01 - b00)), so with rows along patch.h's u and columns along its v the written normal is
// evaluatePatch's du x dv: outwards on a mesh whose faces run counter-clockwise seen from outside.
// Coordinates are written with 17 significant digits (they read back to the same doubles).
//
// WHAT IS WRITTEN, AND HOW EXACTLY.
//  * Regular, Boundary, PolarRing, EndCap: each uniform bicubic B-spline patch of patch.h (middle
//    knot span) becomes one bicubic Bezier patch ("5 / 3 3", 16 points), converted per direction by
//    b0 = (d0 + 4 d1 + d2) / 6, b1 = (2 d1 + d2) / 3, b2 = (d1 + 2 d2) / 3, b3 = (d1 + 4 d2 + d3) / 6.
//    Exact: the same polynomial, up to round-off in the last digits.
//  * PoleCap (patch.h's Taylor cap, sector j of a pole): T(x, y) + h(u) D0(v) + R g(u) D1(v)
//    + R^2 k(u) D2(v) is a polynomial of degree 5 in u (T quadratic in r = R u, h, g, k quintics)
//    but not a polynomial in v: T, D0, D1 and D2 hold cos and sin of the angle and its double. Each
//    sector is split along v into S equal sub-sectors, each written as a "5 / 5 d" patch
//    (d = BezierViewOptions::capAngularDegree, default 5) that interpolates evaluatePatch at 6
//    equidistant u times d + 1 Chebyshev-Lobatto v nodes. Consequences:
//      - along u the patch is exact (interpolating a quintic by a quintic);
//      - the seam with ring L (u = 1) is exact: there the cap is the ring's cubic boundary curve,
//        which degree-d interpolation reproduces (d >= 3); its cross-seam derivatives are not
//        (they hold the angle's cos and sin): the written pieces meet the ring C2 only to the fit's
//        accuracy;
//      - the sub-sectors' radial edges (v = node 0 and node d) are exact, so neighbouring caps and
//        sub-sectors meet watertight, and every patch's row u = 0 is the pole p0 itself (a collapsed
//        edge, as on the Utah teapot's lid);
//      - only the interior of each sub-sector deviates, by the interpolation error of cos and sin,
//        O((2 pi / (n S))^(d+1)).
//    S is chosen per cap by measurement: S = 1, 2, 4, ... up to capMaxSplit, the first whose
//    deviation from evaluatePatch, measured on a 9 x (4d + 1) grid of each sub-sector, is at most
//    capTolerance times the diagonal of the patches' bounding box (default 1e-7). The measured
//    maximum is reported (BezierViewStats), so a file never claims more accuracy than it has.
//    Measured on 33 x 65 samples per sub-sector (tests/core/bezierview_export_test.cpp: caps of
//    valence 5, 6, 8, 12, globes, the mushroom and the assets; C2PS, RTS, BPS; levels 0-2): at most
//    9.9e-8 of the bounding-box diagonal (globe valence 5, BPS level 2, one piece a sector; RTS
//    9.8e-8 there), 5.2e-8 for valence 6 at level 0; C2PS's narrow sectors at level 2 stay below
//    1e-11. Valence 5 needs 2 pieces at level 0. (The C1 cap's quartic fit measured at most 6.8e-8,
//    5.1e-8 at level 2: the C2 cap's extra angular terms, from F and d2T/dr2, cost up to twice
//    that, still within the 1e-7 target.)
#pragma once

#include <array>
#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/spline/patch_extraction.h"

namespace polarview {

// A tensor-product Bezier patch of degree (degU, degV): cp[(degV + 1) * i + j], i = 0..degU along
// u, j = 0..degV along v (the row-major order of the .bv file).
struct BezierPatch {
  int degU = 3, degV = 3;
  std::vector<Point> cp;

  // Position at (u, v) in [0,1]^2 by de Casteljau's algorithm. [O(degU * degV)]
  Point evaluate(double u, double v) const;
};

struct BezierViewOptions {
  int capAngularDegree = 5;    // degree d of the cap patches along the angle (3..12)
  double capTolerance = 1e-7;  // target deviation of a cap, relative to the bounding-box diagonal
  int capMaxSplit = 64;        // the most sub-sectors a cap sector is split into
};

// What writeBezierView wrote.
struct BezierViewStats {
  std::array<size_t, 5> written{};  // Bezier patches written per PatchKind (caps: the sub-sectors)
  size_t groups = 0;                // Group lines
  size_t capSectors = 0;            // PoleCap patches of the set
  int maxCapSplit = 0;              // largest number of sub-sectors of one cap sector
  double boxDiagonal = 0.0;         // diagonal of the bounding box of the patches' control points
  double capMaxDeviation = 0.0;     // largest measured cap deviation (absolute; 0 without caps)

  size_t total() const;
  // Cap deviation relative to the bounding-box diagonal (0 when the box is a point).
  double capRelativeDeviation() const { return boxDiagonal > 0.0 ? capMaxDeviation / boxDiagonal : 0.0; }
};

// The exact bicubic Bezier form of a B-spline patch (any kind but PoleCap). [O(1)]
BezierPatch bicubicBezier(const Patch& patch);

// A PoleCap split into `split` sub-sectors along v, each interpolated by a (5, angularDegree)
// Bezier patch (rules above), in order of v. [O(split * angularDegree^2)]
std::vector<BezierPatch> approximatePoleCap(const Patch& cap, int split, int angularDegree);

// Largest distance between evaluatePatch(cap) and the sub-sector patches of approximatePoleCap on
// a samplesU x samplesV grid of each sub-sector (corners included). [O(pieces * samples)]
double poleCapDeviation(const Patch& cap, const std::vector<BezierPatch>& pieces, int samplesU, int samplesV);

// The pieces writeBezierView writes for a cap: approximatePoleCap with the coarsest split 1, 2, 4,
// ... (at most options.capMaxSplit) whose poleCapDeviation on a 9 x (4d + 1) grid is at most
// options.capTolerance * boxDiagonal; that deviation goes to *deviation. [O(split * samples)]
std::vector<BezierPatch> fitPoleCap(const Patch& cap, const BezierViewOptions& options, double boxDiagonal,
                                    double* deviation = nullptr);

// Diagonal of the bounding box of the patches' control points (B-spline points; for caps the pole
// p0 and the boundary points). [O(patches)]
double patchBoxDiagonal(const PatchSet& set);

// Throws InputError(sourceName, 0, "patch K (kind) has a non-finite control point: ...") for the first
// patch with a non-finite control point or origin: the writers refuse before writing anything. [O(patches)]
void checkFinitePatches(const PatchSet& set, const std::string& sourceName);

// Writes `set` in .bv format (rules above): one Group per (kind, level), named "regular-level-L",
// "boundary-level-L", "polar-ring-M", "pole-cap-level-L", "end-cap-level-L", ids 1, 2, ... in that
// order (kind, then level). Throws InputError(sourceName, 0, ...) before writing anything when a
// control point is not finite. [O(patches + caps * split * samples)]
BezierViewStats writeBezierView(std::ostream& out, const PatchSet& set, const BezierViewOptions& options = {},
                                const std::string& sourceName = "<patches>");

// One group of a .bv file read back: its name, colour id and patches (kinds 4 and 5).
struct BezierViewGroup {
  std::string name;
  int id = 0;
  std::vector<BezierPatch> patches;
};

// Reads the kinds 4 and 5 and Group lines of a .bv file; patches before any Group line go to a
// group with an empty name. Throws InputError(sourceName, 0, ...) on anything else or a truncated
// file. [O(file)]
std::vector<BezierViewGroup> readBezierView(std::istream& in, const std::string& sourceName = "<bv>");

}  // namespace polarview
