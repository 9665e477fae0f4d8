// The GL-free surface pipeline (pipeline/model.h, level_limits.h, surface_build.h, surface_job.h):
// what a view shows, built, stepped between levels, refreshed after edits, and the statistics behind
// the colour range. No display.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/mesh/obj_io.h"
#include "core/mesh/shapes.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/adaptive_refiner.h"
#include "core/subdiv/polar_config.h"
#include "core/mesh/topology.h"
#include "pipeline/model.h"
#include "pipeline/surface_key.h"
#include "pipeline/level_limits.h"
#include "pipeline/weighted_statistics.h"
#include "pipeline/surface_build.h"

namespace polarview {
namespace {

// The viewer's default model (assets/default.obj) as a Model of generation 1.
Model defaultModel() {
  const std::string path = std::string(POLARVIEW_ASSET_DIR) + "/default.obj";
  return makeModel(std::make_shared<const PolyMesh>(loadObj(path)), path, 1);
}

// Weighted share of values above `bound`, below `-bound`, at or above it, at or below `-bound`.
struct TailWeights {
  double above = 0, below = 0, atOrAbove = 0, atOrBelow = 0, total = 0;
};

TailWeights tails(const std::vector<double>& values, const std::vector<double>& weights, double bound) {
  TailWeights t;
  for (size_t i = 0; i < values.size(); ++i) {
    t.total += weights[i];
    if (values[i] > bound) t.above += weights[i];
    if (values[i] < -bound) t.below += weights[i];
    if (values[i] >= bound) t.atOrAbove += weights[i];
    if (values[i] <= -bound) t.atOrBelow += weights[i];
  }
  return t;
}

}  // namespace

TEST_CASE("automatic colour range: each tail saturates on at most 1 - P of the weight and the range is the smallest such") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int trial = 0; trial < 400; ++trial) {
    const size_t n = 1 + rng() % 300;
    const float shift = 4.0f * u(rng) - 2.0f, scale = std::exp(6.0f * u(rng) - 3.0f);
    std::vector<double> values(n), weights(n);
    for (size_t i = 0; i < n; ++i) {
      values[i] = scale * (shift + std::tan(3.0f * (u(rng) - 0.5f)));  // heavy tails on both sides
      weights[i] = float(1 + rng() % 8);  // small integers: exact sums
    }
    const float quantile = 0.5f + 0.5f * u(rng);
    const double range = weightedSymmetricRange(values, weights, quantile);
    CAPTURE(trial);
    REQUIRE(range > 0.0f);
    TailWeights t = tails(values, weights, range);
    const double allowed = (1.0 - quantile) * t.total;
    CHECK(t.above <= allowed + 1e-9 * t.total);
    CHECK(t.below <= allowed + 1e-9 * t.total);
    // Smallest: at the range itself one tail reaches its share (unless all values are 0).
    CHECK((t.atOrAbove >= allowed - 1e-9 * t.total || t.atOrBelow >= allowed - 1e-9 * t.total));
  }
}

TEST_CASE("colour histogram: area-weighted bins over the bar's two slopes, values beyond in the end bins") {
  // below 2, above 1: -1 -> t = -0.5 (bin 1 of 4), 0.5 -> t = 0.5 (bin 3), 3 -> saturates into bin 3.
  const std::vector<double> values{-1.0, 0.5, 3.0, -8.0}, weights{1.0, 2.0, 1.0, 0.5};
  const std::vector<float> bins = weightedHistogram(values, weights, ColourInterval{-2.0, 1.0}, 4);
  REQUIRE(bins.size() == 4);
  CHECK(bins[0] == doctest::Approx(0.5f / 3.0f));  // -8 saturates into the first bin
  CHECK(bins[1] == doctest::Approx(1.0f / 3.0f));
  CHECK(bins[2] == 0.0f);
  CHECK(bins[3] == doctest::Approx(1.0f));
  CHECK(weightedPercentile(values, weights, 0.5f) == 0.5f);  // running weight 0.5, 1.5, 3.5 of 4.5
  CHECK(weightedPercentile(values, weights, 0.0f) == -8.0f);
  CHECK(weightedPercentile(values, weights, 1.0f) == 3.0f);
  // Several fractions from one sort, each as on its own (running weight 0.5, 1.5, 3.5, 4.5).
  CHECK(weightedPercentiles(values, weights, {0.5, 0.0, 1.0, 0.1, 0.12, 0.33, 0.34}) ==
        std::vector<double>{0.5, -8.0, 3.0, -8.0, -1.0, -1.0, 0.5});
  CHECK(weightedPercentiles({}, {}, {0.5, 0.9}) == std::vector<double>{0.0, 0.0});
}

TEST_CASE("automatic colour range: a tight corner on a few percent of the area does not set the range") {
  // 94% of the area curved like a cap (K in 0.5..1), 6% at a valence-3 corner (K = 100).
  std::vector<double> values, weights;
  for (int i = 0; i < 94; ++i) {
    values.push_back(0.5f + 0.5f * float(i) / 93.0f);
    weights.push_back(1.0f);
  }
  for (int i = 0; i < 6; ++i) {
    values.push_back(100.0f);
    weights.push_back(1.0f);
  }
  CHECK(weightedSymmetricRange(values, weights, 0.90f) <= 1.0f);
  CHECK(weightedSymmetricRange(values, weights, 0.95f) == 100.0f);
  // All zero (a plane) or no weight: 1, never 0.
  CHECK(weightedSymmetricRange({0.0, 0.0}, {1.0, 2.0}, 0.9f) == 1.0);
  CHECK(weightedSymmetricRange({}, {}, 0.9f) == 1.0f);
}

TEST_CASE("curvature samples for the range come from every patch except the end caps at extraordinary vertices") {
  Model model = makeModel(std::make_shared<const PolyMesh>(shapes::mushroom(12)), "mushroom", 1);
  for (SchemeChoice scheme : {SchemeChoice::C2PS, SchemeChoice::CatmullClark}) {
    for (int level = 1; level <= 3; ++level) {
      auto surface = buildSurface(model, SurfaceKey{1, scheme, level}, kDefaultFaceBudget);
      const int endCaps = surface->patchesPerKind[size_t(PatchKind::EndCap)];
      const size_t counted = surface->patches.size() - size_t(endCaps);
      CAPTURE(level);
      REQUIRE(endCaps > 0);
      REQUIRE(counted > 0);
      const size_t samples = surface->samples->gaussian.size();
      CHECK(samples % counted == 0);
      const size_t perPatch = samples / counted;
      const size_t side = size_t(std::lround(std::sqrt(double(perPatch))));
      CHECK(side * side == perPatch);
      CHECK(surface->samples->areas.size() == samples);
    }
  }
}

TEST_CASE("viewer surface: an edit drops the levels made ahead, then refreshes the shown one as a fresh build") {
  Model model = defaultModel();
  const SurfaceKey key{model.generation, SchemeChoice::C2PS, 2, model.points};
  const auto surface = buildSurface(model, key, kDefaultFaceBudget);
  prepareLevel(*surface->hierarchy, model, SurfaceKey{model.generation, SchemeChoice::C2PS, 4, model.points}, kDefaultFaceBudget);
  CHECK(surface->hierarchy->deepestMade.load() == 4);
  CHECK(surface->hierarchy->aheadLevel.load() == 4);
  Model otherPoints = model;
  ++otherPoints.points;  // other points: nothing made
  prepareLevel(*surface->hierarchy, otherPoints, SurfaceKey{model.generation, SchemeChoice::C2PS, 5, otherPoints.points}, kDefaultFaceBudget);
  CHECK(surface->hierarchy->deepestMade.load() == 4);
  auto moved = std::make_shared<PolyMesh>(*model.mesh);
  moved->points[3] += Point(0.02, -0.01, 0.03);
  model.mesh = moved;
  ++model.points;
  const auto refreshed = refreshSurface(*surface, model, false);
  CHECK(surface->hierarchy->deepestMade.load() == 2);
  CHECK(surface->hierarchy->aheadLevel.load() == -1);  // the surface made ahead was of the old points
  CHECK(surface->hierarchy->refinement->levelCount() == 3);
  const PatchSet fresh = extractPatches(AdaptiveRefinement(*moved, refineOptionsFor(SchemeChoice::C2PS, 2)));
  REQUIRE(fresh.patches.size() == refreshed->patches.size());
  double worst = 0.0;
  for (size_t k = 0; k < fresh.patches.size(); ++k)
    for (int i = 0; i < 16; ++i)
      worst = std::max(worst, glm::length(withAbsolutePositions(fresh.patches[k]).cp[i] -
                                          withAbsolutePositions(refreshed->patches[k]).cp[i]));
  CHECK(worst < 1e-12);
  CHECK(refreshed->stamp != surface->stamp);  // new points: nothing on the GPU is theirs
}

TEST_CASE("viewer surface: RTS and BPS close their poles below a pixel at any level, C2PS at the level asked") {
  const Model model = defaultModel();
  double size = 0.0;
  for (const Point& p : model.mesh->points) size = std::max(size, glm::length(p - model.mesh->points[0]));
  for (SchemeChoice scheme : {SchemeChoice::RTS, SchemeChoice::BPS, SchemeChoice::C2PS})
    for (int level : {0, 2, 4}) {
      CAPTURE(int(scheme));
      CAPTURE(level);
      const auto surface = buildSurface(model, SurfaceKey{model.generation, scheme, level, model.points}, kDefaultFaceBudget);
      const bool c2 = scheme == SchemeChoice::C2PS;
      CHECK(surface->patchLevel == (c2 ? level : kNonC2CapLevel));
      // The caps' extent: the seam where a cap not C2 with its ring meets it (the dark ring of
      // curvature maps) is then ~1e-5 of the model, under a pixel of any window.
      double capExtent = 0.0;
      int caps = 0;
      for (const Patch& patch : surface->patches)
        if (patch.kind == PatchKind::PoleCap) {
          ++caps;
          for (int k = 6; k < 10; ++k) capExtent = std::max(capExtent, glm::length(patch.cp[k] - patch.cp[0]));
        }
      REQUIRE(caps > 0);
      if (!c2) CHECK(capExtent < 1e-4 * size);
      else CHECK(capExtent > 1e-3 * size);
    }
}

}  // namespace polarview

namespace polarview {

TEST_CASE("viewer surface: a pole touched by a crease or corner tag is left to Catmull-Clark, and the view says so") {
  PolyMesh cap = shapes::polarCap(8, 3);
  // A crease on the 1-link (vertices 1 and 2: the cap's first ring) and, apart, the same cap untagged.
  cap.tags.creases.push_back(CreaseEdge{1, 2, 1.0});
  const MeshTopology topo = buildTopology(cap);
  const std::vector<PolarConfig> configs = findPolarConfigs(cap, topo);
  REQUIRE(configs.size() == 1);
  CHECK_FALSE(configs[0].refinable);
  CHECK(configs[0].rejection == PolarRejection::SharpFeature);
  CHECK(configs[0].reason.find("at vertex 1") != std::string::npos);
  const Model model = makeModel(std::make_shared<const PolyMesh>(cap), "creased cap", 1);
  const auto surface = buildSurface(model, SurfaceKey{1, SchemeChoice::C2PS, 2}, kDefaultFaceBudget);
  CHECK(surface->polesByScheme == 0);
  CHECK(surface->polesByCatmullClark == 1);
  CHECK(surface->fallbackReason.find("crease or corner tag") != std::string::npos);
  CHECK(surface->patchesPerKind[size_t(PatchKind::PoleCap)] == 0);  // no C2PS cap: Catmull-Clark closed it
  // Untagged, C2PS refines it.
  PolyMesh plain = cap;
  plain.tags = SubdivTags{};
  const Model plainModel = makeModel(std::make_shared<const PolyMesh>(plain), "cap", 2);
  CHECK(buildSurface(plainModel, SurfaceKey{2, SchemeChoice::C2PS, 2}, kDefaultFaceBudget)->polesByScheme == 1);
}

}  // namespace polarview

namespace polarview {

TEST_CASE("viewer surface: the next level made ahead while idle is handed out as the step's surface, equal to a fresh build") {
  const Model model = defaultModel();
  const SurfaceKey shown{model.generation, SchemeChoice::C2PS, 3, model.points};
  const auto surface = buildSurface(model, shown, kDefaultFaceBudget);
  SurfaceKey next = shown;
  next.level = 4;
  prepareLevel(*surface->hierarchy, model, next, kDefaultFaceBudget);
  REQUIRE(surface->hierarchy->aheadLevel.load() == 4);
  const auto stepped = buildSurface(model, next, kDefaultFaceBudget, surface->hierarchy);
  CHECK(surface->hierarchy->aheadLevel.load() == -1);  // handed out
  CHECK(stepped->patchesMs == 0.0);                    // nothing assembled during the step
  CHECK(stepped->key == next);
  CHECK(stepped->hierarchy.get() == surface->hierarchy.get());
  REQUIRE(bool(stepped->samples));
  const auto fresh = buildSurface(model, next, kDefaultFaceBudget);
  REQUIRE(fresh->patches.size() == stepped->patches.size());
  size_t differ = 0;
  for (size_t k = 0; k < fresh->patches.size(); ++k)
    differ += fresh->patches[k].cp != stepped->patches[k].cp || fresh->patches[k].origin != stepped->patches[k].origin;
  CHECK(differ == 0);
  CHECK(stepped->samples->gaussian == fresh->samples->gaussian);
  // A stale one (other level asked for) is not handed out.
  prepareLevel(*surface->hierarchy, model, next, kDefaultFaceBudget);
  SurfaceKey other = shown;
  other.level = 2;
  const auto back = buildSurface(model, other, kDefaultFaceBudget, surface->hierarchy);
  CHECK(back->key == other);
  CHECK(back->patchLevel == 2);
}

}  // namespace polarview

namespace polarview {

TEST_CASE("colour range one-sided: values of one sign span the bar; zero stays the middle when it is inside") {
  // All positive, [0.8, 1.2]: linear over the bar, the histogram spreads over its bins.
  const ColourInterval positive{0.8, 1.2};
  CHECK(positive.oneSided());
  CHECK(colourBarPosition(0.8, positive) == 0.0);
  CHECK(colourBarPosition(1.0, positive) == doctest::Approx(0.5));
  CHECK(colourBarPosition(5.0, positive) == 1.0);
  CHECK(colourBarValue(0.25, positive) == doctest::Approx(0.9));
  const std::vector<double> values{0.85, 0.95, 1.05, 1.15}, weights{1.0, 1.0, 1.0, 1.0};
  const std::vector<float> bins = weightedHistogram(values, weights, positive, 4);
  CHECK(bins == std::vector<float>{1.0f, 1.0f, 1.0f, 1.0f});
  // The positive half of the map: green (zero's colour) to red, never blue; the negative half mirrors.
  using Map = ShadingParams::ColorMap;
  CHECK(colorMapCpu(Map::Paper, 0.8, positive) == colorMapCpu(Map::Paper, 0.0, 1.0));
  CHECK(colorMapCpu(Map::Paper, 1.2, positive) == colorMapCpu(Map::Paper, 1.0, 1.0));
  CHECK(colorMapCpu(Map::Paper, -1.2, ColourInterval{-1.2, -0.8}) == colorMapCpu(Map::Paper, -1.0, 1.0));
  // Mixed: two slopes with zero at the middle (the paper's Fig. 13), as before.
  const ColourInterval mixed{-2.0, 1.0};
  CHECK_FALSE(mixed.oneSided());
  CHECK(colourBarPosition(0.0, mixed) == 0.5);
  CHECK(colourBarPosition(-1.0, mixed) == 0.25);
  CHECK(colourBarValue(0.75, mixed) == 0.5);
  CHECK(colorMapCpu(Map::Paper, 0.0, mixed) == colorMapCpu(Map::Paper, 0.0, 1.0));
}

}  // namespace polarview
