// RTS: radial Taylor subdivision, the stationary auxiliary scheme of
// Myles & Peters, "Bi-3 C2 Polar Subdivision", ACM TOG 28(3) 2009, Section 5.2, Definition 1, (9)-(12).
//
// The valence n stays fixed and refinement is radial only (Fig. 10): column j stays column j. The
// 1-link weights are b_{h-j}, d_{h-j} of (4) (c2ps::weightB, c2ps::weightD at integer shifts), summed
// in Fourier form in O(n). Links beyond 2 use the radial uniform cubic rules (12). Its subdivision
// matrix (13) has the dominant spectrum 1, 1/2, 1/2, 1/4, 1/4, 1/4 of Table 1.
#pragma once

#include "core/subdiv/polar_grid.h"

namespace polarview::rts {

// Paper (9): q00' = 3/4 q00 + 1/4 M. [O(n)]
Point refinePole(const PolarGrid& grid);

// Paper (10): q'_{1j} = 1/2 q00 + sum_h b_{h-j} q_{1h}; writes n points. [O(n)]
void refineLink1(const PolarGrid& grid, Point* out);

// Paper (11): q'_{2j} = 11/12 q_{1j} + 1/12 q_{2j} + sum_h d_{h-j} q_{1h}; or, when uniformFirstStep
// (paper Section 6, "one step of BPS"; docs/schemes.md, Section-6 uniform first step),
// q'_{2j} = 1/8 q00 + 3/4 q_{1j} + 1/8 q_{2j}.
// Needs links >= 2; writes n points. [O(n)]
void refineLink2(const PolarGrid& grid, Point* out, bool uniformFirstStep);

// One RTS step: links 0..K -> links 0..2K-1, valence n ((9)-(11), radial rules (12) beyond).
// Needs K >= 2. [O(K n)]
PolarGrid refineGrid(const PolarGrid& grid, bool uniformFirstStep = false);

}  // namespace polarview::rts
