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

#include "core/subdiv/polar_grid.h"

namespace polarview::test {

constexpr double kPi = 3.14159265358979323846264338327950288;

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

// ---------------------------------------------------------------------------------------------
// Subdivision matrix (13) of a valence-preserving polar scheme on links 0..5, the pole listed once
// per column (q_{0j} = q00), unknowns ordered q = [q_{0,0}, .., q_{5,0}, q_{0,1}, .., q_{5,n-1}].
// Column (h, c) is the scheme applied to the unit input at q_{c,h}; the pole's column is split
// evenly among its n copies, as in (13).
using Matrix = std::vector<std::vector<double>>;

inline int matrixIndex(int link, int column) { return 6 * column + link; }

inline Matrix subdivisionMatrix(int n, const Refine& refine) {
  Matrix a(6 * n, std::vector<double>(6 * n, 0.0));
  for (int h = 0; h < n; ++h)
    for (int c = 0; c < 6; ++c) {
      PolarGrid unit(n, 5);
      double share = 1.0;
      if (c == 0) {
        unit.pole = Point(1.0);
        share = 1.0 / n;
      } else {
        unit.q(c, h) = Point(1.0);
      }
      PolarGrid fine = refine(unit);
      for (int j = 0; j < n; ++j) {
        a[matrixIndex(0, j)][matrixIndex(c, h)] = share * fine.pole.x;
        for (int i = 1; i < 6; ++i) a[matrixIndex(i, j)][matrixIndex(c, h)] = share * fine.q(i, j).x;
      }
    }
  return a;
}

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

using Complex = std::complex<double>;
using ComplexMatrix = std::vector<std::vector<Complex>>;

// Fourier block hat A_alpha = sum_h omega^{h alpha} A_{0h}: A maps v_h = v^ omega^{h alpha} to
// (hat A_alpha v^) omega^{j alpha} when A is block circulant, so the blocks' spectra make A's.
inline ComplexMatrix fourierBlock(const Matrix& a, int n, int alpha) {
  ComplexMatrix block(6, std::vector<Complex>(6, 0.0));
  for (int h = 0; h < n; ++h) {
    Complex omega = std::polar(1.0, 2.0 * kPi * double((long long)h * alpha % n) / n);
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) block[r][c] += omega * a[matrixIndex(r, 0)][matrixIndex(c, h)];
  }
  return block;
}

// Eigenvalues of a small complex matrix: Householder reduction to Hessenberg form, then QR steps
// with Wilkinson shifts and deflation.
inline std::vector<Complex> eigenvalues(ComplexMatrix h) {
  const int size = int(h.size());
  double norm = 0.0;
  for (auto& row : h)
    for (auto& x : row) norm = std::max(norm, std::abs(x));
  // Hessenberg reduction.
  for (int k = 0; k + 2 < size; ++k) {
    std::vector<Complex> v(size, 0.0);
    double alpha = 0.0;
    for (int i = k + 1; i < size; ++i) alpha += std::norm(h[i][k]);
    alpha = std::sqrt(alpha);
    if (alpha == 0.0) continue;
    Complex phase = std::abs(h[k + 1][k]) > 0.0 ? h[k + 1][k] / std::abs(h[k + 1][k]) : Complex(1.0);
    for (int i = k + 1; i < size; ++i) v[i] = h[i][k];
    v[k + 1] += phase * alpha;
    double vv = 0.0;
    for (int i = k + 1; i < size; ++i) vv += std::norm(v[i]);
    if (vv == 0.0) continue;
    // H <- (I - 2 v v*/v*v) H (I - 2 v v*/v*v)
    for (int c = 0; c < size; ++c) {
      Complex s = 0.0;
      for (int i = k + 1; i < size; ++i) s += std::conj(v[i]) * h[i][c];
      s *= 2.0 / vv;
      for (int i = k + 1; i < size; ++i) h[i][c] -= v[i] * s;
    }
    for (int r = 0; r < size; ++r) {
      Complex s = 0.0;
      for (int i = k + 1; i < size; ++i) s += h[r][i] * v[i];
      s *= 2.0 / vv;
      for (int i = k + 1; i < size; ++i) h[r][i] -= s * std::conj(v[i]);
    }
  }
  // Shifted QR on the active leading block 0..m-1.
  std::vector<Complex> result;
  const double eps = 1e-15;
  int m = size, iterations = 0;
  while (m > 0) {
    if (m == 1) {
      result.push_back(h[0][0]);
      break;
    }
    double sub = std::abs(h[m - 1][m - 2]);
    if (sub <= eps * (std::abs(h[m - 1][m - 1]) + std::abs(h[m - 2][m - 2])) || sub <= eps * norm * 1e-3) {
      result.push_back(h[m - 1][m - 1]);
      --m;
      iterations = 0;
      continue;
    }
    if (++iterations > 1000) throw std::runtime_error("eigenvalues: QR did not converge");
    // Wilkinson shift from the trailing 2x2 block (an exceptional shift now and then).
    Complex a = h[m - 2][m - 2], b = h[m - 2][m - 1], c = h[m - 1][m - 2], d = h[m - 1][m - 1];
    Complex tr = a + d, det = a * d - b * c;
    Complex root = std::sqrt(tr * tr / 4.0 - det);
    Complex mu1 = tr / 2.0 + root, mu2 = tr / 2.0 - root;
    Complex shift = std::abs(mu1 - d) < std::abs(mu2 - d) ? mu1 : mu2;
    if (iterations % 11 == 10) shift = d + Complex(0.75 * sub, 0.25 * sub);
    for (int i = 0; i < m; ++i) h[i][i] -= shift;
    std::vector<Complex> cs(m), sn(m);
    for (int k = 0; k + 1 < m; ++k) {  // H = Q R by Givens rotations
      Complex x = h[k][k], y = h[k + 1][k];
      double r = std::sqrt(std::norm(x) + std::norm(y));
      if (r == 0.0) {
        cs[k] = 1.0;
        sn[k] = 0.0;
        continue;
      }
      cs[k] = x / r;
      sn[k] = y / r;
      for (int col = k; col < m; ++col) {
        Complex top = h[k][col], bottom = h[k + 1][col];
        h[k][col] = std::conj(cs[k]) * top + std::conj(sn[k]) * bottom;
        h[k + 1][col] = -sn[k] * top + cs[k] * bottom;
      }
    }
    for (int k = 0; k + 1 < m; ++k) {  // H = R Q
      for (int row = 0; row <= std::min(k + 1, m - 1); ++row) {
        Complex left = h[row][k], right = h[row][k + 1];
        h[row][k] = left * cs[k] + right * sn[k];
        h[row][k + 1] = -left * std::conj(sn[k]) + right * std::conj(cs[k]);
      }
    }
    for (int i = 0; i < m; ++i) h[i][i] += shift;
  }
  return result;
}

// All eigenvalues of a block-circulant (13) matrix via its n Fourier blocks, tagged by block,
// sorted by decreasing modulus.
struct TaggedEigenvalue {
  Complex value;
  int alpha;
};
inline std::vector<TaggedEigenvalue> spectrumByFourierBlocks(const Matrix& a, int n) {
  std::vector<TaggedEigenvalue> all;
  for (int alpha = 0; alpha < n; ++alpha)
    for (Complex z : eigenvalues(fourierBlock(a, n, alpha))) all.push_back({z, alpha});
  std::stable_sort(all.begin(), all.end(),
                   [](const TaggedEigenvalue& x, const TaggedEigenvalue& y) { return std::abs(x.value) > std::abs(y.value); });
  return all;
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
