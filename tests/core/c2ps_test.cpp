// C2PS (Myles & Peters 2009, Section 3, (1)-(5), (29); Appendix (34), (35), Lemma 5): the O(n)
// rules against the direct sums with the half shift h - k/2, knot insertion, affine invariance,
// symmetry, planes, and the scaling of the eigencoefficients p0..p5 over many steps.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "core/spline/pole_taylor.h"
#include "core/subdiv/c2ps.h"
#include "core/subdiv/polar_rules.h"
#include "polar_test_support.h"

using namespace polarview;
using namespace polarview::test;

namespace {

const double kLambda[6] = {1.0, 0.5, 0.5, 0.25, 0.25, 0.25};

// (5) written out index by index (the reference for refinePeriodicLink).
std::vector<Point> refinePeriodicDirectly(const PolarGrid& g, int i) {
  std::vector<Point> out(2 * g.n);
  for (int j = 0; j < g.n; ++j) {
    out[2 * j] = (1.0 / 8) * g.q(i, j - 1) + (6.0 / 8) * g.q(i, j) + (1.0 / 8) * g.q(i, j + 1);
    out[2 * j + 1] = 0.5 * g.q(i, j) + 0.5 * g.q(i, j + 1);
  }
  return out;
}

// Direct O(n^2) sums of (1)-(3) with b_{h-k/2}, d_{h-k/2}; `shiftHalf` false reads the index as
// h - k (the misreading docs/misprints.md warns about).
PolarGrid refineDirectly(const PolarGrid& g, bool uniformFirstStep, bool shiftHalf = true) {
  int n = g.n;
  PolarGrid fine(2 * n, 2);
  std::vector<Point> tilde1 = refinePeriodicDirectly(g, 1), tilde2 = refinePeriodicDirectly(g, 2);
  Point sum{0.0};
  for (int h = 0; h < n; ++h) sum += g.q(1, h);
  fine.pole = 0.75 * g.pole + sum / (4.0 * n);
  for (int k = 0; k < 2 * n; ++k) {
    Point link1 = 0.5 * g.pole;
    Point link2 = uniformFirstStep ? (1.0 / 8) * g.pole + (3.0 / 4) * tilde1[k] + (1.0 / 8) * tilde2[k]
                                   : (11.0 / 12) * tilde1[k] + (1.0 / 12) * tilde2[k];
    for (int h = 0; h < n; ++h) {
      double g_ = shiftHalf ? h - 0.5 * k : double(h - k);
      link1 += c2ps::weightB(g_, n) * g.q(1, h);
      if (!uniformFirstStep) link2 += c2ps::weightD(g_, n) * g.q(1, h);
    }
    fine.q(1, k) = link1;
    fine.q(2, k) = link2;
  }
  return fine;
}

// Up to `steps` C2PS steps, keeping links 0..2 (all the polar rules read), returning every level.
std::vector<PolarGrid> refineLevels(const PolarGrid& g, int steps, bool uniformFirstStep = false) {
  std::vector<PolarGrid> levels{keepLinks(g, 2)};
  for (int m = 0; m < steps; ++m) levels.push_back(keepLinks(c2ps::refineGrid(levels.back(), uniformFirstStep && m == 0), 2));
  return levels;
}

}  // namespace

TEST_CASE("c2ps: (5) is knot insertion: the refined link defines the same periodic cubic spline") {
  for (int n : {3, 4, 7, 20}) {
    PolarGrid g = randomGrid(n, 1, 3 * n);
    std::vector<Point> refined(2 * n);
    refinePeriodicLink(&g.q(1, 0), n, refined.data());
    std::vector<Point> direct = refinePeriodicDirectly(g, 1);
    for (int k = 0; k < 2 * n; ++k) CHECK(distance(refined[k], direct[k]) < 1e-15);
    // Both control polygons, as uniform periodic cubic splines over tau in [0,1), agree everywhere.
    for (int s = 0; s < 50; ++s) {
      double tau = s / 50.0 + 0.003;
      auto curve = [&](const std::vector<Point>& pts, int count) {
        double t = tau * count;
        int j0 = int(std::floor(t)) - 1;
        auto b = cubicBasis(t - (j0 + 1));
        Point x{0.0};
        for (int a = 0; a < 4; ++a) x += b[a] * pts[((j0 + a) % count + count) % count];
        return x;
      };
      CHECK(distance(curve(g.ring, n), curve(refined, 2 * n)) < 1e-14);
    }
  }
}

TEST_CASE("c2ps: the O(n) Fourier form of (1)-(3) equals the direct sums with the half shift h - k/2") {
  for (int n = 3; n <= 40; ++n) {
    PolarGrid g = randomGrid(n, 2, 200 + n);
    for (bool uniformFirstStep : {false, true}) {
      PolarGrid direct = refineDirectly(g, uniformFirstStep);
      PolarGrid fine = c2ps::refineGrid(g, uniformFirstStep);
      REQUIRE(fine.n == 2 * n);
      REQUIRE(fine.links == 3);
      CHECK(maxGridDistance(keepLinks(fine, 2), direct) < 1e-13);

      std::vector<Point> link1(2 * n), link2(2 * n);
      c2ps::refineLink1(g, link1.data());
      c2ps::refineLink2(g, link2.data(), uniformFirstStep);
      CHECK(distance(c2ps::refinePole(g), direct.pole) < 1e-14);
      double worst = 0.0;
      for (int k = 0; k < 2 * n; ++k)
        worst = std::max({worst, distance(link1[k], direct.q(1, k)), distance(link2[k], direct.q(2, k))});
      CHECK(worst < 1e-13);
    }
  }
}

TEST_CASE("c2ps: links beyond the 2-link are bi-3 knot insertion (29): the spline ring is unchanged") {
  for (int n : {3, 6, 13}) {
    const int links = 6;
    PolarGrid g = randomGrid(n, links, 23 * n);
    PolarGrid fine = c2ps::refineGrid(g);
    REQUIRE(fine.links == 2 * links - 1);
    REQUIRE(fine.n == 2 * n);
    CHECK(outerRingDefect(g, fine) < 1e-13);
  }
}

TEST_CASE("c2ps: every rule is affine invariant, cyclically symmetric (by two) and reproduces planes") {
  for (int n : {3, 4, 6, 11, 32})
    for (bool uniformFirstStep : {false, true}) {
      Refine step = [uniformFirstStep](const PolarGrid& g) { return c2ps::refineGrid(g, uniformFirstStep); };
      Refine twoSteps = [uniformFirstStep](const PolarGrid& g) { return c2ps::refineGrid(c2ps::refineGrid(g, uniformFirstStep)); };
      PolarGrid g = randomGrid(n, 4, 29 * n);
      CHECK(affineDefect(step, g) < 1e-12);
      CHECK(rotationDefect(step, g, 2) < 1e-13);  // old column j is new column 2j
      CHECK(planeDefect(twoSteps, n, 4, 37 * n) < 1e-13);
    }
}

TEST_CASE("c2ps: Lemma 5: p_k^m = lambda_k^m p_k over six steps for n = 3..24, p0 invariant") {
  // Data are centred on their limit point (affine invariance), so that rounding is measured against
  // the terms that decay rather than against a constant offset that cancels in p3 = M - q00. The
  // error is relative to lambda_k^m max_k |p_k| (at n = 4, p5 is identically 0: sin(pi j) = 0).
  double worstRelative = 0.0, worstLimitDrift = 0.0;
  for (int n = 3; n <= 24; ++n)
    for (bool uniformFirstStep : {false, true}) {
      PolarGrid data = randomGrid(n, 2, 300 + n);
      Point limit = poleTaylorCoefficients(data, Scheme::C2PS).p[0];
      auto levels = refineLevels(mapGrid(data, [&](const Point& q) { return q - limit; }), 6, uniformFirstStep);
      auto uncentred = refineLevels(data, 6, uniformFirstStep);
      TaylorCoefficients base = poleTaylorCoefficients(levels[0], Scheme::C2PS);
      double scale = 0.0;
      for (const Point& p : base.p) scale = std::max(scale, glm::length(p));
      for (int m = 1; m < int(levels.size()); ++m) {
        REQUIRE(levels[m].n == n << m);
        TaylorCoefficients level = poleTaylorCoefficients(levels[m], Scheme::C2PS);
        for (int k = 0; k < 6; ++k) {
          double factor = std::pow(kLambda[k], m);
          double relative = distance(level.p[k], factor * base.p[k]) / (factor * scale);
          worstRelative = std::max(worstRelative, relative);
          INFO("n = " << n << " uniformFirstStep = " << uniformFirstStep << " m = " << m << " k = " << k);
          CHECK(relative < 1e-12);
        }
        double drift = distance(poleTaylorCoefficients(uncentred[m], Scheme::C2PS).p[0], limit);
        worstLimitDrift = std::max(worstLimitDrift, drift);
        CHECK(drift < 1e-14);
      }
    }
  MESSAGE("Lemma 5, C2PS, n = 3..24, 6 steps (plain and Section-6 first step): max |p_k^m - lambda_k^m p_k| / "
          "(lambda_k^m max|p|) = "
          << worstRelative << "; max drift of p0 (uncentred data in [-1,1]^3) = " << worstLimitDrift);
}

TEST_CASE("c2ps: reading the index of (2), (3) as h - k instead of h - k/2 breaks Lemma 5") {
  PolarGrid g = randomGrid(7, 2, 41);
  PolarGrid misread = refineDirectly(g, false, /*shiftHalf=*/false);
  TaylorCoefficients base = poleTaylorCoefficients(g, Scheme::C2PS);
  TaylorCoefficients after = poleTaylorCoefficients(misread, Scheme::C2PS);
  CHECK(distance(after.p[1], 0.5 * base.p[1]) > 1e-3 * glm::length(base.p[1]));
}

TEST_CASE("c2ps: (34), (35) hold with the corrected p3, p4, p5 and fail with the printed (27)") {
  for (int n : {3, 5, 6, 10, 17}) {
    auto levels = refineLevels(randomGrid(n, 2, 400 + n), 6);
    TaylorCoefficients t = poleTaylorCoefficients(levels[0], Scheme::C2PS);
    const auto& p = t.p;
    double worst = 0.0;
    for (int m = 0; m + 1 < int(levels.size()); ++m) {
      double lambda = std::pow(0.5, m + 1), mu = lambda * lambda;
      const PolarGrid& next = levels[m + 1];
      // (34): q00^{m+1} = p0 - mu^{m+1}/3 p3
      worst = std::max(worst, distance(next.pole, p[0] - (mu / 3.0) * p[3]));
      // (35): q_{1,[tau]}^{m+1} = p0 + lambda^{m+1}(p1 c + p2 s) + 2 mu^{m+1}/3 (p3 + p4 c2 + p5 s2)
      for (int k = 0; k < next.n; ++k) {
        double tau = 2.0 * kPi * k / next.n;
        Point predicted = p[0] + lambda * (std::cos(tau) * p[1] + std::sin(tau) * p[2]) +
                          (2.0 * mu / 3.0) * (p[3] + std::cos(2 * tau) * p[4] + std::sin(2 * tau) * p[5]);
        worst = std::max(worst, distance(next.q(1, k), predicted));
      }
    }
    CHECK(worst < 1e-13);

    // Printed (27): p3 = 2/3 (M - q00), p4 = (1/n) sum c2 q1j, p5 likewise.
    Point printedP3 = (2.0 / 3.0) * p[3], printedP4 = p[4] / 3.0, printedP5 = p[5] / 3.0;
    const PolarGrid& first = levels[1];
    CHECK(distance(first.pole, p[0] - (0.25 / 3.0) * printedP3) > 1e-3 * glm::length(p[3]));
    double printedWorst = 0.0;
    for (int k = 0; k < first.n; ++k) {
      double tau = 2.0 * kPi * k / first.n;
      Point predicted = p[0] + 0.5 * (std::cos(tau) * p[1] + std::sin(tau) * p[2]) +
                        (2.0 * 0.25 / 3.0) * (printedP3 + std::cos(2 * tau) * printedP4 + std::sin(2 * tau) * printedP5);
      printedWorst = std::max(printedWorst, distance(first.q(1, k), predicted));
    }
    CHECK(printedWorst > 1e-3);
  }
}

TEST_CASE("c2ps: the 1- and 2-link rules run in O(n) at valence 65536 and still scale p1, p2 by 1/2") {
  const int n = 65536;  // valence 64 after 10 levels
  PolarGrid g = randomGrid(n, 2, 77);
  std::vector<Point> link1(2 * n), link2(2 * n);
  c2ps::refineLink1(g, link1.data());
  c2ps::refineLink2(g, link2.data(), false);

  PolarGrid fine(2 * n, 1);
  fine.pole = c2ps::refinePole(g);
  fine.ring = link1;
  TaylorCoefficients before = poleTaylorCoefficients(g, Scheme::C2PS);
  TaylorCoefficients after = poleTaylorCoefficients(fine, Scheme::C2PS);
  for (int k = 0; k < 6; ++k) CHECK(distance(after.p[k], kLambda[k] * before.p[k]) < 1e-12);

  // A few columns against the direct sums (each one O(n)).
  for (int k : {0, 1, 4097, 2 * n - 1}) {
    Point direct1 = 0.5 * g.pole, directD{0.0};
    for (int h = 0; h < n; ++h) {
      direct1 += c2ps::weightB(h - 0.5 * k, n) * g.q(1, h);
      directD += c2ps::weightD(h - 0.5 * k, n) * g.q(1, h);
    }
    std::vector<Point> tilde1(2 * n), tilde2(2 * n);
    refinePeriodicLink(&g.q(1, 0), n, tilde1.data());
    refinePeriodicLink(&g.q(2, 0), n, tilde2.data());
    CHECK(distance(link1[k], direct1) < 1e-12);
    CHECK(distance(link2[k], (11.0 / 12) * tilde1[k] + (1.0 / 12) * tilde2[k] + directD) < 1e-12);
  }
}

TEST_CASE("c2ps: refinement rejects grids it cannot refine") {
  CHECK_THROWS_AS(c2ps::refineGrid(randomGrid(6, 1, 1)), std::invalid_argument);
  std::vector<Point> out(4);
  CHECK_THROWS_AS(c2ps::refineLink2(randomGrid(2, 2, 1), out.data(), false), std::invalid_argument);
}
