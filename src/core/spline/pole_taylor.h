// The pole's second-order Taylor expansion (Myles & Peters 2009, (26), (32), Table 1):
//   x(x,y) = p0 + p1 x + p2 y + p3 (x^2 + y^2) + p4 (x^2 - y^2) + p5 2xy + o(x^2 + y^2),
// with (x,y) = r (cos 2 pi tau, sin 2 pi tau) in the grid's own radial unit: link i of the grid
// sits at r = i. So the same function applied to a level-m grid gives the level-m expansion
// (for C2PS p_k^m = lambda_k^m p_k, lambda = 1/2, 1/2, 1/4, 1/4, 1/4: Lemma 5).
//
// The eigencoefficients are those of Table 1's left eigenvectors normalised as its caption demands
// (w_k^T v_k = 1); docs/rings-and-pole.md, Eigencoefficients:
//   p0 = 2/3 q00 + 1/3 M, p1 = (2/n) sum c_{j/n} q1j, p2 = (2/n) sum s_{j/n} q1j,
//   p3 = M - q00,        p4 = (3/n) sum c_{2j/n} q1j, p5 = (3/n) sum s_{2j/n} q1j.
// The printed (27) has p3 = 2/3 (M - q00) and p4, p5 with 1/n: misprints (tests show (34), (35)
// and the curvature fail with them; docs/misprints.md, (27)).
#pragma once

#include <array>

#include "core/subdiv/polar_grid.h"
#include "core/subdiv/scheme.h"

namespace polarview {

struct TaylorCoefficients {
  std::array<Point, 6> p{};  // p0..p5 of (32)
  int order = 2;             // 2: full quadratic (C2PS, RTS); 1: limit point and tangent plane only (BPS)
};

// Eigencoefficients of a polar grid (needs links >= 1, n >= 3). C2PS and RTS: Table 1
// (docs/rings-and-pole.md, Eigencoefficients), order 2. BPS: limit point 1/2 q00 + 1/2 M and p1, p2
// as above, p3..p5 = 0, order 1.
// Catmull-Clark has no such expansion: throws std::logic_error. [O(n)]
TaylorCoefficients poleTaylorCoefficients(const PolarGrid& grid, Scheme scheme);

// Position and partial derivatives of the expansion (32) at (x,y).
struct TaylorJet {
  Point position{}, xx{}, yy{}, xy{}, x{}, y{};
};

// Evaluates (32) (the quadratic terms only when order == 2). [O(1)]
TaylorJet evaluateTaylor(const TaylorCoefficients& t, double x, double y);

// Limit point, unit normal (along p1 x p2) and curvatures at the pole.
struct PoleDifferential {
  Point limit{}, normal{};
  double gaussian = 0.0;  // K
  double mean = 0.0;      // H, positive where the surface bends towards the normal
  bool curvatureDefined = false;
};

// Differential geometry at the pole from x_x = p1, x_y = p2, x_xx = 2(p3+p4), x_yy = 2(p3-p4),
// x_xy = 2 p5 (formulas: docs/rings-and-pole.md, Curvature at the pole). Order 1, or a degenerate
// tangent plane (p1 x p2 = 0, normal left zero): curvatureDefined = false and K = H = 0. Computed
// on p1..p5 scaled exactly to unit size; a K or H beyond a double (a model 1e-200 across) is left
// undefined (curvatureDefined = false, K = H = 0). [O(1)]
PoleDifferential analyzePole(const TaylorCoefficients& t);

}  // namespace polarview
