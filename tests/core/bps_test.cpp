// BPS (weights of the authors' group's polar_subdiv.m, see bps.h): rules against their direct
// sums, affine invariance, symmetry, planes, spectrum by Fourier blocks, and its limit point.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "core/spline/pole_taylor.h"
#include "core/subdiv/bps.h"
#include "polar_test_support.h"

using namespace polarview;
using namespace polarview::test;

namespace {

Refine bpsStep() {
  return [](const PolarGrid& g) { return bps::refineGrid(g); };
}

// Direct O(n^2) sums with gamma_{h-j} (the reference for the Fourier form).
PolarGrid refineDirectly(const PolarGrid& g) {
  int n = g.n;
  PolarGrid fine(n, 2);
  Point mean{0.0};
  for (int h = 0; h < n; ++h) mean += g.q(1, h) / double(n);
  fine.pole = (1.0 - bps::kAlpha) * g.pole + bps::kAlpha * mean;
  for (int j = 0; j < n; ++j) {
    Point link1 = (1.0 - bps::kBeta) * g.pole;
    for (int h = 0; h < n; ++h) link1 += bps::weightGamma(h - j, n) * g.q(1, h);
    fine.q(1, j) = link1;
    fine.q(2, j) = 0.125 * g.pole + 0.75 * g.q(1, j) + 0.125 * g.q(2, j);
  }
  return fine;
}

}  // namespace

TEST_CASE("bps: the gamma weights sum to beta (n >= 4) and the O(n) form equals the direct sums with gamma_{h-j}") {
  for (int n = 3; n <= 40; ++n) {
    double sum = 0.0;
    for (int g = 0; g < n; ++g) sum += bps::weightGamma(g, n);
    // At n = 3 the cos^3 term aliases onto the constant mode: the weights are not affine invariant.
    CHECK(sum == doctest::Approx(n == 3 ? bps::kBeta + 0.125 : bps::kBeta).epsilon(1e-14));

    PolarGrid g = randomGrid(n, 2, 500 + n);
    PolarGrid direct = refineDirectly(g);
    PolarGrid fine = bps::refineGrid(g);
    REQUIRE(fine.n == n);
    REQUIRE(fine.links == 3);
    CHECK(maxGridDistance(keepLinks(fine, 2), direct) < 1e-13);
    std::vector<Point> link1(n);
    bps::refineLink1(g, link1.data());
    CHECK(distance(bps::refinePole(g), direct.pole) < 1e-14);
    for (int j = 0; j < n; ++j) CHECK(distance(link1[j], direct.q(1, j)) < 1e-13);
  }
}

TEST_CASE("bps: every rule is affine invariant, cyclically symmetric and reproduces planes") {
  for (int n : {4, 5, 8, 19}) {
    PolarGrid g = randomGrid(n, 4, 43 * n);
    CHECK(affineDefect(bpsStep(), g) < 1e-12);
    CHECK(rotationDefect(bpsStep(), g, 1) < 1e-13);
    CHECK(planeDefect(bpsStep(), n, 4, 47 * n) < 1e-13);
  }
}

TEST_CASE("bps: links beyond the 2-link are radial knot insertion") {
  for (int n : {4, 9}) {
    PolarGrid g = randomGrid(n, 6, 53 * n);
    CHECK(outerRingDefect(g, bps::refineGrid(g)) < 1e-13);
  }
}

TEST_CASE("bps: spectrum 1, 1/2, 1/2, 1/4, 1/4, 1/4, 1/8 for n >= 6; at n = 5 the cos^3 term aliases to 5/16") {
  const double expected[7] = {1.0, 0.5, 0.5, 0.25, 0.25, 0.25, 0.125};
  double worst = 0.0;
  for (int n = 6; n <= 24; ++n) {
    Matrix a = subdivisionMatrix(n, bpsStep());
    CHECK(blockCirculantDefect(a, n) < 1e-15);
    auto spectrum = spectrumByFourierBlocks(a, n);
    for (int k = 0; k < 7; ++k) {
      worst = std::max(worst, std::abs(spectrum[k].value - expected[k]));
      CHECK(std::abs(spectrum[k].value - expected[k]) < 1e-7);  // 1/8 is a double root at n = 6
    }
    CHECK(std::abs(spectrum[7].value) < 0.125 + 1e-7);
  }
  MESSAGE("BPS n = 6..24: max |lambda_k - expected| for the seven dominant eigenvalues: " << worst);

  Matrix a5 = subdivisionMatrix(5, bpsStep());
  auto spectrum5 = spectrumByFourierBlocks(a5, 5);
  CHECK(std::abs(spectrum5[0].value - 1.0) < 1e-12);
  CHECK(std::abs(spectrum5[1].value - 0.5) < 1e-12);
  CHECK(std::abs(spectrum5[3].value - 5.0 / 16.0) < 1e-12);  // blocks 2 and 3 = -2: 1/4 + 1/16
  CHECK(std::abs(spectrum5[4].value - 5.0 / 16.0) < 1e-12);
}

TEST_CASE("bps: the 1/2 eigenvectors are linear in the link index; the 1/4 one is not Table 1's r^2") {
  const int n = 9;
  Matrix a = subdivisionMatrix(n, bpsStep());
  std::vector<double> linear(6 * n), quadratic(6 * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < 6; ++i) {
      linear[matrixIndex(i, j)] = i * std::cos(2 * kPi * j / n);
      quadratic[matrixIndex(i, j)] = i == 0 ? -1.0 / 3.0 : i * i - 1.0 / 3.0;
    }
  CHECK(maxAbsDifference(multiply(a, linear), linear, 0.5) < 1e-13);
  // Why BPS's Taylor expansion stops at the tangent plane: its mu = 1/4 eigenvector is not r^2.
  CHECK(maxAbsDifference(multiply(a, quadratic), quadratic, 0.25) > 0.1);
}

TEST_CASE("bps: the limit point 1/2 q00 + 1/2 M is invariant and p1, p2 halve under a step (n >= 5)") {
  for (int n : {4, 5, 6, 12, 25}) {
    PolarGrid g = randomGrid(n, 2, 59 * n);
    TaylorCoefficients base = poleTaylorCoefficients(g, Scheme::BPS);
    REQUIRE(base.order == 1);
    for (int m = 1; m <= 8; ++m) {
      g = keepLinks(bps::refineGrid(g), 2);
      TaylorCoefficients level = poleTaylorCoefficients(g, Scheme::BPS);
      // At n = 4 the cos^3 mode aliases onto mode 1: the tangent eigenvalue is 1/2 + 1/16.
      double halving = std::pow(n == 4 ? 9.0 / 16.0 : 0.5, m);
      CHECK(distance(level.p[0], base.p[0]) < 1e-14);
      CHECK(distance(level.p[1], halving * base.p[1]) < 1e-14);
      CHECK(distance(level.p[2], halving * base.p[2]) < 1e-14);
    }
    // The pole and the 1-link converge to that point.
    CHECK(distance(g.pole, base.p[0]) < 1e-3);
  }
}
