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

// What the session keeps for the cache: the views' settings and the status the cache reports.
struct Views {
  ViewerSettings settings;
  ViewerStatus status;
  SurfaceRequest request(const Model& model) const { return surfaceRequest(settings, model); }
};

// One frame of the cache as the session runs it: reverts applied to the settings, status reported.
std::optional<EditCost> update(SurfaceCache& cache, Views& views, const Model& model, bool dragging) {
  const SurfaceUpdate update = cache.update(views.request(model), model, dragging);
  for (int v = 0; v < kMaxViews; ++v) {
    if (const std::optional<SurfaceKey>& shown = update.reverted[size_t(v)]) {
      views.settings.views[size_t(v)].scheme = shown->scheme;
      views.settings.views[size_t(v)].level = shown->level;
    }
    cache.report(v, model, views.status.views[size_t(v)]);
  }
  return update.editCost;
}

// Frames until every visible view shows what its settings ask for (or failed).
void settle(SurfaceCache& cache, Views& views, const Model& model) {
  update(cache, views, model, false);
  while (cache.busy(views.request(model), model, false)) {
    cache.pause();
    update(cache, views, model, false);
  }
}

Views oneView(SchemeChoice scheme, int level) {
  Views views;
  views.settings.views[0].scheme = scheme;
  views.settings.views[0].level = level;
  return views;
}

}  // namespace

TEST_CASE("surface cache: a view shows the surface its settings ask for, and reports it") {
  const Model model = testModel();
  SurfaceCache cache(kDefaultFaceBudget, false);
  Views state = oneView(SchemeChoice::C2PS, 2);
  settle(cache, state, model);
  REQUIRE(cache.shown(0).get() != nullptr);
  CHECK(cache.shown(0)->key == state.request(model).wanted[0]);
  CHECK(state.status.views[0].hasSurface);
  CHECK(state.status.views[0].shownLevel == 2);
  CHECK(state.status.views[0].patchCount == int(cache.shown(0)->patches.size()));
  CHECK(cache.shown(1).get() == nullptr);  // invisible views build nothing
}

TEST_CASE("surface cache: a scheme toggle back is a swap, a level step back shows the kept level") {
  const Model model = testModel();
  SurfaceCache cache(kDefaultFaceBudget, false);
  Views state = oneView(SchemeChoice::C2PS, 2);
  settle(cache, state, model);
  const BuiltSurface* c2ps = cache.shown(0).get();

  state.settings.views[0].scheme = SchemeChoice::CatmullClark;
  settle(cache, state, model);
  CHECK(cache.shown(0)->key.scheme == SchemeChoice::CatmullClark);
  CHECK(cache.parked(0).get() == c2ps);
  CHECK_FALSE(cache.unparked(0));
  state.settings.views[0].scheme = SchemeChoice::C2PS;
  settle(cache, state, model);
  CHECK(cache.shown(0).get() == c2ps);  // not rebuilt
  CHECK(cache.unparked(0));
  CHECK(state.status.views[0].unparked);
  CHECK(cache.parked(0)->key.scheme == SchemeChoice::CatmullClark);

  state.settings.views[0].level = 3;
  settle(cache, state, model);
  CHECK(cache.shown(0)->key.level == 3);
  CHECK(cache.previousLevel(0).get() == c2ps);
  CHECK(cache.parked(0)->key.scheme == SchemeChoice::CatmullClark);  // kept: the step reused C2PS's hierarchy
  state.settings.views[0].level = 2;
  settle(cache, state, model);
  CHECK(cache.shown(0).get() == c2ps);
  CHECK(cache.reshown(0));
  CHECK(cache.previousLevel(0)->key.level == 3);
}

TEST_CASE("surface cache: two views asking for the same key share one surface") {
  const Model model = testModel();
  SurfaceCache cache(kDefaultFaceBudget, false);
  Views state = oneView(SchemeChoice::RTS, 2);
  settle(cache, state, model);
  REQUIRE(cache.shown(0).get() != nullptr);
  state.settings.viewCount = 2;  // a second view on the same scheme and level
  state.settings.views[1] = state.settings.views[0];
  update(cache, state, model, false);
  CHECK_FALSE(cache.busy(state.request(model), model, false));  // nothing to build
  CHECK(cache.shown(1).get() == cache.shown(0).get());
}

TEST_CASE("surface cache: what is kept stays within the face budget") {
  const Model model = testModel();
  // Room for the level shown and little else: nothing is parked or kept beside it.
  const size_t level3 = estimatedLevelFaces(model, SchemeChoice::C2PS, 3, kDefaultFaceBudget);
  const size_t budget = level3 + level3 / 4;
  SurfaceCache cache(budget, false);
  Views state = oneView(SchemeChoice::C2PS, 3);
  settle(cache, state, model);
  REQUIRE(cache.shown(0).get() != nullptr);
  state.settings.views[0].scheme = SchemeChoice::C2PSUniformFirstStep;
  settle(cache, state, model);
  CHECK(cache.parked(0).get() == nullptr);
  CHECK(cache.facesHeld(state.request(model), model) <= budget);
  state.settings.views[0].level = 2;
  settle(cache, state, model);
  CHECK(cache.facesHeld(state.request(model), model) <= budget);
  // The same steps under the default budget keep both.
  SurfaceCache roomy(kDefaultFaceBudget, false);
  Views other = oneView(SchemeChoice::C2PS, 3);
  settle(roomy, other, model);
  other.settings.views[0].scheme = SchemeChoice::C2PSUniformFirstStep;
  settle(roomy, other, model);
  CHECK(roomy.parked(0).get() != nullptr);
}

TEST_CASE("surface cache: a level over the budget is refused with a message and the view keeps its level") {
  const Model model = testModel();
  const size_t budget = estimatedLevelFaces(model, SchemeChoice::C2PS, 3, kDefaultFaceBudget);
  SurfaceCache cache(budget, false);
  Views state = oneView(SchemeChoice::C2PS, 2);
  settle(cache, state, model);
  const int deepest = state.status.views[0].deepestLevel;
  REQUIRE(deepest < 6);
  state.settings.views[0].level = 6;  // as a scripted setting would (the keys refuse it before)
  settle(cache, state, model);
  CHECK(state.status.views[0].message == levelRefusal(model, SchemeChoice::C2PS, 6, budget));
  update(cache, state, model, false);  // the next frame
  CHECK(state.settings.views[0].level == 2);  // reverted to what it shows, so the controls tell the truth
  CHECK(cache.shown(0)->key.level == 2);
}

TEST_CASE("surface cache: moved points are a positions-only update with its cost") {
  Model model = testModel();
  SurfaceCache cache(kDefaultFaceBudget, false);
  Views state = oneView(SchemeChoice::C2PS, 3);
  settle(cache, state, model);
  const std::shared_ptr<const BuiltSurface> before = cache.shown(0);
  auto moved = std::make_shared<PolyMesh>(*model.mesh);
  moved->points[0] += Point(0.0, 0.0, 0.1);
  model.mesh = moved;
  ++model.points;
  const std::optional<EditCost> cost = update(cache, state, model, true);  // while dragging
  REQUIRE(cost.has_value());
  CHECK(cost->views == 1);
  CHECK(cache.refreshed(0));
  CHECK(cache.shown(0)->key.points == model.points);
  CHECK(cache.shown(0)->refinement.get() == before->refinement.get());  // the same topology, new points
  CHECK(cache.shown(0)->patches.size() == before->patches.size());
  CHECK(cache.busy(state.request(model), model, false));  // the samples are retaken once the drag is over
  settle(cache, state, model);
  CHECK(cache.shown(0)->samples->points == model.points);
}

TEST_CASE("surface cache: a new model drops what was kept of the old one") {
  const Model first = testModel(1);
  SurfaceCache cache(kDefaultFaceBudget, false);
  Views state = oneView(SchemeChoice::C2PS, 2);
  settle(cache, state, first);
  state.settings.views[0].scheme = SchemeChoice::RTS;
  settle(cache, state, first);
  REQUIRE(cache.parked(0).get() != nullptr);
  const Model second = makeModel(std::make_shared<const PolyMesh>(shapes::mushroom(8)), "mushroom 8", 2);
  cache.modelChanged();
  settle(cache, state, second);
  CHECK(cache.parked(0).get() == nullptr);
  CHECK(cache.shown(0)->key.model == 2);
}

TEST_CASE("surface cache: the refining time counts from the request, also while an older request's job runs first") {
  const Model model = testModel();
  SurfaceCache cache(kDefaultFaceBudget, false);
  Views state = oneView(SchemeChoice::C2PS, 2);
  settle(cache, state, model);
  // Level 7 starts building; level 8 is asked for while it runs and starts only when 7 is done.
  state.settings.views[0].level = 7;
  update(cache, state, model, false);
  REQUIRE(state.status.views[0].refining);
  state.settings.views[0].level = 8;
  const auto asked = std::chrono::steady_clock::now();
  update(cache, state, model, false);
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  update(cache, state, model, false);
  CHECK(state.status.views[0].refiningSeconds >= 0.03);
  // Level 7's job ends (its surface is dropped: 8 is wanted) and level 8's job begins.
  while (!cache.refiningKey(0) || cache.refiningKey(0)->level != 8) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    update(cache, state, model, false);
  }
  // Level 8's job has just begun: the wait for it began when it was asked for.
  INFO(state.status.views[0].message);
  REQUIRE(state.status.views[0].refining);
  const double sinceAsked = std::chrono::duration<double>(std::chrono::steady_clock::now() - asked).count();
  CHECK(state.status.views[0].refiningSeconds >= 0.9 * sinceAsked - 0.002);
  CHECK(state.status.views[0].refiningSeconds > 0.03);
  settle(cache, state, model);
  CHECK(state.status.views[0].refiningSeconds == 0.0);
  CHECK(cache.shown(0)->key.level == 8);
}
