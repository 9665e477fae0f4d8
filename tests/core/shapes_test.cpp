// The paper's test configurations (shapes::paperHeight): the pole's curvature has the sign and
// symmetry of the height function sampled.
#include <doctest/doctest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "core/mesh/shapes.h"
#include "core/spline/pole_taylor.h"
#include "core/subdiv/refine_steps.h"

using namespace polarview;

namespace {
PoleDifferential c2psPole(const std::string& height, int n) {
  const PolyMesh mesh = shapes::heightCap(n, 4, shapes::paperHeight(height));
  PolarGrid grid(n, 4);
  grid.pole = mesh.points[0];
  for (size_t k = 0; k < grid.ring.size(); ++k) grid.ring[k] = mesh.points[k + 1];
  return analyzePole(poleTaylorCoefficients(grid, Scheme::C2PS));
}
}  // namespace

TEST_CASE("shapes: the paper's height caps give poles curved as their functions") {
  for (int n : {6, 10, 20}) {
    INFO("valence " << n);
    const PoleDifferential bowl = c2psPole("paraboloid", n), saddle = c2psPole("saddle", n);
    CHECK(bowl.gaussian > 0.0);
    CHECK(bowl.mean > 0.0);
    CHECK(saddle.gaussian < 0.0);
    CHECK(std::abs(saddle.mean) < 1e-12);
    // The monkey saddle (angular mode 3) and the 4th-order saddle (mode 4) have no quadratic part
    // at the origin; sampled on n columns, mode 4 aliases to mode 2 at n = 6 (4 = -2 mod 6), where
    // the pole does get curvature.
    for (const char* flat : {"monkey", "saddle4"}) {
      if (n == 6 && std::string(flat) == "saddle4") {
        CHECK(std::abs(c2psPole(flat, n).gaussian) > 1e-3);
        continue;
      }
      const PoleDifferential d = c2psPole(flat, n);
      CHECK(std::abs(d.gaussian) < 1e-12);
      CHECK(std::abs(d.mean) < 1e-12);
    }
    CHECK(std::abs(glm::length(c2psPole("convex", n).normal) - 1.0) < 1e-12);
  }
  CHECK_FALSE(shapes::paperHeight("sphere"));
}
