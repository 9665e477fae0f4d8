// The surface cache's policy without a display: what a view shows, what it keeps (parked, previous
// level, twins), what it drops for the face budget, refusals, and positions-only updates.
#include <doctest/doctest.h>

#include <chrono>
#include <memory>
#include <thread>

#include "core/mesh/shapes.h"
#include "session/surface_cache.h"

using namespace polarview;

namespace {

Model testModel(uint64_t generation = 1) {
  return makeModel(std::make_shared<const PolyMesh>(shapes::mushroom(6)), "mushroom", generation);
}

// Frames until every visible view shows what its settings ask for (or failed).
void settle(SurfaceCache& cache, ViewerState& state, const Model& model) {
  cache.update(state, model, false);
  while (cache.busy(state, model, false)) {
    cache.pause();
    cache.update(state, model, false);
  }
}

ViewerState oneView(SchemeChoice scheme, int level) {
  ViewerState state;
  state.views[0].scheme = scheme;
  state.views[0].level = level;
  return state;
}

}  // namespace

TEST_CASE("surface cache: a view shows the surface its settings ask for, and reports it") {
  const Model model = testModel();
  SurfaceCache cache(kDefaultFaceBudget, false);
  ViewerState state = oneView(SchemeChoice::C2PS, 2);
  settle(cache, state, model);
  REQUIRE(cache.shown(0).get() != nullptr);
  CHECK(cache.shown(0)->key == wantedKey(state, model, 0));
  CHECK(state.views[0].status.hasSurface);
  CHECK(state.views[0].status.shownLevel == 2);
  CHECK(state.views[0].status.patchCount == int(cache.shown(0)->patches.size()));
  CHECK(cache.shown(1).get() == nullptr);  // invisible views build nothing
}

TEST_CASE("surface cache: a scheme toggle back is a swap, a level step back shows the kept level") {
  const Model model = testModel();
  SurfaceCache cache(kDefaultFaceBudget, false);
  ViewerState state = oneView(SchemeChoice::C2PS, 2);
  settle(cache, state, model);
  const BuiltSurface* c2ps = cache.shown(0).get();

  state.views[0].scheme = SchemeChoice::CatmullClark;
  settle(cache, state, model);
  CHECK(cache.shown(0)->key.scheme == SchemeChoice::CatmullClark);
  CHECK(cache.parked(0).get() == c2ps);
  CHECK_FALSE(cache.unparked(0));
  state.views[0].scheme = SchemeChoice::C2PS;
  settle(cache, state, model);
  CHECK(cache.shown(0).get() == c2ps);  // not rebuilt
  CHECK(cache.unparked(0));
  CHECK(state.views[0].status.unparked);
  CHECK(cache.parked(0)->key.scheme == SchemeChoice::CatmullClark);

  state.views[0].level = 3;
  settle(cache, state, model);
  CHECK(cache.shown(0)->key.level == 3);
  CHECK(cache.previousLevel(0).get() == c2ps);
  CHECK(cache.parked(0)->key.scheme == SchemeChoice::CatmullClark);  // kept: the step reused C2PS's hierarchy
  state.views[0].level = 2;
  settle(cache, state, model);
  CHECK(cache.shown(0).get() == c2ps);
  CHECK(cache.reshown(0));
  CHECK(cache.previousLevel(0)->key.level == 3);
}

TEST_CASE("surface cache: two views asking for the same key share one surface") {
  const Model model = testModel();
  SurfaceCache cache(kDefaultFaceBudget, false);
  ViewerState state = oneView(SchemeChoice::RTS, 2);
  settle(cache, state, model);
  REQUIRE(cache.shown(0).get() != nullptr);
  state.viewCount = 2;  // a second view on the same scheme and level
  state.views[1] = state.views[0];
  cache.update(state, model, false);
  CHECK_FALSE(cache.busy(state, model, false));  // nothing to build
  CHECK(cache.shown(1).get() == cache.shown(0).get());
}

TEST_CASE("surface cache: what is kept stays within the face budget") {
  const Model model = testModel();
  // Room for the level shown and little else: nothing is parked or kept beside it.
  const size_t level3 = estimatedLevelFaces(model, SchemeChoice::C2PS, 3, kDefaultFaceBudget);
  const size_t budget = level3 + level3 / 4;
  SurfaceCache cache(budget, false);
  ViewerState state = oneView(SchemeChoice::C2PS, 3);
  settle(cache, state, model);
  REQUIRE(cache.shown(0).get() != nullptr);
  state.views[0].scheme = SchemeChoice::C2PSUniformFirstStep;
  settle(cache, state, model);
  CHECK(cache.parked(0).get() == nullptr);
  CHECK(cache.facesHeld(state, model) <= budget);
  state.views[0].level = 2;
  settle(cache, state, model);
  CHECK(cache.facesHeld(state, model) <= budget);
  // The same steps under the default budget keep both.
  SurfaceCache roomy(kDefaultFaceBudget, false);
  ViewerState other = oneView(SchemeChoice::C2PS, 3);
  settle(roomy, other, model);
  other.views[0].scheme = SchemeChoice::C2PSUniformFirstStep;
  settle(roomy, other, model);
  CHECK(roomy.parked(0).get() != nullptr);
}

TEST_CASE("surface cache: a level over the budget is refused with a message and the view keeps its level") {
  const Model model = testModel();
  const size_t budget = estimatedLevelFaces(model, SchemeChoice::C2PS, 3, kDefaultFaceBudget);
  SurfaceCache cache(budget, false);
  ViewerState state = oneView(SchemeChoice::C2PS, 2);
  settle(cache, state, model);
  const int deepest = state.views[0].status.deepestLevel;
  REQUIRE(deepest < 6);
  state.views[0].level = 6;  // as a scripted setting would (the keys refuse it before)
  settle(cache, state, model);
  CHECK(state.views[0].status.message == levelRefusal(model, SchemeChoice::C2PS, 6, budget));
  cache.update(state, model, false);  // the next frame
  CHECK(state.views[0].level == 2);  // reverted to what it shows, so the controls tell the truth
  CHECK(cache.shown(0)->key.level == 2);
}

TEST_CASE("surface cache: moved points are a positions-only update with its cost") {
  Model model = testModel();
  SurfaceCache cache(kDefaultFaceBudget, false);
  ViewerState state = oneView(SchemeChoice::C2PS, 3);
  settle(cache, state, model);
  const std::shared_ptr<const BuiltSurface> before = cache.shown(0);
  auto moved = std::make_shared<PolyMesh>(*model.mesh);
  moved->points[0] += Point(0.0, 0.0, 0.1);
  model.mesh = moved;
  ++model.points;
  const std::optional<EditCost> cost = cache.update(state, model, true);  // while dragging
  REQUIRE(cost.has_value());
  CHECK(cost->views == 1);
  CHECK(cache.refreshed(0));
  CHECK(cache.shown(0)->key.points == model.points);
  CHECK(cache.shown(0)->refinement.get() == before->refinement.get());  // the same topology, new points
  CHECK(cache.shown(0)->patches.size() == before->patches.size());
  CHECK(cache.busy(state, model, false));  // the samples are retaken once the drag is over
  settle(cache, state, model);
  CHECK(cache.shown(0)->samples->points == model.points);
}

TEST_CASE("surface cache: a new model drops what was kept of the old one") {
  const Model first = testModel(1);
  SurfaceCache cache(kDefaultFaceBudget, false);
  ViewerState state = oneView(SchemeChoice::C2PS, 2);
  settle(cache, state, first);
  state.views[0].scheme = SchemeChoice::RTS;
  settle(cache, state, first);
  REQUIRE(cache.parked(0).get() != nullptr);
  const Model second = makeModel(std::make_shared<const PolyMesh>(shapes::mushroom(8)), "mushroom 8", 2);
  cache.modelChanged(state);
  settle(cache, state, second);
  CHECK(cache.parked(0).get() == nullptr);
  CHECK(cache.shown(0)->key.model == 2);
}

TEST_CASE("surface cache: the refining time counts from the request, also while an older request's job runs first") {
  const Model model = testModel();
  SurfaceCache cache(kDefaultFaceBudget, false);
  ViewerState state = oneView(SchemeChoice::C2PS, 2);
  settle(cache, state, model);
  // Level 7 starts building; level 8 is asked for while it runs and starts only when 7 is done.
  state.views[0].level = 7;
  cache.update(state, model, false);
  REQUIRE(state.views[0].status.refining);
  state.views[0].level = 8;
  const auto asked = std::chrono::steady_clock::now();
  cache.update(state, model, false);
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  cache.update(state, model, false);
  CHECK(state.views[0].status.refiningSeconds >= 0.03);
  // Level 7's job ends (its surface is dropped: 8 is wanted) and level 8's job begins.
  while (!cache.refiningKey(0) || cache.refiningKey(0)->level != 8) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    cache.update(state, model, false);
  }
  // Level 8's job has just begun: the wait for it began when it was asked for.
  INFO(state.views[0].status.message);
  REQUIRE(state.views[0].status.refining);
  const double sinceAsked = std::chrono::duration<double>(std::chrono::steady_clock::now() - asked).count();
  CHECK(state.views[0].status.refiningSeconds >= 0.9 * sinceAsked - 0.002);
  CHECK(state.views[0].status.refiningSeconds > 0.03);
  settle(cache, state, model);
  CHECK(state.views[0].status.refiningSeconds == 0.0);
  CHECK(cache.shown(0)->key.level == 8);
}
