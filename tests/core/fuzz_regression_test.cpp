// Regression tests for what tests/fuzz/fuzz_pipeline.cpp found: each case is a fuzzer finding cut
// down to the failing core call, with the mesh or numbers inline.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "core/mesh/shapes.h"
#include "core/spline/pole_taylor.h"
#include "core/subdiv/refiner.h"

using namespace polarview;

namespace {

bool allFinite(const Point& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

}  // namespace

// analyzePole took E G - F^2 as the difference of two products: for a tangent plane whose p1 and
// p2 are nearly parallel (but not parallel: the normal is defined) the difference cancels to 0 and
// K and H came out inf or NaN with curvatureDefined = true. |p1 x p2|^2 is the same number without
// the cancellation.
TEST_CASE("fuzz regression: analyzePole gives finite K and H at a nearly degenerate tangent plane") {
  TaylorCoefficients t;
  t.p[1] = Point(1.0, 0.0, 0.0);
  t.p[2] = Point(0.5, 5e-10, 0.0);  // p1 x p2 = (0, 0, 5e-10)
  t.p[3] = Point(0.0, 0.0, 1.0);    // x_xx = x_yy = (0, 0, 2), x_xy = 0
  const PoleDifferential d = analyzePole(t);
  CHECK(d.normal == Point(0.0, 0.0, 1.0));
  REQUIRE(d.curvatureDefined);
  // K = (L N - M^2) / |p1 x p2|^2 = 4 / 2.5e-19; H = (E N - 2 F M + G L) / (2 |p1 x p2|^2).
  CHECK(d.gaussian == doctest::Approx(4.0 / 2.5e-19).epsilon(1e-6));
  CHECK(d.mean == doctest::Approx((1.0 * 2.0 + 0.25 * 2.0) / (2.0 * 2.5e-19)).epsilon(1e-6));
}

// The fuzzer's input: a globe (valence 8, 3 links) with one vertex of the bottom pole's 3-link
// moved to x = -8.7e17 (a mistyped digit). Its p1..p5 are then dominated by that one vertex and
// the bottom pole's p1, p2 nearly parallel: `polarview pole` reported K = inf there.
TEST_CASE("fuzz regression: pole curvature of a globe with one far vertex is finite or undefined") {
  PolyMesh mesh = shapes::globe(8, 3);
  mesh.points[21].x = -870710678118654757.0;
  for (Scheme scheme : {Scheme::C2PS, Scheme::RTS}) {
    const Refinement refinement(mesh, {scheme, 0, false});
    const RefinedLevel& level = refinement.level(0);
    REQUIRE(level.poles.size() == 2);
    for (size_t k = 0; k < level.poles.size(); ++k) {
      INFO(std::string(schemeName(scheme)), " pole ", level.poles[k].pole);
      const PoleDifferential d = analyzePole(level.poleTaylor[k]);
      CHECK(allFinite(d.limit));
      CHECK(allFinite(d.normal));
      if (d.curvatureDefined) {
        CHECK(std::isfinite(d.gaussian));
        CHECK(std::isfinite(d.mean));
      } else {
        CHECK(d.gaussian == 0.0);
        CHECK(d.mean == 0.0);
      }
    }
  }
}
