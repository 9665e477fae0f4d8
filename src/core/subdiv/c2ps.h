// C2PS: bi-3 C2 polar subdivision.
// Myles & Peters, "Bi-3 C2 Polar Subdivision", ACM TOG 28(3) (SIGGRAPH 2009), Section 3,
// rules (1)-(5) and (29); the Section-6 variant (uniform 2-link in the first step) as read in
// docs/schemes.md, Section-6 uniform first step.
//
// One step maps a polar configuration of valence n to one of valence 2n: new column k = 0..2n-1
// sits at angle k/(2n) turns (old column j is new column 2j). The 1-link weights b_g, d_g of (4)
// are evaluated at the half-integer shift g = h - k/2 (reading it as h - k breaks Lemma 5) and
// summed in their Fourier form (docs/schemes.md, O(n) evaluation), so every rule is O(n).
#pragma once

#include "core/subdiv/polar_grid.h"

namespace polarview::c2ps {

// Paper (4): b_g = (1/n)(1/2 + cos(2 pi g/n) + 1/2 cos(4 pi g/n)), g may be a half-integer.
double weightB(double g, int n);
// Paper (4): d_g = -cos(2 pi g/n) / (6n).
double weightD(double g, int n);

// Paper (1): q00' = 3/4 q00 + 1/4 M. [O(n)]
Point refinePole(const PolarGrid& grid);

// Paper (2): q'_{1k} = 1/2 q00 + sum_h b_{h-k/2} q_{1h}, k = 0..2n-1; writes 2n points. [O(n)]
void refineLink1(const PolarGrid& grid, Point* out);

// Paper (3): q'_{2k} = 11/12 q~_{1k} + 1/12 q~_{2k} + sum_h d_{h-k/2} q_{1h}; or, when
// uniformFirstStep (paper Section 6; docs/schemes.md, Section-6 uniform first step),
// q'_{2k} = 1/8 q00 + 3/4 q~_{1k} + 1/8 q~_{2k}.
// q~ are links refined periodically by (5). Needs links >= 2; writes 2n points. [O(n)]
void refineLink2(const PolarGrid& grid, Point* out, bool uniformFirstStep);

// One C2PS step: links 0..K of valence n -> links 0..2K-1 of valence 2n (rules (1)-(3), and (29)
// with (5) beyond link 2). Needs K >= 2. [O(K n)]
PolarGrid refineGrid(const PolarGrid& grid, bool uniformFirstStep = false);

}  // namespace polarview::c2ps
