// Helpers shared by the polar-scheme tests (c2ps_test, rts_test, bps_test, pole_taylor_test):
// random polar grids, the uniform cubic B-spline, the dense subdivision matrix (13) of a
// valence-preserving scheme, its Fourier blocks, and a small complex eigenvalue solver.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "core/mesh/constants.h"
#include "core/subdiv/polar_grid.h"
#include "core/subdiv/spectrum.h"

namespace polarview::test {

inline double distance(const Point& a, const Point& b) { return glm::length(a - b); }

// A polar grid with every point uniform in [-1,1]^3 (deterministic per seed).
inline PolarGrid randomGrid(int n, int links, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PolarGrid g(n, links);
  g.pole = Point(u(rng), u(rng), u(rng));
  for (Point& p : g.ring) p = Point(u(rng), u(rng), u(rng));
  return g;
}

// The same grid with every point passed through f (pole included).
inline PolarGrid mapGrid(const PolarGrid& g, const std::function<Point(const Point&)>& f) {
  PolarGrid out = g;
  out.pole = f(g.pole);
  for (Point& p : out.ring) p = f(p);
  return out;
}

// Columns rotated by `shift`: out.q(i, j) = g.q(i, j - shift).
inline PolarGrid rotateColumns(const PolarGrid& g, int shift) {
  PolarGrid out = g;
  for (int i = 1; i <= g.links; ++i)
    for (int j = 0; j < g.n; ++j) out.q(i, j) = g.q(i, j - shift);
  return out;
}

// Links 0..keep of g (the polar rules for new links 0..2 only read old links 0..2).
inline PolarGrid keepLinks(const PolarGrid& g, int keep) {
  PolarGrid out(g.n, keep);
  out.pole = g.pole;
  std::copy(g.ring.begin(), g.ring.begin() + size_t(keep) * g.n, out.ring.begin());
  return out;
}

// Largest distance between corresponding points (pole included); grids must have equal shape.
inline double maxGridDistance(const PolarGrid& a, const PolarGrid& b) {
  double d = distance(a.pole, b.pole);
  for (size_t k = 0; k < a.ring.size(); ++k) d = std::max(d, distance(a.ring[k], b.ring[k]));
  return d;
}

// Uniform cubic B-spline basis on one knot span, t in [0,1].
inline std::array<double, 4> cubicBasis(double t) {
  double s = 1.0 - t;
  return {s * s * s / 6.0, (3 * t * t * t - 6 * t * t + 4) / 6.0, (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6.0,
          t * t * t / 6.0};
}

// The tensor-product spline of links first..last of g (radial control point i at r = i * spacing,
// periodic column j at tau = j/n), evaluated at (r, tau). r must lie where four links exist.
inline Point evaluateRingSpline(const PolarGrid& g, int first, double spacing, double r, double tau) {
  double radial = r / spacing;  // in link units
  int i0 = int(std::floor(radial)) - 1;
  if (radial - std::floor(radial) == 0.0 && i0 + 3 > g.links) --i0;  // right end of the range
  double t = radial - (i0 + 1);
  double periodic = tau * g.n;
  int j0 = int(std::floor(periodic)) - 1;
  double s = periodic - (j0 + 1);
  auto br = cubicBasis(t), bt = cubicBasis(s);
  Point x{0.0};
  for (int a = 0; a < 4; ++a) {
    int i = i0 + a;
    if (i < first || i > g.links) throw std::out_of_range("evaluateRingSpline: link outside the grid");
    for (int b = 0; b < 4; ++b) x += br[a] * bt[b] * g.q(i, j0 + b);
  }
  return x;
}

// Largest distance between the spline ring of links 1..K of `coarse` (spacing 1) and that of the new
// links 3..2K-1 of `fine` (spacing 1/2), sampled over r in [2, K-1] where both are defined. Zero when
// the rules beyond the 2-link are exact knot insertion ((12), (29)).
inline double outerRingDefect(const PolarGrid& coarse, const PolarGrid& fine) {
  double worst = 0.0;
  const int samples = 30;
  for (int s = 0; s <= samples; ++s)
    for (double tau : {0.0, 0.07, 0.31, 0.5, 0.93}) {
      double r = 2.0 + (coarse.links - 3.0) * s / samples;
      worst = std::max(worst, distance(evaluateRingSpline(coarse, 1, 1.0, r, tau), evaluateRingSpline(fine, 3, 0.5, r, tau)));
    }
  return worst;
}

using Refine = std::function<PolarGrid(const PolarGrid&)>;

// Affine invariance: |refine(f(g)) - f(refine(g))| for a fixed general affine map f. Zero iff every
// rule's weights sum to one (f has a translation and a non-orthogonal linear part).
inline double affineDefect(const Refine& refine, const PolarGrid& g) {
  auto f = [](const Point& p) {
    return Point(0.3 * p.x - 1.2 * p.y + 0.5 * p.z + 4.0, 2.0 * p.x + 0.1 * p.z - 3.0, -p.x + 0.7 * p.y + 1.5 * p.z + 0.25);
  };
  return maxGridDistance(refine(mapGrid(g, f)), mapGrid(refine(g), f));
}

// Cyclic symmetry: |refine(rotate(g, 1)) - rotate(refine(g), outputShift)|.
inline double rotationDefect(const Refine& refine, const PolarGrid& g, int outputShift) {
  return maxGridDistance(refine(rotateColumns(g, 1)), rotateColumns(refine(g), outputShift));
}

// Plane reproduction: the largest distance from a fixed plane of the refined points of a random
// control net lying on that plane.
inline double planeDefect(const Refine& refine, int n, int links, unsigned seed) {
  Point origin(0.4, -1.0, 2.0), u = glm::normalize(Point(1.0, 2.0, -0.5)), v = glm::normalize(Point(-0.3, 0.2, 1.0));
  Point normal = glm::normalize(glm::cross(u, v));
  PolarGrid fine = refine(mapGrid(randomGrid(n, links, seed), [&](const Point& p) { return origin + 3.0 * p.x * u + 2.0 * p.y * v; }));
  double offPlane = std::abs(glm::dot(fine.pole - origin, normal));
  for (const Point& p : fine.ring) offPlane = std::max(offPlane, std::abs(glm::dot(p - origin, normal)));
  return offPlane;
}

// The matrix (13), its Fourier blocks and eigenvalues live in core/subdiv/spectrum.h (the `spectrum`
// command uses them too); these names keep the tests short.
using polarview::Complex;
using polarview::ComplexMatrix;
using polarview::eigenvalues;
using polarview::fourierBlock;
using polarview::Matrix;
using polarview::spectrumByFourierBlocks;
using polarview::TaggedEigenvalue;
inline int matrixIndex(int link, int column) { return polarMatrixIndex(link, column); }
inline Matrix subdivisionMatrix(int n, const Refine& refine) { return polarSubdivisionMatrix(n, refine); }

// Largest |A_{jh} - A_{0,(h-j) mod n}|: zero for a block-circulant matrix.
inline double blockCirculantDefect(const Matrix& a, int n) {
  double defect = 0.0;
  for (int j = 0; j < n; ++j)
    for (int h = 0; h < n; ++h)
      for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c)
          defect = std::max(defect, std::abs(a[matrixIndex(r, j)][matrixIndex(c, h)] -
                                             a[matrixIndex(r, 0)][matrixIndex(c, ((h - j) % n + n) % n)]));
  return defect;
}

// Dense products used to check eigenvector identities.
inline std::vector<double> multiply(const Matrix& a, const std::vector<double>& v) {
  std::vector<double> out(a.size(), 0.0);
  for (size_t r = 0; r < a.size(); ++r)
    for (size_t c = 0; c < v.size(); ++c) out[r] += a[r][c] * v[c];
  return out;
}
inline std::vector<double> multiplyLeft(const std::vector<double>& w, const Matrix& a) {
  std::vector<double> out(a[0].size(), 0.0);
  for (size_t r = 0; r < a.size(); ++r)
    for (size_t c = 0; c < out.size(); ++c) out[c] += w[r] * a[r][c];
  return out;
}
inline double dotProduct(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (size_t k = 0; k < a.size(); ++k) s += a[k] * b[k];
  return s;
}
inline double maxAbsDifference(const std::vector<double>& a, const std::vector<double>& b, double scale = 1.0) {
  double d = 0.0;
  for (size_t k = 0; k < a.size(); ++k) d = std::max(d, std::abs(a[k] - scale * b[k]));
  return d;
}

}  // namespace polarview::test
