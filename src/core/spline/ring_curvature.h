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
  // K along spokes (empty unless asked for): spoke s at s / spokes of a turn from column 0, sampled
  // from the ring's outer edge (link 4) inwards to its inner edge (link 2), 17 points. Joined ring
  // after ring they are K(r) towards the pole; spokeSignChanges counts where dK/dr turns.
  std::vector<std::vector<double>> kAlongSpokes;
  int spokeSignChanges = 0;  // sign changes of dK/dr along this ring's spokes, summed over them
};

// Sign changes of dK/dr along the spokes of `rings` (ring 1 outermost), each spoke joined from ring
// to ring and ended by `poleK` (a monotone radial curvature profile: 0), summed over the spokes;
// steps under 1e-9 of the largest |K| count as flat. NaN poleK: the rings only.
int spokeSignChanges(const std::vector<RingCurvature>& rings, double poleK);

// Refines `grid` (a pole's links 0..K, K >= 2, in level 0's radial unit) `rings` times with
// `scheme` (C2PS, RTS or BPS; `uniformFirstStep`: the Section-6 first step) and samples each spline
// ring m = 1..rings on samples x samples points of every patch; H is oriented by `poleNormal`.
// Only links 0..5 are carried from level to level (all a ring needs). With angleSamples > 0 each
// ring also gets kAlongAngle, with spokes > 0 kAlongSpokes and spokeSignChanges.
// [O(rings * (n_rings * samples^2 + angleSamples + spokes))]
std::vector<RingCurvature> ringCurvatures(PolarGrid grid, Scheme scheme, bool uniformFirstStep, int rings, double poleK,
                                          double poleH, const Point& poleNormal, int samples = 5, int angleSamples = 0,
                                          int spokes = 0);

}  // namespace polarview
