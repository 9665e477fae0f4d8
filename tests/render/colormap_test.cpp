// The curvature colour maps: the paper map's green band at zero (Fig. 13's caption: "the green range
// straddles Gauss zero curvature, while negative curvature is blue and positive is red"), on the CPU
// mirror and in the shader (run under xvfb-run).
#include <doctest/doctest.h>

#include <string>

#include "render/framebuffer_capture.h"
#include "render_test_support.h"

namespace polarview {
namespace {

using Map = ShadingParams::ColorMap;

TEST_CASE("paper colour map: one green on a band around zero, blue below it, red above it") {
  const float range = 2.0f;
  const glm::vec3 zero = colorMapCpu(Map::Paper, 0.0f, range);
  CHECK(zero.y > 0.9f);
  CHECK(zero.x == 0.0f);
  CHECK(zero.z == 0.0f);
  // Within 10% of the range on either side: exactly the zero colour.
  for (float t : {-0.099f, -0.05f, -0.001f, 0.001f, 0.05f, 0.099f}) {
    CAPTURE(t);
    CHECK(colorMapCpu(Map::Paper, t * range, range) == zero);
  }
  // Beyond it the hue moves on (x, y, z: red, green, blue): towards blue below zero, red above,
  // saturating at the ends.
  for (float t : {0.2f, 0.5f, 0.8f}) {
    CAPTURE(t);
    const glm::vec3 below = colorMapCpu(Map::Paper, -t * range, range), above = colorMapCpu(Map::Paper, t * range, range);
    CHECK(below.z > 0.0f);
    CHECK(below.x == 0.0f);
    CHECK(above.x > 0.0f);
    CHECK(above.z == 0.0f);
  }
  CHECK(colorMapCpu(Map::Paper, -range, range) == glm::vec3(0.0f, 0.0f, 0.95f));
  CHECK(colorMapCpu(Map::Paper, range, range) == glm::vec3(0.95f, 0.0f, 0.0f));
  CHECK(colorMapCpu(Map::Paper, 3.0f * range, range) == colorMapCpu(Map::Paper, range, range));
  // The band follows each side's own range (--range MIN:MAX).
  CHECK(colorMapCpu(Map::Paper, -0.09f, ColourInterval{-1.0, 4.0}) == zero);
  CHECK(colorMapCpu(Map::Paper, -0.2f, ColourInterval{-1.0, 4.0}) != zero);
}

TEST_CASE("paper colour map: the shader draws the green band as the CPU mirror does") {
  test::glContext();
  auto renderer = test::makeRenderer();
  // A paraboloid cap of K = 4 at the pole, seen from above with the pole on the centre pixel.
  renderer->setPatches(test::paraboloidCap(8, 1.0, 1.1));
  const int size = 65;
  const ViewParams view = test::topView(glm::dvec3(0.0), 1.2, {0, 0, size, size});
  // K = 4 at t = 0.04, 0.08 (in the band), 0.2, 0.5 (outside).
  for (float range : {100.0f, 50.0f, 20.0f, 8.0f}) {
    CAPTURE(range);
    auto shading = test::flatCurvature(ShadingParams::Mode::Gaussian, Map::Paper, range);
    shading.fixedTessLevel = 16;
    OffscreenTarget target;
    std::string error;
    REQUIRE_MESSAGE(target.create(size, size, 1, &error), error);
    target.bindAndClear(0, 0, 0, 0);
    renderer->draw(view, shading, test::surfaceOnly());
    const RgbaImage image = target.read();
    OffscreenTarget::bindDefault();
    const uint8_t* pole = image.at(size / 2, size / 2);
    CHECK(test::colorDistance(pole, colorMapCpu(Map::Paper, 4.0f, range)) <= 2);
    if (range >= 50.0f) CHECK(test::colorDistance(pole, colorMapCpu(Map::Paper, 0.0f, range)) <= 2);
  }
}

}  // namespace
}  // namespace polarview
