// The level driver: detection on real-looking meshes, C2PS inside Catmull-Clark equals the grid
// rules, RTS/BPS radial refinement, budgets.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "core/mesh/input_error.h"
#include "core/mesh/shapes.h"
#include "core/subdiv/c2ps.h"
#include "core/subdiv/polar_config.h"
#include "core/subdiv/refiner.h"
#include "core/subdiv/rts.h"

using namespace polarview;

namespace {

double maxDistance(const PolarGrid& a, const PolarGrid& b, int links) {
  double d = glm::length(a.pole - b.pole);
  for (int i = 1; i <= links; ++i)
    for (int j = 0; j < a.n; ++j) d = std::max(d, glm::length(a.q(i, j) - b.q(i, j)));
  return d;
}

PolarGrid gridOf(const RefinedLevel& level, size_t pole, int links) {
  const PolarConfig& c = level.poles[pole];
  PolarGrid g(c.valence, links);
  g.pole = level.mesh.points[c.pole];
  for (int i = 1; i <= links; ++i)
    for (int j = 0; j < c.valence; ++j) g.q(i, j) = level.mesh.points[c.links[size_t(i - 1) * c.valence + j]];
  return g;
}

// A globe whose points are jittered, so no symmetry hides a wrong index.
PolyMesh jitteredGlobe(int n, int links, unsigned seed) {
  PolyMesh mesh = shapes::globe(n, links);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.08, 0.08);
  for (Point& p : mesh.points) p += Point(jitter(rng), jitter(rng), jitter(rng));
  return mesh;
}

}  // namespace

TEST_CASE("detection finds both poles of a globe, with their links and the opposite pole") {
  PolyMesh mesh = shapes::globe(12, 7);
  MeshTopology topo = buildTopology(mesh);
  std::vector<PolarConfig> configs = findPolarConfigs(mesh, topo);
  REQUIRE(configs.size() == 2);
  for (const PolarConfig& c : configs) {
    CHECK(c.refinable);
    CHECK(c.valence == 12);
    CHECK(c.linkCount == 7);
    CHECK(c.outer == PolarConfig::Outer::Pole);
  }
  CHECK(configs[0].oppositePole == configs[1].pole);
}

TEST_CASE("detection: an open cap ends at its boundary; a pole with a 5-valent 1-link vertex falls back") {
  PolyMesh cap = shapes::polarCap(8, 2);
  MeshTopology topo = buildTopology(cap);
  auto configs = findPolarConfigs(cap, topo);
  REQUIRE(configs.size() == 1);
  CHECK(configs[0].refinable);
  CHECK(configs[0].outer == PolarConfig::Outer::Boundary);
  CHECK(configs[0].linkCount == 2);

  // Too few links: a fan with no quad ring.
  PolyMesh fan = shapes::polarCap(6, 1);
  MeshTopology fanTopo = buildTopology(fan);
  auto fanConfigs = findPolarConfigs(fan, fanTopo);
  REQUIRE(fanConfigs.size() == 1);
  CHECK_FALSE(fanConfigs[0].refinable);
  CHECK(fanConfigs[0].reason.find("boundary") != std::string::npos);
}

TEST_CASE("detection: every rejected candidate says why by kind, every refinable one has none") {
  // An octahedron: each vertex is a fan of 4 triangles whose rim is 4-valent but ringed by triangles.
  PolyMesh octahedron;
  octahedron.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (auto [a, b, c] : {std::array<Index, 3>{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}})
    octahedron.addFace({a, b, c});
  auto configs = findPolarConfigs(octahedron, buildTopology(octahedron));
  REQUIRE(configs.size() == 6);
  for (const PolarConfig& c : configs) {
    CHECK_FALSE(c.refinable);
    CHECK(c.rejection == PolarRejection::Link1NotTwoQuads);
    CHECK(std::string(polarRejectionKey(c.rejection)) == "link1_not_2_triangles_2_quads");
  }

  // A fan ringed by a boundary; bipyramids (globes with one link: the apexes' rims are ringed by
  // triangles, the equator's rims hold an apex); refinable globes.
  PolyMesh fan = shapes::polarCap(6, 1);
  auto open = findPolarConfigs(fan, buildTopology(fan));
  REQUIRE(open.size() == 1);
  CHECK(open[0].rejection == PolarRejection::Link1OnBoundary);
  for (int n : {3, 8}) {
    CAPTURE(n);
    PolyMesh bipyramid = shapes::globe(n, 1);
    auto candidates = findPolarConfigs(bipyramid, buildTopology(bipyramid));
    CHECK(candidates.size() == size_t(n + 2));
    for (const PolarConfig& c : candidates) {
      CHECK_FALSE(c.refinable);
      CHECK((c.rejection == PolarRejection::Link1NotTwoQuads || c.rejection == PolarRejection::Link1NotFourValent));
      CHECK_FALSE(c.reason.empty());
    }
    PolyMesh refinable = shapes::globe(n, 4);
    for (const PolarConfig& c : findPolarConfigs(refinable, buildTopology(refinable))) {
      CHECK(c.refinable);
      CHECK(c.rejection == PolarRejection::None);
      CHECK(c.reason.empty());
    }
  }
}

TEST_CASE("detection on the mushroom: one pole, regular links down to the stem's closing grid") {
  PolyMesh mesh = shapes::mushroom(12);
  MeshTopology topo = buildTopology(mesh);
  auto configs = findPolarConfigs(mesh, topo);
  REQUIRE(configs.size() == 1);
  CHECK(configs[0].refinable);
  CHECK(configs[0].outer == PolarConfig::Outer::Mesh);
  CHECK(configs[0].linkCount == 9);
  CHECK(configs[0].regularLinks == 8);
}

TEST_CASE("c2ps inside Catmull-Clark equals the grid rules (1)-(5), (29) on links 0..5") {
  for (int n : {3, 5, 8, 13}) {
    PolyMesh mesh = jitteredGlobe(n, 12, 7u + n);
    Refinement r(mesh, {Scheme::C2PS, 2, false});
    PolarGrid grid = gridOf(r.level(0), 0, 6);
    for (int m = 1; m <= 2; ++m) {
      grid = c2ps::refineGrid(grid, false);
      grid.links = 6;
      grid.ring.resize(size_t(6) * grid.n);
      REQUIRE(r.level(m).poles[0].valence == n << m);
      PolarGrid fromMesh = gridOf(r.level(m), 0, 5);
      CAPTURE(n);
      CAPTURE(m);
      CHECK(maxDistance(grid, fromMesh, 5) < 1e-13);
    }
  }
}

TEST_CASE("c2ps doubles the polar valence and keeps every new 1-link vertex 4-valent") {
  Refinement r(shapes::mushroom(12), {Scheme::C2PS, 3, false});
  for (int m = 0; m <= 3; ++m) {
    const RefinedLevel& level = r.level(m);
    REQUIRE(level.poles.size() == 1);
    const PolarConfig& c = level.poles[0];
    CHECK(c.valence == 12 << m);
    CHECK(level.topology.valence(c.pole) == c.valence);
    for (int j = 0; j < c.valence; ++j) CHECK(level.topology.valence(c.links[j]) == 4);
    // Detection on the refined mesh agrees with the derived configuration.
    auto found = findPolarConfigs(level.mesh, level.topology);
    REQUIRE(found.size() == 1);
    CHECK(found[0].pole == c.pole);
    CHECK(found[0].valence == c.valence);
  }
}

TEST_CASE("rts refines a globe radially with the valence fixed, equal to the grid rules") {
  PolyMesh mesh = jitteredGlobe(7, 6, 3u);
  Refinement r(mesh, {Scheme::RTS, 2, false});
  REQUIRE(r.radialOnly());
  PolarGrid grid = gridOf(r.level(0), 0, 6);
  for (int m = 1; m <= 2; ++m) {
    grid = rts::refineGrid(grid, false);
    const RefinedLevel& level = r.level(m);
    CHECK(level.mesh.faceCount() == (49 << m));  // radial: faces double per level
    REQUIRE(level.poles.size() == 2);
    CHECK(level.poles[0].valence == 7);
    PolarGrid fromMesh = gridOf(level, 0, 4);
    CHECK(maxDistance(grid, fromMesh, 4) < 1e-13);
  }
}

TEST_CASE("a level over the memory budget is refused with an input error") {
  PolyMesh mesh = shapes::cube();
  CHECK_THROWS_AS(Refinement(mesh, {Scheme::CatmullClark, 12, false}, "cube.obj", 1000000), InputError);
  CHECK(estimateFaceCount(mesh, {Scheme::CatmullClark, 2, false}) >= 96);
}

TEST_CASE("face estimates: RTS/BPS on caps and globes grow x2 a level (radial), exactly; elsewhere x4") {
  const PolyMesh globe = shapes::globe(16, 7), cap = shapes::polarCap(12, 6), mushroom = shapes::mushroom(12);
  CHECK(refinesRadially(globe, Scheme::RTS));
  CHECK(refinesRadially(cap, Scheme::BPS));
  CHECK(!refinesRadially(mushroom, Scheme::RTS));       // CC stem: periodic refinement, x4
  CHECK(!refinesRadially(globe, Scheme::C2PS));          // the valence doubles: x4
  CHECK(!refinesRadially(shapes::globe(4, 5), Scheme::RTS));  // valence 4: Catmull-Clark refines it
  for (const Scheme scheme : {Scheme::RTS, Scheme::BPS})
    for (const PolyMesh* mesh : {&globe, &cap})
      for (int levels = 1; levels <= 5; ++levels) {
        RefineOptions options;
        options.scheme = scheme;
        options.levels = levels;
        const Refinement refinement(*mesh, options);
        REQUIRE(refinement.radialOnly());
        CAPTURE(levels);
        CHECK(estimateFaceCount(*mesh, options, true) == size_t(refinement.finest().mesh.faceCount()));
      }
  // The refiner's own budget uses the radial estimate: RTS level 12 of the globe (524288 faces)
  // fits a budget Catmull-Clark growth would exceed 100 times over.
  RefineOptions deep;
  deep.scheme = Scheme::RTS;
  deep.levels = 12;
  CHECK(estimateFaceCount(globe, deep) > 100 * estimateFaceCount(globe, deep, true));
  CHECK_NOTHROW(Refinement(shapes::globe(6, 3), deep, "<globe>", size_t(1) << 20));
}
