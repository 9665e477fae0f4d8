// The model's analysis (pipeline/model_analysis.h): made once per model by makeModel, owned by it,
// shared by its copies and edits; the same answers as building the tables and refinements anew.
#include <doctest/doctest.h>

#include <filesystem>
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "core/mesh/manifold_split.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/shapes.h"
#include "core/subdiv/adaptive_refiner.h"
#include "core/subdiv/polar_config.h"
#include "pipeline/model_analysis.h"
#include "pipeline/model.h"
#include "pipeline/surface_key.h"
#include "pipeline/level_limits.h"
#include "pipeline/surface_build.h"

namespace polarview {
namespace {

// A small budget: the estimates stop early on the larger assets, and the test stays quick.
constexpr size_t kBudget = 200000;

// The mushroom with a triangle on one of its stem's edges (three faces there: refined as its split).
PolyMesh nonManifoldMushroom() {
  PolyMesh mesh = shapes::mushroom(8);
  const Index f = mesh.faceCount() - 1;
  const Index a = mesh.faceVerts[size_t(mesh.faceStart[f])], b = mesh.faceVerts[size_t(mesh.faceStart[f]) + 1];
  mesh.points.push_back(mesh.points[size_t(a)] + Point(0.1, 0.2, 0.3));
  mesh.addFace({b, a, Index(mesh.points.size() - 1)});
  return mesh;
}

// Every asset, the non-manifold mushroom and a cube (no poles).
std::vector<std::pair<std::string, PolyMesh>> meshes() {
  std::vector<std::pair<std::string, PolyMesh>> all;
  for (const auto& entry : std::filesystem::directory_iterator(POLARVIEW_ASSET_DIR))
    if (entry.path().extension() == ".obj") all.emplace_back(entry.path().filename().string(), loadObj(entry.path().string()));
  all.emplace_back("non-manifold mushroom", nonManifoldMushroom());
  all.emplace_back("cube", shapes::cube());
  return all;
}

constexpr SchemeChoice kChoices[] = {SchemeChoice::CatmullClark,        SchemeChoice::C2PS, SchemeChoice::C2PSUniformFirstStep,
                                     SchemeChoice::RTS, SchemeChoice::RTSUniformFirstStep, SchemeChoice::BPS};

}  // namespace

TEST_CASE("model analysis: two models of the same generation (two viewers in one process) keep their own answers") {
  // Both viewers number their first model 1; face estimates and poles once memoized by generation
  // were the first model's for the second.
  const Model cube = makeModel(std::make_shared<const PolyMesh>(shapes::cube()), "cube", 1);
  const Model cap = makeModel(std::make_shared<const PolyMesh>(shapes::polarCap(8, 3)), "cap", 1);
  for (const Model* model : {&cube, &cap}) {
    CAPTURE(model->name);
    const std::vector<size_t> fresh =
        estimateAdaptiveFaceCounts(*model->mesh, refineOptionsFor(SchemeChoice::C2PS, kMaxLevel), 5000, kMeasuredLevels);
    for (int level = 0; level <= kMaxLevel; ++level) CHECK(estimatedLevelFaces(*model, SchemeChoice::C2PS, level, 5000) == fresh[size_t(level)]);
    int deepest = 0;
    while (deepest < kMaxLevel && fresh[size_t(deepest) + 1] <= 5000) ++deepest;
    CHECK(deepestLevel(*model, SchemeChoice::C2PS, 5000) == deepest);
  }
  // RTS is not C2 at the pole: the cap's view shows a deeper patch level, the cube's the level asked.
  CHECK(patchLevelFor(cube, SchemeChoice::RTS, 2, kDefaultFaceBudget) == 2);
  CHECK(patchLevelFor(cap, SchemeChoice::RTS, 2, kDefaultFaceBudget) == kNonC2CapLevel);
}

TEST_CASE("model analysis: the same tables, poles, radial flag and estimates as made anew, on every asset") {
  for (const auto& [name, mesh] : meshes()) {
    CAPTURE(name);
    const ModelAnalysis analysis(mesh, name);
    REQUIRE(analysis.error().empty());
    ManifoldSplit split;
    MeshTopology topology;
    const PolyMesh& base = refinableMesh(mesh, split, topology, name);
    CHECK(analysis.split().empty() == split.empty());
    CHECK(analysis.topology().edgeCount == topology.edgeCount);
    const std::vector<PolarConfig> configs = findPolarConfigs(base, topology);
    REQUIRE(analysis.polarConfigs().size() == configs.size());
    for (const SchemeTraits& traits : schemeTable()) {
      bool refines = false;
      for (const PolarConfig& config : configs) refines = refines || schemeRefinesPole(traits.scheme, config);
      CHECK(analysis.refinesPoles(traits.scheme) == refines);
    }
    // Manifold meshes: refinesRadially's own answer; split ones: the refiner's (level 0 is the split).
    if (split.empty()) CHECK(analysis.radialForRtsBps() == refinesRadially(mesh, Scheme::RTS));
    CHECK(analysis.radialForRtsBps() == AdaptiveRefinement(mesh, refineOptionsFor(SchemeChoice::RTS, 0)).radialOnly());
    for (SchemeChoice choice : kChoices) {
      CAPTURE(int(choice));
      const std::vector<size_t> fresh = estimateAdaptiveFaceCounts(mesh, refineOptionsFor(choice, kMaxLevel), kBudget, 2);
      for (int level = 0; level <= kMaxLevel; ++level) CHECK(analysis.estimatedFaces(mesh, choice, level, kBudget, 2) == fresh[size_t(level)]);
    }
  }
}

TEST_CASE("model analysis: refinements from the analysed base equal those made from the mesh, after edits too") {
  for (const auto& [name, mesh] : meshes()) {
    CAPTURE(name);
    const ModelAnalysis analysis(mesh, name);
    // The analysis reads no points: an edit of the mesh (a split's copies read the edited points).
    PolyMesh edited = mesh;
    for (size_t v = 0; v < edited.points.size(); v += 3) edited.points[v] += Point(0.01 * double(v % 7), -0.02, 0.015);
    for (SchemeChoice choice : kChoices) {
      CAPTURE(int(choice));
      const RefineOptions options = refineOptionsFor(choice, 2);
      const AdaptiveRefinement made(edited, options, name, kBudget * 4);
      const AdaptiveRefinement prepared(edited, analysis.preparedBase(edited), options, name, kBudget * 4);
      REQUIRE(prepared.levelCount() == made.levelCount());
      CHECK(prepared.totalFaces() == made.totalFaces());
      CHECK(prepared.radialOnly() == made.radialOnly());
      for (int m = 0; m < made.levelCount(); ++m) {
        REQUIRE(prepared.level(m).mesh.faceVerts == made.level(m).mesh.faceVerts);
        CHECK(prepared.level(m).poles.size() == made.level(m).poles.size());
        for (Index v = 0; v < made.level(m).mesh.vertexCount(); ++v)
          REQUIRE(prepared.level(m).absolutePoint(v) == made.level(m).absolutePoint(v));
      }
    }
  }
}

TEST_CASE("model analysis: copies and edits of a model share it; threads asking at once get the single thread's answers") {
  Model model = makeModel(std::make_shared<const PolyMesh>(shapes::mushroom(12)), "mushroom", 1);
  const Model copy = model;
  auto moved = std::make_shared<PolyMesh>(*model.mesh);
  moved->points[5] += Point(0.1, 0.0, 0.0);
  model.mesh = moved;  // what the viewer's commitEditedPoints does
  ++model.points;
  CHECK(model.analysis == copy.analysis);
  std::vector<std::future<int>> asked;
  for (SchemeChoice choice : kChoices)
    asked.push_back(std::async(std::launch::async, [&model, choice] { return deepestLevel(model, choice, kBudget); }));
  const Model alone = makeModel(std::make_shared<const PolyMesh>(shapes::mushroom(12)), "mushroom", 1);
  for (size_t k = 0; k < asked.size(); ++k) CHECK(asked[k].get() == deepestLevel(alone, kChoices[k], kBudget));
  // A Model made without its analysis is refused, not refined without one.
  Model bare;
  bare.mesh = std::make_shared<const PolyMesh>(shapes::cube());
  bare.generation = 1;
  CHECK_THROWS_AS(deepestLevel(bare, SchemeChoice::C2PS, kBudget), std::invalid_argument);
}

TEST_CASE("model analysis: a mesh that cannot be refined keeps the reason, estimates nothing and the build says why") {
  PolyMesh broken;
  broken.points = {Point(0.0), Point(1.0, 0.0, 0.0), Point(0.0, 1.0, 0.0)};
  broken.addFace({0, 1, 2});
  broken.addFace({0, 1});  // two corners: not even its manifold split refines it
  const Model model = makeModel(std::make_shared<const PolyMesh>(broken), "broken", 1);
  REQUIRE(model.analysis->error().find("at least 3 needed") != std::string::npos);
  CHECK(estimatedLevelFaces(model, SchemeChoice::C2PS, 3) == 0);
  CHECK_FALSE(model.analysis->refinesPoles(Scheme::C2PS));
  CHECK_THROWS_WITH(buildSurface(model, SurfaceKey{1, SchemeChoice::C2PS, 1}, kDefaultFaceBudget), model.analysis->error().c_str());
}

}  // namespace polarview
