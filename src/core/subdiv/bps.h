// BPS: bicubic polar subdivision (radial step, valence fixed).
// Scheme: K. Karciauskas, J. Peters, "Bicubic polar subdivision", ACM TOG 26(4) 2007; used with
// Catmull-Clark in A. Myles, K. Karciauskas, J. Peters, "Extending Catmull-Clark subdivision and
// PCCM with polar structures" / "Pairs of bi-cubic surface constructions supporting polar
// connectivity", CAGD 25(8) 2008.
//
// Where the weights come from: the 2007 paper's body could not be read. The weights below are those
// of the authors' group's public MATLAB code, file polar_subdiv.m in the GitHub repository
// Leon-Zhaohw/NumericalProjectsCollections, folder Gemotry/c2spline/c2polar_matlab/ (it credits
// Myles, Karciauskas, Peters), re-read for this implementation (docs/schemes.md, BPS):
//   beta = 5/8, alpha = beta - 1/4,
//   q00' = (1 - alpha) q00 + alpha M                        = 5/8 q00 + 3/8 M
//   q'1j = (1 - beta) q00 + sum_h gamma_{h-j} q1h,  gamma_g = (1/n)(beta - 1/2 + 5/8 c + c^2 + 1/2 c^3),
//          c = cos(2 pi g / n)
//   q'2j = 1/8 q00 + 3/4 q1j + 1/8 q2j, links beyond by the radial uniform cubic rules.
// Not verified against the 2007 paper: that these are its exact weights, and how BPS is stitched to
// a Catmull-Clark mesh. Verified by tests: sum gamma = beta (affine invariance), spectrum
// 1, 1/2, 1/2, 1/4, 1/4, 1/4, 1/8 for n >= 6 and the invariant limit point 1/2 q00 + 1/2 M.
// Note: gamma_g = (1/n)(beta + c + 1/2 cos 2g + 1/8 cos 3g); at n = 5 the cos 3g mode aliases onto
// mode 2 (its eigenvalue becomes 1/4 + 1/16 = 5/16 > 1/4); at n = 4 it aliases onto mode 1
// (1/2 + 1/16); at n = 3 onto mode 0: the weights then sum to 1 + 1/8, so BPS as published in that
// code is NOT affine invariant at valence 3 (kept as is, tested; callers should not use BPS at n = 3).
#pragma once

#include "core/subdiv/polar_grid.h"

namespace polarview::bps {

constexpr double kBeta = 5.0 / 8.0;           // 1-link weight sum
constexpr double kAlpha = kBeta - 1.0 / 4.0;  // pole's weight on M

// gamma_g = (1/n)(beta - 1/2 + 5/8 c + c^2 + 1/2 c^3), c = cos(2 pi g / n).
double weightGamma(int g, int n);

// q00' = (1 - alpha) q00 + alpha M. [O(n)]
Point refinePole(const PolarGrid& grid);

// q'1j = (1 - beta) q00 + sum_h gamma_{h-j} q1h; writes n points. [O(n)]
void refineLink1(const PolarGrid& grid, Point* out);

// q'2j = 1/8 q00 + 3/4 q1j + 1/8 q2j (BPS's 2-link is always the uniform rule). Needs links >= 2;
// writes n points. [O(n)]
void refineLink2(const PolarGrid& grid, Point* out);

// One BPS step: links 0..K -> links 0..2K-1, valence n. Needs K >= 2. [O(K n)]
PolarGrid refineGrid(const PolarGrid& grid);

}  // namespace polarview::bps
