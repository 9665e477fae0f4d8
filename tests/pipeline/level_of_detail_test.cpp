// Level of detail (pipeline/level_of_detail.h): per level the largest patch, halving a level near
// the features; the level drawn rises as the camera approaches a pole and never passes the level.
#include <doctest/doctest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "core/mesh/shapes.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/adaptive_refiner.h"
#include "pipeline/level_of_detail.h"

using namespace polarview;

TEST_CASE("level of detail: patch sizes halve a level; the drawn level follows the distance to the pole") {
  const PolyMesh cap = shapes::polarCap(12, 3);
  const AdaptiveRefinement refinement(cap, {Scheme::C2PS, 8, false});
  const std::vector<Patch> patches = extractPatches(refinement).patches;
  const DetailSizes sizes = detailSizes(patches);
  REQUIRE(sizes.levelSize.size() == 9);
  REQUIRE(!sizes.features.empty());
  // C2PS rings halve their radial width a level (paper (6): ring m spans r in [2, 4] 2^-m); the
  // finest level's largest patch is its cap, as wide as the ring before it.
  for (int m = 2; m <= 6; ++m) {
    CAPTURE(m);
    CHECK(sizes.levelSize[size_t(m + 1)] / sizes.levelSize[size_t(m)] == doctest::Approx(0.5).epsilon(0.1));
  }
  // The features are at the pole (the finest patches: its last rings and cap).
  for (const Point& feature : sizes.features) CHECK(glm::length(glm::dvec2(feature)) < 4.0 * sizes.levelSize[8]);

  OrbitCamera camera;
  camera.target = Point(0.0, 0.0, sizes.features[0].z);
  camera.pitchDeg = 60.0;
  int previous = -1;
  for (double distance : {1e3, 30.0, 3.0, 0.3, 3e-2, 3e-3, 3e-4}) {
    CAPTURE(distance);
    camera.distance = distance;
    const int drawn = levelToDraw(sizes, 8, camera, 600.0);
    CHECK(drawn >= previous);  // nearer: never shallower
    CHECK(drawn <= 8);
    // What the drawn level leaves out near the pole is below 3 pixels across (2 patches of its level).
    const double pixelsPerUnit = 600.0 / (2.0 * distance * std::tan(camera.fovDeg * 3.14159265358979 / 360.0));
    if (drawn < 8) CHECK(2.0 * sizes.levelSize[size_t(drawn)] * pixelsPerUnit < 3.0 * 1.01);
    if (drawn > 0) CHECK(2.0 * sizes.levelSize[size_t(drawn - 1)] * pixelsPerUnit >= 3.0 * 0.99);
    previous = drawn;
  }
  camera.distance = 1e3;
  CHECK(levelToDraw(sizes, 8, camera, 600.0) <= 1);
  camera.distance = 3e-4;
  CHECK(levelToDraw(sizes, 8, camera, 600.0) == 8);
  // Any difference allowed: level 0.
  CHECK(levelToDraw(sizes, 8, camera, 600.0, 1e300) == 0);
  // The pole behind the eye does not count: the eye 5 below it, looking down, draws level 0.
  camera.target = Point(0.0, 0.0, sizes.features[0].z - 10.0);
  camera.distance = 5.0;
  camera.pitchDeg = 89.0;
  CHECK(levelToDraw(sizes, 8, camera, 600.0) == 0);
  camera.pitchDeg = -89.0;  // the eye 15 below it, looking up at it: it counts again
  CHECK(levelToDraw(sizes, 8, camera, 600.0) > 0);
}

TEST_CASE("level of detail: a level without patches of its own (all end caps) is never drawn in place of a deeper one") {
  // A Blender-style cylinder: its 24-gon caps make every vertex extraordinary at level 0, so the
  // level-3 set has no level-0 patch; drawing level 0 instead showed its end caps, visibly another
  // surface (a scalloped cap, K off by its whole range).
  const AdaptiveRefinement refinement(shapes::ngonCylinder(24), {Scheme::CatmullClark, 3, false});
  const DetailSizes sizes = detailSizes(extractPatches(refinement).patches);
  REQUIRE(sizes.levelSize.size() == 4);
  REQUIRE(sizes.levelSize[0] == 0.0);
  OrbitCamera camera;
  for (double distance : {1e6, 30.0, 3.0}) {
    camera.distance = distance;
    CHECK(levelToDraw(sizes, 3, camera, 600.0) > 0);
  }
  // Any difference allowed: the first level with patches (level 2: the rim's valence-3 vertices keep
  // every face of levels 0 and 1 irregular).
  int first = 0;
  while (sizes.levelSize[size_t(first)] == 0.0) ++first;
  CHECK(first == 2);
  CHECK(levelToDraw(sizes, 3, camera, 600.0, 1e300) == first);
}
