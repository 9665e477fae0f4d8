// The limit surface as tensor-product B-spline surfaces, the geometry the CAD writers (STEP,
// IGES) put in their files (docs/formats.md, STEP and IGES).
//
// Each surface is a clamped polynomial B-spline of one span: degree (degU, degV), knots 0 and 1
// each of multiplicity deg + 1, i.e. a Bezier patch in B-spline form.
//  * Regular, Boundary, PolarRing, EndCap patches: bicubicBezier (core/spline/bezierview_export.h),
//    exact: the same polynomial as evaluatePatch up to round-off.
//  * PoleCap sectors: fitPoleCap's (5, d) pieces, within 1e-7 of the bounding-box diagonal; each
//    piece covers v in [piece, piece + 1] / pieces of its sector, and its row u = 0 is the pole
//    (a collapsed edge).
// Parameters: u along the rows of BezierPatch::cp, v along its columns, so du x dv is
// evaluatePatch's normal direction (outwards on a counter-clockwise mesh).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/spline/bezierview_export.h"
#include "core/spline/patch_extraction.h"

namespace polarview {

struct CadSurface {
  BezierPatch bezier;  // control points, absolute coordinates
  PatchKind kind = PatchKind::Regular;
  int level = 0;
  int ring = -1;      // polar ring index (PolarRing, PoleCap), -1 otherwise
  size_t patch = 0;   // index of the patch in the PatchSet
  int piece = 0;      // cap pieces: which sub-sector of its cap sector, of `pieces`
  int pieces = 1;

  // Whether the edge u = 0 collapses to a point (the pole of a cap piece).
  bool collapsedAtU0() const { return kind == PatchKind::PoleCap; }
};

struct CadSurfaceSet {
  std::vector<CadSurface> surfaces;  // in the PatchSet's order, cap pieces in order of v
  std::array<size_t, 5> written{};   // surfaces per PatchKind (caps: the pieces)
  size_t capSectors = 0;
  double boxDiagonal = 0.0;      // patchBoxDiagonal of the set
  double capMaxDeviation = 0.0;  // largest measured cap deviation (absolute; 0 without caps)
  Point boxMin{0.0}, boxMax{0.0};  // bounding box of the surfaces' control points

  double capRelativeDeviation() const { return boxDiagonal > 0.0 ? capMaxDeviation / boxDiagonal : 0.0; }
};

// The surfaces of `set` (rules above). Throws InputError(sourceName, 0, ...) when a control point
// is not finite, before anything is made. [O(patches + caps * split * samples)]
CadSurfaceSet cadSurfaces(const PatchSet& set, const std::string& sourceName);

// The knot vector a writer states for a surface of degree `degree`: 0 and 1, each deg + 1 times.
std::vector<double> clampedBezierKnots(int degree);

// Position and first and second derivatives of a surface at (u, v) in [0,1]^2, by de Boor's
// algorithm on clampedBezierKnots (an evaluation of the B-spline the files state, independent of
// de Casteljau). [O(degU * degV^2)]
struct CadSurfaceDerivatives {
  Point position{}, du{}, dv{}, duu{}, duv{}, dvv{};
};
CadSurfaceDerivatives evaluateCadSurface(const CadSurface& surface, double u, double v);

// The cap parameter of a piece's (u, v): the sector's v. [O(1)]
inline double sectorV(const CadSurface& surface, double v) { return (surface.piece + v) / surface.pieces; }

// Shortest text that reads back as exactly `value` ("0.1", "1e-07"), by std::to_chars.
std::string shortestDouble(double value);
// shortestDouble as a CAD file's real: always a decimal point, the exponent after `exponentLetter`
// ('E' in STEP: "1.E-07"; 'D' in IGES: "1.D-07"). [O(1)]
std::string cadReal(double value, char exponentLetter);

}  // namespace polarview
