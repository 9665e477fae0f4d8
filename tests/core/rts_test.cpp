// RTS (Myles & Peters 2009, Definition 1, (9)-(13), Table 1): rules against their direct sums,
// affine invariance, symmetry, planes, and the spectrum and eigenvectors of its matrix (13).
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "core/subdiv/bps.h"
#include "core/subdiv/c2ps.h"
#include "core/subdiv/rts.h"
#include "polar_test_support.h"

using namespace polarview;
using namespace polarview::test;

namespace {

// Direct O(n^2) sums of (9)-(11), the reference the O(n) Fourier form must match.
PolarGrid refineDirectly(const PolarGrid& g) {
  int n = g.n;
  PolarGrid fine(n, 3);
  Point mean{0.0};
  for (int h = 0; h < n; ++h) mean += g.q(1, h);
  fine.pole = 0.75 * g.pole + 0.25 * mean / double(n);
  for (int j = 0; j < n; ++j) {
    Point link1 = 0.5 * g.pole, link2 = (11.0 / 12.0) * g.q(1, j) + (1.0 / 12.0) * g.q(2, j);
    for (int h = 0; h < n; ++h) {
      link1 += c2ps::weightB(h - j, n) * g.q(1, h);
      link2 += c2ps::weightD(h - j, n) * g.q(1, h);
    }
    fine.q(1, j) = link1;
    fine.q(2, j) = link2;
    fine.q(3, j) = 0.5 * (g.q(1, j) + g.q(2, j));
  }
  return fine;
}

// Table 1 (and (14)): radial parts and periodic factors of the six dominant eigenvectors.
const double kRightRadial[6][6] = {{1, 1, 1, 1, 1, 1},
                                   {0, 1, 2, 3, 4, 5},
                                   {0, 1, 2, 3, 4, 5},
                                   {-1.0 / 3, 2.0 / 3, 11.0 / 3, 26.0 / 3, 47.0 / 3, 74.0 / 3},
                                   {0, 2.0 / 3, 11.0 / 3, 26.0 / 3, 47.0 / 3, 74.0 / 3},
                                   {0, 2.0 / 3, 11.0 / 3, 26.0 / 3, 47.0 / 3, 74.0 / 3}};
// Left radial parts normalised so that w_k^T v_k = 1 (Table 1's caption; docs/misprints.md, (27)).
const double kLeftRadial[6][6] = {{2.0 / 3, 1.0 / 3, 0, 0, 0, 0}, {0, 2, 0, 0, 0, 0}, {0, 2, 0, 0, 0, 0},
                                  {-1, 1, 0, 0, 0, 0},           {0, 3, 0, 0, 0, 0}, {0, 3, 0, 0, 0, 0}};
// The same rows as printed in the paper's (27): p3 with beta = 2/3, p4 and p5 with 1/n.
const double kPrintedLeftRadial[6][6] = {{2.0 / 3, 1.0 / 3, 0, 0, 0, 0}, {0, 2, 0, 0, 0, 0}, {0, 2, 0, 0, 0, 0},
                                         {-2.0 / 3, 2.0 / 3, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0}};
const double kLambda[6] = {1.0, 0.5, 0.5, 0.25, 0.25, 0.25};

// op_k(j/n) of (14): 1, c, s, 1, c2, s2.
double periodicFactor(int k, int j, int n) {
  double t = 2.0 * kPi * j / n;
  switch (k) {
    case 1: return std::cos(t);
    case 2: return std::sin(t);
    case 4: return std::cos(2 * t);
    case 5: return std::sin(2 * t);
    default: return 1.0;
  }
}

// (14): (v_k)_{ij} = (v^_k)_i op_k(j/n); (26): (w_k)_{ij} = (1/n)(w^_k)_i op_k(j/n).
std::vector<double> fullVector(const double radial[6], int k, int n, double scale) {
  std::vector<double> v(6 * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < 6; ++i) v[matrixIndex(i, j)] = scale * radial[i] * periodicFactor(k, j, n);
  return v;
}

Refine rtsStep(bool uniformFirstStep = false) {
  return [uniformFirstStep](const PolarGrid& g) { return rts::refineGrid(g, uniformFirstStep); };
}

}  // namespace

TEST_CASE("rts: the O(n) Fourier form of (9)-(11) equals the direct sums with b_{h-j}, d_{h-j}") {
  for (int n = 3; n <= 40; ++n) {
    PolarGrid g = randomGrid(n, 2, 100 + n);
    PolarGrid direct = refineDirectly(g);
    PolarGrid fine = rts::refineGrid(g);
    REQUIRE(fine.n == n);
    REQUIRE(fine.links == 3);
    CHECK(maxGridDistance(fine, direct) < 1e-13);

    // The single-rule entry points agree with the grid step.
    std::vector<Point> link1(n), link2(n);
    rts::refineLink1(g, link1.data());
    rts::refineLink2(g, link2.data(), false);
    CHECK(distance(rts::refinePole(g), direct.pole) < 1e-14);
    for (int j = 0; j < n; ++j) {
      CHECK(distance(link1[j], direct.q(1, j)) < 1e-13);
      CHECK(distance(link2[j], direct.q(2, j)) < 1e-13);
    }
  }
}

TEST_CASE("rts: every rule is affine invariant, cyclically symmetric and reproduces planes") {
  for (int n : {3, 5, 8, 13, 24})
    for (bool uniformFirstStep : {false, true}) {
      PolarGrid g = randomGrid(n, 4, 7 * n);
      CHECK(affineDefect(rtsStep(uniformFirstStep), g) < 1e-12);
      CHECK(rotationDefect(rtsStep(uniformFirstStep), g, 1) < 1e-13);  // column j stays column j
      CHECK(planeDefect(rtsStep(uniformFirstStep), n, 4, 13 * n) < 1e-13);
    }
}

TEST_CASE("rts: links beyond the 2-link are radial knot insertion (12): the spline ring is unchanged") {
  for (int n : {3, 7, 12}) {
    const int links = 6;
    PolarGrid g = randomGrid(n, links, 17 * n);
    PolarGrid fine = rts::refineGrid(g);
    REQUIRE(fine.links == 2 * links - 1);
    CHECK(outerRingDefect(g, fine) < 1e-13);
  }
}

TEST_CASE("rts: the matrix (13) is block circulant with spectrum 1, 1/2, 1/2, 1/4, 1/4, 1/4, then 1/12 (Table 1)") {
  double worstDominant = 0.0, largestSeventh = 0.0;
  for (int n = 5; n <= 24; ++n) {
    Matrix a = subdivisionMatrix(n, rtsStep());
    CHECK(blockCirculantDefect(a, n) < 1e-15);
    auto spectrum = spectrumByFourierBlocks(a, n);
    REQUIRE(spectrum.size() == size_t(6 * n));
    for (int k = 0; k < 6; ++k) {
      worstDominant = std::max(worstDominant, std::abs(spectrum[k].value - kLambda[k]));
      CHECK(std::abs(spectrum[k].value - kLambda[k]) < 1e-10);
    }
    // Which Fourier block contributes which eigenvalue (Table 1's alpha_k column).
    CHECK(spectrum[0].alpha == 0);
    for (int k : {1, 2}) CHECK((spectrum[k].alpha == 1 || spectrum[k].alpha == n - 1));
    int quarterFromBlockZero = 0, quarterFromBlockTwo = 0;
    for (int k : {3, 4, 5}) {
      quarterFromBlockZero += spectrum[k].alpha == 0;
      quarterFromBlockTwo += spectrum[k].alpha == 2 || spectrum[k].alpha == n - 2;
    }
    CHECK(quarterFromBlockZero == 1);
    CHECK(quarterFromBlockTwo == 2);
    double seventh = std::abs(spectrum[6].value);
    largestSeventh = std::max(largestSeventh, seventh);
    CHECK(seventh < 0.25 - 1e-3);
    CHECK(seventh == doctest::Approx(1.0 / 12.0).epsilon(1e-9));
  }
  MESSAGE("RTS n = 5..24: max |lambda_k - Table 1| for k < 6: " << worstDominant
          << "; 7th eigenvalue modulus (max over n): " << largestSeventh << " (1/12 = " << 1.0 / 12 << ")");
}

TEST_CASE("rts: Table 1's right eigenvectors satisfy A v_k = lambda_k v_k") {
  for (int n = 5; n <= 24; ++n) {
    Matrix a = subdivisionMatrix(n, rtsStep());
    for (int k = 0; k < 6; ++k) {
      std::vector<double> v = fullVector(kRightRadial[k], k, n, 1.0);
      CHECK(maxAbsDifference(multiply(a, v), v, kLambda[k]) < 1e-13);
    }
  }
}

TEST_CASE("rts: the corrected left eigenvectors are biorthonormal to Table 1's; the printed (27) are not normalised") {
  for (int n = 5; n <= 24; ++n) {
    Matrix a = subdivisionMatrix(n, rtsStep());
    for (int k = 0; k < 6; ++k) {
      std::vector<double> w = fullVector(kLeftRadial[k], k, n, 1.0 / n);
      CHECK(maxAbsDifference(multiplyLeft(w, a), w, kLambda[k]) < 1e-14);  // w_k^T A = lambda_k w_k^T
      for (int l = 0; l < 6; ++l)
        CHECK(dotProduct(w, fullVector(kRightRadial[l], l, n, 1.0)) == doctest::Approx(k == l ? 1.0 : 0.0).epsilon(1e-13));

      // The printed rows are multiples of the true ones (so still left eigenvectors: the identity
      // w^T A = lambda w^T cannot see a scale) but w_k^T v_k = 2/3 for p3 and 1/3 for p4, p5.
      std::vector<double> printed = fullVector(kPrintedLeftRadial[k], k, n, 1.0 / n);
      CHECK(maxAbsDifference(multiplyLeft(printed, a), printed, kLambda[k]) < 1e-14);
      double normalisation = dotProduct(printed, fullVector(kRightRadial[k], k, n, 1.0));
      if (k < 3) {
        CHECK(normalisation == doctest::Approx(1.0).epsilon(1e-13));
      } else {
        CHECK(std::abs(normalisation - 1.0) > 0.3);
        CHECK(normalisation == doctest::Approx(k == 3 ? 2.0 / 3.0 : 1.0 / 3.0).epsilon(1e-13));
      }
    }
  }
}

TEST_CASE("rts: the Section-6 first step is one step of BPS on the 2-link") {
  for (int n : {3, 6, 11, 30}) {
    PolarGrid g = randomGrid(n, 3, 19 * n);
    std::vector<Point> rtsLink2(n), bpsLink2(n);
    rts::refineLink2(g, rtsLink2.data(), true);
    bps::refineLink2(g, bpsLink2.data());
    for (int j = 0; j < n; ++j) CHECK(distance(rtsLink2[j], bpsLink2[j]) == 0.0);
  }
}

TEST_CASE("rts: refinement rejects grids it cannot refine") {
  CHECK_THROWS_AS(rts::refineGrid(randomGrid(6, 1, 1)), std::invalid_argument);
  CHECK_THROWS_AS(rts::refineGrid(randomGrid(2, 3, 1)), std::invalid_argument);
}
