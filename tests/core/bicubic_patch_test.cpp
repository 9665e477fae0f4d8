#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>

#include <glm/geometric.hpp>

#include "core/mesh/constants.h"
#include "core/spline/patch.h"
#include "core/spline/pole_taylor.h"

using namespace polarview;

namespace {

Point randomPoint(std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> d(-scale, scale);
  return Point(d(rng), d(rng), d(rng));
}

// A random rotation (orthonormal frame from Gram-Schmidt) to check that K, H do not depend on pose.
struct Frame {
  Point a, b, c;
  Point apply(const Point& p) const { return p.x * a + p.y * b + p.z * c; }
};
Frame randomFrame(std::mt19937& rng) {
  Point a = glm::normalize(randomPoint(rng));
  Point b = randomPoint(rng);
  b = glm::normalize(b - glm::dot(a, b) * a);
  return {a, b, glm::cross(a, b)};
}

// Reference curvature of the graph z = f(x,y) with upward normal.
struct GraphCurvature {
  double K, H;
};
GraphCurvature graphCurvature(double fx, double fy, double fxx, double fxy, double fyy) {
  const double W = 1.0 + fx * fx + fy * fy;
  return {(fxx * fyy - fxy * fxy) / (W * W),
          ((1.0 + fy * fy) * fxx - 2.0 * fx * fy * fxy + (1.0 + fx * fx) * fyy) / (2.0 * std::pow(W, 1.5))};
}

// Reference K, H of a Taylor expansion at its origin from x_x = p1, x_y = p2, x_xx = 2(p3+p4),
// x_yy = 2(p3-p4), x_xy = 2 p5 (docs/rings-and-pole.md, Taylor expansion), via the fundamental forms.
GraphCurvature taylorCurvature(const std::array<Point, 6>& p) {
  const Point N = glm::normalize(glm::cross(p[1], p[2]));
  const double E = glm::dot(p[1], p[1]), F = glm::dot(p[1], p[2]), G = glm::dot(p[2], p[2]);
  const double L = glm::dot(2.0 * (p[3] + p[4]), N), M = glm::dot(2.0 * p[5], N), N2 = glm::dot(2.0 * (p[3] - p[4]), N);
  const double det = E * G - F * F;
  return {(L * N2 - M * M) / det, (E * N2 - 2.0 * F * M + G * L) / (2.0 * det)};
}

Patch randomBSplinePatch(std::mt19937& rng) {
  Patch patch;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) patch.cp[4 * j + i] = Point(i, j, 0.0) + randomPoint(rng, 0.3);
  return patch;
}

// A cap of sector j of n (patch.h layout) with random Taylor data (p3..p5 zero for order 1, as
// extraction stores BPS's tangent plane) and ring data b, e, f near the expansion's on the circle.
Patch randomPoleCap(std::mt19937& rng, int n, int j, int order) {
  Patch cap;
  cap.kind = PatchKind::PoleCap;
  cap.sector = j;
  cap.sectorCount = n;
  cap.cp[0] = randomPoint(rng);
  cap.cp[1] = Point(1.0, 0.0, 0.0) + randomPoint(rng, 0.2);
  cap.cp[2] = Point(0.0, 1.0, 0.0) + randomPoint(rng, 0.2);
  for (int k = 3; k < 6; ++k) cap.cp[k] = order >= 2 ? randomPoint(rng, 0.3) : Point(0.0);
  const double R = kPoleCapRadius;
  for (int k = 0; k < 4; ++k) {  // boundary control points near the circle r = R
    const double a = 2.0 * kPi * (j - 1 + k) / n;
    cap.cp[6 + k] = cap.cp[0] + R * std::cos(a) * cap.cp[1] + R * std::sin(a) * cap.cp[2] + randomPoint(rng, 0.1);
    // First and second radial derivative points near the expansion's.
    cap.cp[12 + k] = std::cos(a) * cap.cp[1] + std::sin(a) * cap.cp[2] + randomPoint(rng, 0.2);
    capSecondPoint(cap, k) = randomPoint(rng, 0.3);
  }
  return cap;
}

// The uniform cubic B-spline basis at v and its first and second derivatives.
void bsplineAt(double v, double b[4], double db[4], double ddb[4]) {
  const double s = 1.0 - v;
  b[0] = s * s * s / 6.0, b[1] = (3 * v * v * v - 6 * v * v + 4) / 6.0;
  b[2] = (-3 * v * v * v + 3 * v * v + 3 * v + 1) / 6.0, b[3] = v * v * v / 6.0;
  db[0] = -s * s / 2.0, db[1] = (3 * v * v - 4 * v) / 2.0, db[2] = (-3 * v * v + 2 * v + 1) / 2.0, db[3] = v * v / 2.0;
  ddb[0] = s, ddb[1] = 3 * v - 2, ddb[2] = 1 - 3 * v, ddb[3] = v;
}

// Central differences of position and first derivatives against the analytic derivatives.
void checkDerivativesByFiniteDifferences(const Patch& patch, double u, double v) {
  const double h = 1e-5;
  const SurfacePoint sp = evaluatePatch(patch, u, v);
  const SurfacePoint up = evaluatePatch(patch, u + h, v), um = evaluatePatch(patch, u - h, v);
  const SurfacePoint vp = evaluatePatch(patch, u, v + h), vm = evaluatePatch(patch, u, v - h);
  const double tol = 1e-6 * (1.0 + glm::length(sp.du) + glm::length(sp.dv) + glm::length(sp.duu) + glm::length(sp.dvv));
  CHECK(glm::length((up.position - um.position) / (2 * h) - sp.du) < tol);
  CHECK(glm::length((vp.position - vm.position) / (2 * h) - sp.dv) < tol);
  CHECK(glm::length((up.du - um.du) / (2 * h) - sp.duu) < tol);
  CHECK(glm::length((vp.du - vm.du) / (2 * h) - sp.duv) < tol);
  CHECK(glm::length((up.dv - um.dv) / (2 * h) - sp.duv) < tol);
  CHECK(glm::length((vp.dv - vm.dv) / (2 * h) - sp.dvv) < tol);
}

}  // namespace

TEST_CASE("bicubic patch: control points on a plane give that plane with K = H = 0") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const Frame frame = randomFrame(rng);
    const Point origin = randomPoint(rng, 5.0);
    Patch patch;
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        patch.cp[4 * j + i] = origin + frame.apply(Point(i + jitter(rng), j + jitter(rng), 0.0));
    for (double u : {0.0, 0.3, 1.0})
      for (double v : {0.0, 0.55, 1.0}) {
        const SurfacePoint sp = evaluatePatch(patch, u, v);
        CHECK(std::abs(glm::dot(sp.position - origin, frame.c)) < 1e-12);
        CHECK(std::abs(std::abs(glm::dot(sp.normal, frame.c)) - 1.0) < 1e-12);
        CHECK(std::abs(sp.gaussian) < 1e-10);
        CHECK(std::abs(sp.mean) < 1e-10);
      }
  }
}

TEST_CASE("bicubic patch: a quadratic graph sampled by its blossom has that graph's K and H everywhere") {
  // Cubic B-splines reproduce quadratics: on knots x_i = x0 + i h the control value of x^2 is its
  // blossom x_i^2 - h^2/3, of x*y it is x_i y_j, of linear terms the value itself.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coef(-1.5, 1.5), spacing(0.05, 0.6);
  for (int trial = 0; trial < 40; ++trial) {
    const double a = coef(rng), b = coef(rng), c = coef(rng), d = coef(rng), e = coef(rng);
    const double h = spacing(rng), x0 = coef(rng), y0 = coef(rng);
    auto f = [&](double x, double y) { return a * x * x + b * x * y + c * y * y + d * x + e * y; };
    const Frame frame = trial == 0 ? Frame{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}} : randomFrame(rng);
    Patch patch;
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const double x = x0 + i * h, y = y0 + j * h;
        const double z = f(x, y) - (a + c) * h * h / 3.0;
        patch.cp[4 * j + i] = frame.apply(Point(x, y, z));
      }
    for (double u = 0.0; u <= 1.0; u += 0.25)
      for (double v = 0.0; v <= 1.0; v += 0.25) {
        const double x = x0 + (1 + u) * h, y = y0 + (1 + v) * h;
        const SurfacePoint sp = evaluatePatch(patch, u, v);
        const GraphCurvature ref = graphCurvature(2 * a * x + b * y + d, b * x + 2 * c * y + e, 2 * a, b, 2 * c);
        CHECK(glm::length(sp.position - frame.apply(Point(x, y, f(x, y)))) < 1e-12);
        CHECK(std::abs(sp.gaussian - ref.K) < 1e-10 * (1 + std::abs(ref.K)));
        CHECK(std::abs(sp.mean - ref.H) < 1e-10 * (1 + std::abs(ref.H)));
      }
  }
}

TEST_CASE("bicubic patch: the paraboloid z = x^2 + y^2 has K = 4 and H = 2 at its apex") {
  const double h = 0.25;
  Patch patch;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const double x = (i - 1.5) * h, y = (j - 1.5) * h;
      patch.cp[4 * j + i] = Point(x, y, x * x + y * y - 2.0 * h * h / 3.0);
    }
  const SurfacePoint apex = evaluatePatch(patch, 0.5, 0.5);
  CHECK(glm::length(apex.position) < 1e-15);
  CHECK(apex.gaussian == doctest::Approx(4.0).epsilon(1e-12));
  CHECK(apex.mean == doctest::Approx(2.0).epsilon(1e-12));
  CHECK(apex.normal.z == doctest::Approx(1.0));
}

TEST_CASE("bicubic patch: K and H of a patch scaled by s are K / s^2 and H / s over the OBJ reader's range") {
  // The paraboloid above, scaled from 1e-150 to 1e150 (coordinates the reader accepts): E G - F^2
  // is a fourth power of the size, 1e-600 .. 1e600 unscaled, past double's range both ways.
  const double h = 0.25;
  for (double s : {1e-150, 1e-80, 1e-10, 1e15, 1e40, 1e150}) {
    CAPTURE(s);
    Patch patch;
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const double x = (i - 1.5) * h, y = (j - 1.5) * h;
        patch.cp[4 * j + i] = s * Point(x, y, x * x + y * y - 2.0 * h * h / 3.0);
      }
    const SurfacePoint apex = evaluatePatch(patch, 0.5, 0.5), side = evaluatePatch(patch, 0.2, 0.7);
    CHECK(apex.gaussian * s * s == doctest::Approx(4.0).epsilon(1e-12));
    CHECK(apex.mean * s == doctest::Approx(2.0).epsilon(1e-12));
    CHECK(apex.normal.z == doctest::Approx(1.0));
    const double x = (0.2 - 0.5) * h, y = (0.7 - 0.5) * h;  // the patch is z = x^2 + y^2 - c over its square
    const GraphCurvature expected = graphCurvature(2.0 * x, 2.0 * y, 2.0, 0.0, 2.0);
    CHECK(side.gaussian * s * s == doctest::Approx(expected.K).epsilon(1e-12));
    CHECK(side.mean * s == doctest::Approx(expected.H).epsilon(1e-12));
  }
}

TEST_CASE("bicubic patch: analytic derivatives match finite differences") {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 30; ++trial) {
    const Patch patch = randomBSplinePatch(rng);
    for (double u : {0.1, 0.5, 0.9})
      for (double v : {0.2, 0.7}) checkDerivativesByFiniteDifferences(patch, u, v);
  }
}

TEST_CASE("pole cap: at u = 0 it is the Taylor expansion, with the Taylor K and H in every sector") {
  std::mt19937 rng(5);
  for (int n : {3, 5, 8, 13}) {
    for (int trial = 0; trial < 10; ++trial) {
      Patch cap = randomPoleCap(rng, n, 0, 2);
      std::array<Point, 6> p;
      for (int k = 0; k < 6; ++k) p[k] = cap.cp[k];
      const GraphCurvature ref = taylorCurvature(p);
      const Point refNormal = glm::normalize(glm::cross(p[1], p[2]));
      for (int j = 0; j < n; ++j) {
        cap.sector = j;
        for (double v : {0.0, 0.4, 1.0}) {
          const SurfacePoint sp = evaluatePatch(cap, 0.0, v);
          CHECK(glm::length(sp.position - p[0]) < 1e-14);
          CHECK(glm::length(sp.normal - refNormal) < 1e-12);
          CHECK(sp.gaussian == doctest::Approx(ref.K).epsilon(1e-12));
          CHECK(sp.mean == doctest::Approx(ref.H).epsilon(1e-12));
        }
      }
    }
  }
}

TEST_CASE("pole cap: at the pole K, H and the normal are analyzePole's") {
  std::mt19937 rng(23);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 4 + trial;
    const Patch cap = randomPoleCap(rng, n, trial % n, 2);
    TaylorCoefficients taylor;
    for (int k = 0; k < 6; ++k) taylor.p[k] = cap.cp[k];
    taylor.order = 2;
    const PoleDifferential pole = analyzePole(taylor);
    const SurfacePoint sp = evaluatePatch(cap, 0.0, 0.5);
    REQUIRE(pole.curvatureDefined);
    CHECK(glm::length(sp.position - pole.limit) < 1e-14);
    CHECK(glm::length(sp.normal - pole.normal) < 1e-12);
    CHECK(sp.gaussian == doctest::Approx(pole.gaussian).epsilon(1e-12));
    CHECK(sp.mean == doctest::Approx(pole.mean).epsilon(1e-12));
  }
}

TEST_CASE("pole cap: curvature is continuous into the pole (K(u) -> K(0) linearly)") {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 10; ++trial) {
    const Patch cap = randomPoleCap(rng, 6, trial % 6, 2);
    const SurfacePoint pole = evaluatePatch(cap, 0.0, 0.3);
    const double e1 = std::abs(evaluatePatch(cap, 1e-3, 0.3).gaussian - pole.gaussian);
    const double e2 = std::abs(evaluatePatch(cap, 1e-4, 0.3).gaussian - pole.gaussian);
    CHECK(e2 < 0.2 * e1 + 1e-12);  // O(u): a tenth of u gives about a tenth of the error
  }
}

TEST_CASE("pole cap: it meets its boundary curve at u = 1 and its neighbour sector along v") {
  std::mt19937 rng(13);
  for (int order : {1, 2}) {
    const int n = 7;
    Patch a = randomPoleCap(rng, n, 2, order);
    Patch b = a;  // sector 3 shares p0..p5; its ring points are shifted by one column
    b.sector = 3;
    for (int k = 0; k < 3; ++k)
      b.cp[6 + k] = a.cp[7 + k], b.cp[12 + k] = a.cp[13 + k], capSecondPoint(b, k) = capSecondPoint(a, k + 1);
    b.cp[9] = randomPoint(rng);
    b.cp[15] = randomPoint(rng);
    capSecondPoint(b, 3) = randomPoint(rng);
    for (double t : {0.0, 0.3, 0.8, 1.0}) {
      // u = 1: the B-spline boundary curve (b_{j-1} + 4 b_j + b_{j+1}) / 6 at v = 0.
      const SurfacePoint edge = evaluatePatch(a, 1.0, 0.0);
      CHECK(glm::length(edge.position - (a.cp[6] + 4.0 * a.cp[7] + a.cp[8]) / 6.0) < 1e-13);
      const SurfacePoint sa = evaluatePatch(a, t, 1.0), sb = evaluatePatch(b, t, 0.0);
      CHECK(glm::length(sa.position - sb.position) < 1e-13);
      if (t > 0.0) CHECK(glm::length(sa.normal - sb.normal) < 1e-12);
    }
  }
}

TEST_CASE("pole cap: at u = 1 its value and first and second radial derivatives are the ring's (C2 with it)") {
  std::mt19937 rng(29);
  for (int order : {1, 2})
    for (int trial = 0; trial < 10; ++trial) {
      const int n = 5 + trial;
      const Patch cap = randomPoleCap(rng, n, trial % n, order);
      const double R = kPoleCapRadius;
      for (double v : {0.0, 0.35, 0.7, 1.0}) {
        // The uniform cubic B-splines of b (cp[6..9]), e (cp[12..15]) and f (capSecondPoint) at v,
        // with their v-derivatives: the ring patch's value, d/dr and d2/dr2 along link 2 (per unit
        // r; u = r / R) and their derivatives along it.
        double b[4], db[4], ddb[4];
        bsplineAt(v, b, db, ddb);
        Point C(0.0), Cv(0.0), Cvv(0.0), E(0.0), Ev(0.0), F(0.0);
        for (int k = 0; k < 4; ++k) {
          C += b[k] * cap.cp[6 + k], Cv += db[k] * cap.cp[6 + k], Cvv += ddb[k] * cap.cp[6 + k];
          E += b[k] * cap.cp[12 + k], Ev += db[k] * cap.cp[12 + k];
          F += b[k] * capSecondPoint(cap, k);
        }
        const SurfacePoint edge = evaluatePatch(cap, 1.0, v);
        const double scale = 1.0 + glm::length(R * R * F) + glm::length(R * E) + glm::length(Cvv);
        CHECK(glm::length(edge.position - C) < 1e-13);
        CHECK(glm::length(edge.du - R * E) < 1e-12 * scale);
        CHECK(glm::length(edge.dv - Cv) < 1e-12 * scale);
        CHECK(glm::length(edge.duu - R * R * F) < 1e-12 * scale);
        CHECK(glm::length(edge.duv - R * Ev) < 1e-12 * scale);
        CHECK(glm::length(edge.dvv - Cvv) < 1e-12 * scale);
      }
    }
}

TEST_CASE("pole cap: analytic (u,v) derivatives match finite differences away from the pole") {
  std::mt19937 rng(17);
  for (int order : {1, 2})
    for (int trial = 0; trial < 10; ++trial) {
      const Patch cap = randomPoleCap(rng, 5 + trial, trial % 5, order);
      for (double u : {0.2, 0.6, 0.95})
        for (double v : {0.1, 0.5, 0.9}) checkDerivativesByFiniteDifferences(cap, u, v);
    }
}

TEST_CASE("pole cap: tangent-plane caps (order 1) are flat at the pole") {
  std::mt19937 rng(19);
  const Patch cap = randomPoleCap(rng, 8, 1, 1);
  const SurfacePoint sp = evaluatePatch(cap, 0.0, 0.5);
  CHECK(std::abs(sp.gaussian) < 1e-14);
  CHECK(std::abs(sp.mean) < 1e-14);
}

TEST_CASE("patch kinds have distinct names") {
  CHECK(std::string(patchKindName(PatchKind::Regular)) != patchKindName(PatchKind::Boundary));
  CHECK(std::string(patchKindName(PatchKind::PolarRing)) != patchKindName(PatchKind::PoleCap));
  CHECK(std::string(patchKindName(PatchKind::EndCap)) == "end-cap");
}

TEST_CASE("bicubic patch: a turned patch is the same surface, its orientation, K and H kept; edges follow") {
  std::mt19937 rng(17);
  Patch patch;
  for (Point& c : patch.cp) c = randomPoint(rng);
  patch.edgeLevelDelta = {1, -2, 3, 0};
  for (int turns = 0; turns < 4; ++turns) {
    CAPTURE(turns);
    const Patch turned = turnedPatch(patch, turns);
    for (double u : {0.0, 0.3, 1.0})
      for (double v : {0.0, 0.6, 1.0}) {
        double pu = u, pv = v;
        turnedParameter(&pu, &pv, turns);
        const SurfacePoint a = evaluatePatch(turned, u, v), b = evaluatePatch(patch, pu, pv);
        CHECK(glm::length(a.position - b.position) < 1e-12);
        CHECK(glm::length(a.normal - b.normal) < 1e-9);  // a turn keeps x_u x x_v's direction
        CHECK(a.gaussian == doctest::Approx(b.gaussian).epsilon(1e-9));
        CHECK(a.mean == doctest::Approx(b.mean).epsilon(1e-9));
      }
    // Edge s of the turned patch runs along edge s + turns of the patch.
    for (int s = 0; s < 4; ++s) CHECK(turned.edgeLevelDelta[size_t(s)] == patch.edgeLevelDelta[size_t((s + turns) % 4)]);
  }
  CHECK(turnedPatch(turnedPatch(patch, 3), 1).cp == patch.cp);
}
