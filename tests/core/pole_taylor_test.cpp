// The pole's Taylor expansion (32) with the eigencoefficients of Table 1 (docs/rings-and-pole.md):
// quadratic reproduction, exact K and H at the pole, invariance under C2PS and RTS steps.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "core/spline/pole_taylor.h"
#include "core/subdiv/c2ps.h"
#include "core/subdiv/rts.h"
#include "polar_test_support.h"

using namespace polarview;
using namespace polarview::test;

namespace {

// A graph z = d x + e y + a x^2 + b xy + c y^2 over the tangent plane at the origin.
struct Quadratic {
  double a, b, c, d, e;
  double operator()(double x, double y) const { return d * x + e * y + a * x * x + b * x * y + c * y * y; }
  double gaussian() const {
    double w = 1 + d * d + e * e;
    return (4 * a * c - b * b) / (w * w);
  }
  double mean() const {
    double w = 1 + d * d + e * e;
    return ((1 + e * e) * 2 * a - 2 * d * e * b + (1 + d * d) * 2 * c) / (2 * std::pow(w, 1.5));
  }
  Point normal() const { return glm::normalize(Point(-d, -e, 1.0)); }
};

// Plain samples at the Greville points: link i at radius i * spacing, column j at angle j/n.
PolarGrid grevilleSamples(const Quadratic& f, int n, int links, double spacing = 1.0) {
  PolarGrid g(n, links);
  g.pole = Point(0.0, 0.0, f(0, 0));
  for (int i = 1; i <= links; ++i)
    for (int j = 0; j < n; ++j) {
      double x = i * spacing * std::cos(2 * kPi * j / n), y = i * spacing * std::sin(2 * kPi * j / n);
      g.q(i, j) = Point(x, y, f(x, y));
    }
  return g;
}

// The control net that represents f exactly in Table 1's eigenbasis: radially, the uniform cubic
// B-spline of r^2 has control points (i^2 - 1/3) spacing^2, so each sample is lowered by
// spacing^2/3 times the radial quadratic coefficient; the pole by the mean of those over directions.
PolarGrid exactQuadraticNet(const Quadratic& f, int n, int links, double spacing = 1.0) {
  PolarGrid g = grevilleSamples(f, n, links, spacing);
  double lower = spacing * spacing / 3.0;
  g.pole.z -= lower * 0.5 * (f.a + f.c);
  for (int i = 1; i <= links; ++i)
    for (int j = 0; j < n; ++j) {
      double cs = std::cos(2 * kPi * j / n), sn = std::sin(2 * kPi * j / n);
      g.q(i, j).z -= lower * (f.a * cs * cs + f.b * cs * sn + f.c * sn * sn);
    }
  return g;
}

// A rotation (about a fixed oblique axis) followed by a translation.
Point rigidMotion(const Point& p) {
  Point axis = glm::normalize(Point(1.0, -2.0, 0.5));
  double angle = 0.9, c = std::cos(angle), s = std::sin(angle);
  Point rotated = c * p + s * glm::cross(axis, p) + (1 - c) * glm::dot(axis, p) * axis;
  return rotated + Point(3.0, -1.0, 0.25);
}
Point rotateOnly(const Point& v) { return rigidMotion(v) - rigidMotion(Point(0.0)); }

const Quadratic kParaboloid{1, 0, 1, 0, 0};
const Quadratic kSaddle{1, 0, -1, 0, 0};   // x^2 - y^2
const Quadratic kTwistedSaddle{0, 2, 0, 0, 0};  // 2xy

}  // namespace

TEST_CASE("pole taylor: the paraboloid sampled at the Greville points has K = 4, H = 2 at the pole for n = 6..64") {
  for (int n = 6; n <= 64; ++n) {
    PoleDifferential d = analyzePole(poleTaylorCoefficients(grevilleSamples(kParaboloid, n, 3), Scheme::C2PS));
    REQUIRE(d.curvatureDefined);
    CHECK(d.gaussian == doctest::Approx(4.0).epsilon(1e-12));
    CHECK(d.mean == doctest::Approx(2.0).epsilon(1e-12));
    CHECK(distance(d.normal, Point(0, 0, 1)) < 1e-14);
    // The samples sit 1/3 above the exact net r^2 - 1/3: the limit point is lifted by 1/3.
    CHECK(distance(d.limit, Point(0, 0, 1.0 / 3.0)) < 1e-14);
  }
}

TEST_CASE("pole taylor: saddles need their exact control net; plain Greville samples overstate p4, p5 by 3/2") {
  for (int n = 6; n <= 64; ++n)
    for (const Quadratic& saddle : {kSaddle, kTwistedSaddle}) {
      PoleDifferential exact = analyzePole(poleTaylorCoefficients(exactQuadraticNet(saddle, n, 3), Scheme::C2PS));
      CHECK(exact.gaussian == doctest::Approx(-4.0).epsilon(1e-12));
      CHECK(std::abs(exact.mean) < 1e-12);
      CHECK(distance(exact.normal, Point(0, 0, 1)) < 1e-14);
      CHECK(distance(exact.limit, Point(0.0)) < 1e-14);

      // Samples put 1 instead of 2/3 c_{2j} on the 1-link (Table 1's v4): x_xx comes out 3, K = -9.
      PoleDifferential sampled = analyzePole(poleTaylorCoefficients(grevilleSamples(saddle, n, 3), Scheme::C2PS));
      CHECK(sampled.gaussian == doctest::Approx(-9.0).epsilon(1e-12));
    }
}

TEST_CASE("pole taylor: any tilted, moved quadratic graph gives its exact normal, K and H (n = 6..64)") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 6; n <= 64; ++n) {
    Quadratic f{u(rng), u(rng), u(rng), u(rng), u(rng)};
    PolarGrid net = mapGrid(exactQuadraticNet(f, n, 3), rigidMotion);
    TaylorCoefficients t = poleTaylorCoefficients(net, Scheme::C2PS);
    PoleDifferential d = analyzePole(t);
    REQUIRE(d.curvatureDefined);
    CHECK(d.gaussian == doctest::Approx(f.gaussian()).epsilon(1e-11));
    CHECK(d.mean == doctest::Approx(f.mean()).epsilon(1e-11));
    CHECK(distance(d.normal, rotateOnly(f.normal())) < 1e-13);
    CHECK(distance(d.limit, rigidMotion(Point(0.0))) < 1e-13);
    // The second partials of (32) are the graph's, moved rigidly.
    TaylorJet jet = evaluateTaylor(t, 0.0, 0.0);
    CHECK(distance(jet.xx, rotateOnly(Point(0, 0, 2 * f.a))) < 1e-12);
    CHECK(distance(jet.xy, rotateOnly(Point(0, 0, f.b))) < 1e-12);
    CHECK(distance(jet.yy, rotateOnly(Point(0, 0, 2 * f.c))) < 1e-12);
  }
}

TEST_CASE("pole taylor: RTS reproduces a quadratic exactly: one step gives the exact net at half spacing") {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n : {5, 6, 9, 16, 31}) {
    Quadratic f{u(rng), u(rng), u(rng), u(rng), u(rng)};
    PolarGrid fine = keepLinks(rts::refineGrid(exactQuadraticNet(f, n, 5)), 5);
    CHECK(maxGridDistance(fine, exactQuadraticNet(f, n, 5, 0.5)) < 1e-13);
  }
}

TEST_CASE("pole taylor: C2PS steps keep the pole's limit, normal, K and H; its 0- and 1-links stay exact for quadratics") {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n : {3, 5, 6, 8, 13, 24}) {
    // Generic data: the expansion is the same surface at every level (only its radial unit halves).
    PolarGrid g = randomGrid(n, 2, 600 + n);
    PoleDifferential base = analyzePole(poleTaylorCoefficients(g, Scheme::C2PS));
    for (int m = 1; m <= 7; ++m) {
      g = keepLinks(c2ps::refineGrid(g), 2);
      PoleDifferential level = analyzePole(poleTaylorCoefficients(g, Scheme::C2PS));
      CHECK(distance(level.limit, base.limit) < 1e-14);
      CHECK(distance(level.normal, base.normal) < 1e-12);
      CHECK(level.gaussian == doctest::Approx(base.gaussian).epsilon(1e-10));
      CHECK(level.mean == doctest::Approx(base.mean).epsilon(1e-10));
    }
    if (n < 5) continue;  // p4, p5 alias with p1, p2 below valence 5
    // A quadratic: after a step the pole and the 1-link are its exact net at valence 2n, spacing 1/2.
    Quadratic f{u(rng), u(rng), u(rng), u(rng), u(rng)};
    PolarGrid fine = keepLinks(c2ps::refineGrid(exactQuadraticNet(f, n, 2)), 1);
    CHECK(maxGridDistance(fine, exactQuadraticNet(f, 2 * n, 1, 0.5)) < 1e-13);
  }
}

TEST_CASE("pole taylor: evaluateTaylor's partials are those of its position") {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TaylorCoefficients t;
  for (Point& p : t.p) p = Point(u(rng), u(rng), u(rng));
  const double h = 1e-4;
  for (int s = 0; s < 20; ++s) {
    double x = u(rng), y = u(rng);
    auto at = [&](double dx, double dy) { return evaluateTaylor(t, x + dx, y + dy).position; };
    TaylorJet jet = evaluateTaylor(t, x, y);
    CHECK(distance(jet.x, (at(h, 0) - at(-h, 0)) / (2 * h)) < 1e-8);
    CHECK(distance(jet.y, (at(0, h) - at(0, -h)) / (2 * h)) < 1e-8);
    CHECK(distance(jet.xx, (at(h, 0) - 2.0 * at(0, 0) + at(-h, 0)) / (h * h)) < 1e-5);
    CHECK(distance(jet.yy, (at(0, h) - 2.0 * at(0, 0) + at(0, -h)) / (h * h)) < 1e-5);
    CHECK(distance(jet.xy, (at(h, h) - at(h, -h) - at(-h, h) + at(-h, -h)) / (4 * h * h)) < 1e-5);
  }
}

TEST_CASE("pole taylor: BPS gives its limit point and tangent plane only; Catmull-Clark has no expansion") {
  PolarGrid g = exactQuadraticNet(Quadratic{0.3, -0.2, 0.5, 0.4, -0.1}, 8, 2);
  TaylorCoefficients t = poleTaylorCoefficients(g, Scheme::BPS);
  CHECK(t.order == 1);
  Point mean{0.0};
  for (int j = 0; j < g.n; ++j) mean += g.q(1, j) / double(g.n);
  CHECK(distance(t.p[0], 0.5 * g.pole + 0.5 * mean) < 1e-15);
  PoleDifferential d = analyzePole(t);
  CHECK_FALSE(d.curvatureDefined);
  CHECK(d.gaussian == 0.0);
  CHECK(d.mean == 0.0);
  CHECK(distance(d.normal, glm::normalize(Point(-0.4, 0.1, 1.0))) < 1e-14);
  // The quadratic part is ignored when evaluating an order-1 expansion.
  CHECK(distance(evaluateTaylor(t, 0.5, 0.5).position, t.p[0] + 0.5 * t.p[1] + 0.5 * t.p[2]) < 1e-15);

  CHECK_THROWS_AS(poleTaylorCoefficients(g, Scheme::CatmullClark), std::logic_error);
}

TEST_CASE("pole taylor: a degenerate tangent plane leaves the normal and curvature undefined") {
  PolarGrid flat(6, 2);  // every point at the origin: p1 = p2 = 0
  PoleDifferential d = analyzePole(poleTaylorCoefficients(flat, Scheme::C2PS));
  CHECK_FALSE(d.curvatureDefined);
  CHECK(glm::length(d.normal) == 0.0);
}

TEST_CASE("pole taylor: huge and tiny nets give the exactly scaled normal, K and H (no overflow in E G - F^2)") {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Quadratic f{u(rng), u(rng), u(rng), u(rng), u(rng)};
  const PolarGrid net = mapGrid(exactQuadraticNet(f, 12, 3), rigidMotion);
  const PoleDifferential unit = analyzePole(poleTaylorCoefficients(net, Scheme::C2PS));
  REQUIRE(unit.curvatureDefined);
  // Powers of two scale exactly; 1e150 (the OBJ reader's limit) and 1e-150 as they come.
  for (double s : {0x1p400, 0x1p-400, 1e150, 1e-150, 1e100}) {
    CAPTURE(s);
    const PolarGrid scaled = mapGrid(net, [s](const Point& p) { return s * p; });
    const PoleDifferential d = analyzePole(poleTaylorCoefficients(scaled, Scheme::C2PS));
    REQUIRE(d.curvatureDefined);
    CHECK(distance(d.normal, unit.normal) < 1e-13);
    CHECK(d.gaussian * s * s == doctest::Approx(unit.gaussian).epsilon(1e-11));
    CHECK(d.mean * s == doctest::Approx(unit.mean).epsilon(1e-11));
    CHECK(std::isfinite(d.gaussian));
    CHECK(std::isfinite(d.mean));
  }
}
