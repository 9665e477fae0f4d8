// Pieces shared by the polar schemes (C2PS, RTS, BPS; see c2ps.h, rts.h, bps.h):
//  * the uniform cubic B-spline rules, periodically along one link (paper (5)) and radially across
//    links ((12), (29));
//  * the discrete Fourier sums of a link. The valence-dependent weights b_g, d_g (paper (4)) and
//    gamma_g (BPS) hold only Fourier modes 0..3, so every sum over the 1-link collapses to a few
//    sums computed once: O(n) per link instead of O(n^2) (docs/schemes.md, O(n) evaluation).
// A link is n points q_{i,0..n-1} stored contiguously, index j taken modulo n.
#pragma once

#include <array>

#include "core/mesh/poly_mesh.h"

namespace polarview {

// The highest Fourier mode any polar weight uses (BPS's gamma_g has cos^3).
constexpr int kMaxLinkFrequency = 3;

// Fourier sums of one link q_0..q_{n-1}:
//   mean = M = (1/n) sum_h q_h,
//   cosSum[a] = (1/n) sum_h cos(2 pi a h / n) q_h,  sinSum[a] = (1/n) sum_h sin(2 pi a h / n) q_h,
// for a = 1..maxFrequency (entry 0 unused; modes above maxFrequency are left zero).
// The paper's symbols: C1 = cosSum[1], S1 = sinSum[1], C2 = cosSum[2], S2 = sinSum[2].
struct LinkFourierSums {
  Point mean{};
  std::array<Point, kMaxLinkFrequency + 1> cosSum{};
  std::array<Point, kMaxLinkFrequency + 1> sinSum{};

  // sum over modes a >= 1 of weight[a] (cosSum[a] cos(2 pi a tau) + sinSum[a] sin(2 pi a tau)), given
  // unit = (cos 2 pi tau, sin 2 pi tau). This is (1/n) sum_h K(h/n - tau) q_h for the even kernel
  // K(t) = sum_a weight[a] cos(2 pi a t): the non-constant part of every polar 1-link rule. [O(1)]
  Point trigonometricPart(const std::array<double, kMaxLinkFrequency + 1>& weight,
                          const std::array<double, 2>& unit) const;
};

// Paper (1) = (9): the polar vertex moves to 3/4 q00 + 1/4 M (C2PS and RTS alike). [O(n)]
Point polarVertexRule(const Point& pole, const Point* link1, int n);

// M = (1/n) sum_h q_h. [O(n)]
Point linkMean(const Point* link, int n);

// The Fourier sums of a link up to mode maxFrequency (1..kMaxLinkFrequency). [O(n)]
LinkFourierSums linkFourierSums(const Point* link, int n, int maxFrequency = 2);

// Paper (4) in Fourier form (shared by C2PS and RTS): n b_g = 1/2 + cos(2 pi g/n) + 1/2 cos(4 pi g/n)
// and n d_g = -1/6 cos(2 pi g/n); the mode-0 weights (1/2 and 0) are applied to the mean separately.
constexpr std::array<double, kMaxLinkFrequency + 1> kWeightBModes{0.0, 1.0, 0.5, 0.0};
constexpr std::array<double, kMaxLinkFrequency + 1> kWeightDModes{0.0, -1.0 / 6.0, 0.0, 0.0};

// (cos, sin) of 2 pi k / m with k reduced modulo m first, so large k loses no accuracy.
std::array<double, 2> unitCircle(long long k, long long m);

// Paper (5): periodic uniform cubic refinement of one link, n points -> 2n points:
// out[2j] = 1/8 q_{j-1} + 3/4 q_j + 1/8 q_{j+1}, out[2j+1] = 1/2 (q_j + q_{j+1}). [O(n)]
void refinePeriodicLink(const Point* link, int n, Point* out);

// Uniform cubic rules across links (radial direction, (12), (29)): the new even point between
// three old ones and the new odd point between two.
inline Point radialEvenRule(const Point& before, const Point& at, const Point& after) {
  return 0.125 * before + 0.75 * at + 0.125 * after;
}
inline Point radialOddRule(const Point& at, const Point& after) { return 0.5 * (at + after); }

// New links 3..2K-1 from old links 1..K by the radial uniform cubic rules:
// new 2i+1 = 1/2 (q_i + q_{i+1}) (i >= 1), new 2i = 1/8 q_{i-1} + 3/4 q_i + 1/8 q_{i+1} (i >= 2).
// `links` holds old links 1..K, `width` points each; `out` receives new links 3..2K-1 in the same
// layout (2K-3 links). C2PS passes periodically refined links (width 2n), RTS/BPS the links
// themselves (width n). Needs K >= 2. [O(K width)]
void refineOuterLinksRadially(const Point* links, int width, int linkCount, Point* out);

}  // namespace polarview
