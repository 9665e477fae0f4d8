// Fig. 14: Catmull-Clark extraordinary vertices converted to polar configurations.
#include <doctest/doctest.h>

#include <map>

#include "core/mesh/ev_to_polar.h"
#include "core/mesh/shapes.h"
#include "core/mesh/topology.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/catmull_clark.h"
#include "core/subdiv/polar_config.h"
#include "core/subdiv/refiner.h"
#include "support/reference_catmull_clark.h"

using namespace polarview;

namespace {

// The cube refined twice: eight valence-3 extraordinary vertices far enough apart to convert all.
PolyMesh separatedCorners() {
  PolyMesh mesh = shapes::cube();
  for (int step = 0; step < 2; ++step) mesh = reference::refineCatmullClark(mesh, buildTopology(mesh));
  return mesh;
}

std::map<int, int> valenceCounts(const PolyMesh& mesh) {
  const MeshTopology topo = buildTopology(mesh);
  std::map<int, int> counts;
  for (Index v = 0; v < mesh.vertexCount(); ++v) ++counts[topo.valence(v)];
  return counts;
}

}  // namespace

TEST_CASE("ev to polar (Fig. 14a): each n-valent vertex becomes a 2n-valent pole and n 5-valent vertices") {
  const PolyMesh mesh = separatedCorners();
  const PolarConversion conversion = convertExtraordinaryToPolar(mesh, false);
  CHECK(conversion.converted.size() == 8);
  CHECK(conversion.skipped.empty());
  const MeshTopology topo = buildTopology(conversion.mesh);  // a valid manifold
  int poles = 0;
  for (const PolarConfig& config : findPolarConfigs(conversion.mesh, topo)) {
    if (!config.refinable) continue;
    ++poles;
    CHECK(config.valence == 6);
    CHECK(config.linkCount >= 2);
    CHECK(schemeRefinesPole(Scheme::C2PS, config));
    // Every second 2-link vertex is one of the n new 5-valent extraordinary vertices.
    int fiveValent = 0;
    for (int j = 0; j < config.valence; ++j) fiveValent += topo.valence(config.links[size_t(config.valence + j)]) == 5;
    CHECK(fiveValent == 3);
  }
  CHECK(poles == 8);
  const std::map<int, int> before = valenceCounts(mesh), after = valenceCounts(conversion.mesh);
  CHECK(before.at(3) == 8);
  CHECK(after.count(3) == 0);
  CHECK(after.at(5) == 8 * 3);
  CHECK(after.at(6) == 8);
  // C2PS refines them as poles: a cap of 2n sectors per pole at the finest level.
  const PatchSet patches = extractPatches(Refinement(conversion.mesh, {Scheme::C2PS, 2, false}));
  CHECK(patches.count(PatchKind::PoleCap) == 8 * 6 * 4);
}

TEST_CASE("ev to polar (Fig. 14c): each n-valent vertex becomes an n-valent pole ringed by n pentagons") {
  const PolyMesh mesh = separatedCorners();
  const PolarConversion conversion = convertExtraordinaryToPolar(mesh, true);
  CHECK(conversion.converted.size() == 8);
  int pentagons = 0;
  for (Index f = 0; f < conversion.mesh.faceCount(); ++f) pentagons += conversion.mesh.faceSize(f) == 5;
  CHECK(pentagons == 8 * 3);
  int poles = 0;
  for (const PolarConfig& config : findPolarConfigs(conversion.mesh, buildTopology(conversion.mesh)))
    if (config.refinable) {
      ++poles;
      CHECK(config.valence == 3);
      CHECK(schemeRefinesPole(Scheme::C2PS, config));
    }
  CHECK(poles == 8);
}

TEST_CASE("ev to polar: overlapping regions are skipped, poles and regular vertices left alone") {
  // The plain cube: neighbouring corners share quads, so only corners with disjoint regions convert.
  const PolarConversion cube = convertExtraordinaryToPolar(shapes::cube(), false);
  CHECK(cube.converted.size() + cube.skipped.size() == 8);
  CHECK(cube.converted.size() >= 1);
  CHECK_NOTHROW(buildTopology(cube.mesh));
  // A globe has poles (triangle fans) and 4-valent vertices only: nothing to convert.
  const PolyMesh globe = shapes::globe(8, 4);
  const PolarConversion none = convertExtraordinaryToPolar(globe, false);
  CHECK(none.converted.empty());
  CHECK(none.mesh.faceVerts == globe.faceVerts);
}
