// CPU curvature sampling and the automatic colour-map range (no GL needed).
#include <doctest/doctest.h>

#include <algorithm>
#include <numeric>

#include "render_test_support.h"

namespace polarview {
namespace {

TEST_CASE("curvature range: samples of a quadratic graph are its closed-form K and H") {
  // z = 0.3 x^2 - 0.2 y^2 over 2 x 2 unit patches starting at (-1, -1); 3 x 3 cell centres each.
  const auto patches = test::graphPatches([](double x, double y) { return 0.3 * x * x - 0.2 * y * y; },
                                          2, 2, -1.0, -1.0, 1.0);
  const std::vector<float> K = sampleCurvature(patches, ShadingParams::Mode::Gaussian, 3);
  const std::vector<float> H = sampleCurvature(patches, ShadingParams::Mode::Mean, 3);
  REQUIRE(K.size() == 4 * 9);
  REQUIRE(H.size() == 4 * 9);
  size_t k = 0;
  for (int cj = 0; cj < 2; ++cj)
    for (int ci = 0; ci < 2; ++ci)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i, ++k) {
          const double x = -1.0 + ci + (i + 0.5) / 3, y = -1.0 + cj + (j + 0.5) / 3;
          const auto exact = test::graphCurvature(0.6 * x, -0.4 * y, 0.6, -0.4, 0.0);
          CHECK(K[k] == doctest::Approx(exact.gaussian).epsilon(1e-6));
          CHECK(H[k] == doctest::Approx(exact.mean).epsilon(1e-6));
        }
}

TEST_CASE("curvature range: the suggested range covers the requested quantile of |values|") {
  std::vector<float> values(1001);
  std::iota(values.begin(), values.end(), -500.0f);  // -500..500: |v| has quantiles 0..500
  std::reverse(values.begin(), values.end());
  CHECK(suggestCurvatureRange(values, 1.0f) == 500.0f);
  CHECK(suggestCurvatureRange(values, 0.5f) == doctest::Approx(250.0f).epsilon(0.01));
  CHECK(suggestCurvatureRange(values, 0.9f) == doctest::Approx(450.0f).epsilon(0.01));
  CHECK(suggestCurvatureRange({}, 0.9f) == 1.0f);             // nothing sampled
  CHECK(suggestCurvatureRange({0.0f, 0.0f}, 0.9f) == 1.0f);   // a plane: no zero-width range
}

}  // namespace
}  // namespace polarview
