// Curvature ring by ring towards a pole (Myles & Peters 2009, Theorem 1 and Section 5.2): the
// measurement behind the paper's claim. C2PS's spline rings (6) take on the Taylor expansion's
// (32) K and H as m grows (about /2.5 a level); RTS's keep an angle-dependent K for finite n.
#pragma once

#include <vector>

#include "core/subdiv/polar_grid.h"
#include "core/subdiv/scheme.h"

namespace polarview {

struct RingCurvature {
  int m = 0;                     // level: ring m of paper (6), r in [2, 4] 2^-m in level 0's radial unit
  int valence = 0;               // columns of level m (C2PS doubles them, RTS and BPS keep n)
  double minK = 0.0, maxK = 0.0;  // over the samples of the ring
  double minH = 0.0, maxH = 0.0;  // H with the pole normal's orientation
  double maxAbsDeltaK = 0.0;     // max |K - poleK| (NaN when poleK is NaN)
  double maxAbsDeltaH = 0.0;     // max |H - poleH| (NaN when poleH is NaN)
  // K on the ring's middle circle (r = 3 2^-m, link 3) at angleSamples uniform angles k / angleSamples
  // of a turn from column 0 (empty unless asked for): a C2 scheme's flattens as m grows, RTS's keeps
  // its n-fold wave.
  std::vector<double> kAlongAngle;
};

// Refines `grid` (a pole's links 0..K, K >= 2, in level 0's radial unit) `rings` times with
// `scheme` (C2PS, RTS or BPS; `uniformFirstStep`: the Section-6 first step) and samples each spline
// ring m = 1..rings on samples x samples points of every patch; H is oriented by `poleNormal`.
// Only links 0..5 are carried from level to level (all a ring needs). With angleSamples > 0 each
// ring also gets kAlongAngle. [O(rings * (n_rings * samples^2 + angleSamples))]
std::vector<RingCurvature> ringCurvatures(PolarGrid grid, Scheme scheme, bool uniformFirstStep, int rings, double poleK,
                                          double poleH, const Point& poleNormal, int samples = 5, int angleSamples = 0);

}  // namespace polarview
