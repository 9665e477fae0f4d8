// Spline rings straight from a PolarGrid (Myles & Peters 2009, Section 5.1, (6)-(8)): the grid-based
// twin of feature-adaptive extraction, used to analyse a scheme ring by ring without a mesh.
#pragma once

#include <vector>

#include "core/spline/patch.h"
#include "core/subdiv/polar_grid.h"

namespace polarview {

// Ring m of paper (6): the 2 x n bicubic PolarRing patches between links 2-3 (row 0, control rows
// links 1..4) and links 3-4 (row 1, links 2..5); patch [row * n + j] uses columns j-1..j+2, u runs
// radially outwards and v periodically, so x_u x x_v is the outward normal. Needs grid.links >= 5.
// Patches get ring = level = m, pole = 0. [O(n)]
std::vector<Patch> splineRing(const PolarGrid& grid, int m);

}  // namespace polarview
