// The viewer's surface cache (surface_cache.h).
#include "session/surface_cache.h"

#include "pipeline/stopwatch.h"
#include "pipeline/model.h"
#include "pipeline/surface_key.h"
#include "pipeline/level_limits.h"
#include "pipeline/surface_build.h"
#include "pipeline/surface_job.h"

#include <algorithm>
#include <chrono>
#include <thread>
#include <utility>

namespace polarview {
namespace {

bool sameModelAndPoints(const SurfaceKey& a, const SurfaceKey& b) { return a.model == b.model && a.points == b.points; }

}  // namespace

SurfaceRequest surfaceRequest(const ViewerSettings& settings, const Model& model) {
  SurfaceRequest request;
  for (int v = 0; v < kMaxViews; ++v) {
    const View& view = settings.views[size_t(v)];
    request.wanted[size_t(v)] = SurfaceKey{model.generation, view.scheme, view.level, model.points};
  }
  request.viewCount = settings.viewCount;
  request.activeView = settings.clampedActiveView();
  request.zoomed = settings.poleInspector.zoomRing >= 0;
  return request;
}

SurfaceCache::~SurfaceCache() {
  for (ViewSurfaces& view : views_) {
    view.job.wait();
    view.prepare.join();
  }
}

size_t SurfaceCache::levelFaces(const Model& model, SchemeChoice scheme, int level) const {
  return estimatedLevelFaces(model, scheme, level, faceBudget_);
}

size_t SurfaceCache::facesHeld(const SurfaceRequest& request, const Model& model, bool wantedLevels) const {
  size_t faces = 0;
  for (const ViewSurfaces& view : views_) {
    // A parked surface keeps its whole hierarchy: every level made, ahead ones too.
    if (const BuiltSurface* parked = view.parked.get())
      faces += levelFaces(model, parked->key.scheme,
                          std::max(parked->patchLevel, parked->hierarchy ? parked->hierarchy->deepestMade.load() : 0));
    // The previous level shares the shown surface's hierarchy: its own patches (at most a level's).
    if (const BuiltSurface* previous = view.previousLevel.get())
      faces += levelFaces(model, previous->key.scheme, previous->patchLevel);
  }
  for (int v = 0; v < request.viewCount; ++v) {
    if (wantedLevels) {
      const SurfaceKey& wanted = request.wanted[size_t(v)];
      faces += levelFaces(model, wanted.scheme, patchLevelFor(model, wanted.scheme, wanted.level, faceBudget_));
    } else if (const BuiltSurface* shown = views_[size_t(v)].shown.get()) {
      faces += levelFaces(model, shown->key.scheme, shown->patchLevel);
    }
  }
  return faces;
}

void SurfaceCache::show(int v, std::shared_ptr<const BuiltSurface> surface) {
  ViewSurfaces& view = views_[size_t(v)];
  view.shown = std::move(surface);
  view.unparked = view.reshown = view.refreshed = false;
}

void SurfaceCache::modelChanged() {
  for (ViewSurfaces& view : views_) {
    view.failed.reset();
    view.message.clear();
  }
}

SurfaceUpdate SurfaceCache::update(SurfaceRequest request, const Model& model, bool dragging) {
  SurfaceUpdate result;
  if (!model.mesh) return result;
  result.editCost = refreshEditedViews(request, model, dragging);
  for (int v = 0; v < kMaxViews; ++v) {
    takeFinishedJob(v, request, model);
    // A refused or failed key reverts the view to what it shows, so the controls tell the truth.
    ViewSurfaces& view = views_[size_t(v)];
    SurfaceKey& wanted = request.wanted[size_t(v)];
    if (view.failed && *view.failed == wanted && view.shown && view.shown->key.model == wanted.model) {
      wanted.scheme = view.shown->key.scheme;
      wanted.level = view.shown->key.level;
      result.reverted[size_t(v)] = wanted;
    }
    dropStale(v, request, model);
    // A surface of this topology at older points waits for its positions-only update instead.
    const bool refreshable = view.shown && view.shown->refinement && view.shown->key.sameTopology(wanted) &&
                             !(view.refreshFailed && *view.refreshFailed == wanted);
    const bool dirty = v < request.viewCount && (!view.shown || view.shown->key != wanted) && !refreshable &&
                       !(view.failed && *view.failed == wanted);
    if (dirty && !view.job.running()) satisfy(v, request, model, wanted);
    const bool waiting = view.job.running() && (!view.shown || view.shown->key != wanted);
    if (!waiting) {
      view.waitingFor.reset();
    } else if (view.waitingFor != wanted) {
      view.waitingFor = wanted;
      view.waitingSince = std::chrono::steady_clock::now();
    }
    view.scheme = wanted.scheme;
    view.deepestLevel = deepestLevel(model, wanted.scheme, faceBudget_);
    prepareNextLevel(v, request, model, wanted, dragging);
  }
  return result;
}

std::optional<EditCost> SurfaceCache::refreshEditedViews(const SurfaceRequest& request, const Model& model, bool dragging) {
  EditCost cost;
  bool positionsMoved = false;
  // Each stale surface is refreshed once; views that shared it share the refreshed one.
  std::vector<std::pair<const BuiltSurface*, std::shared_ptr<const BuiltSurface>>> refreshed;
  for (int v = 0; v < request.viewCount; ++v) {
    ViewSurfaces& view = views_[size_t(v)];
    const SurfaceKey& wanted = request.wanted[size_t(v)];
    if (!view.shown || !view.shown->refinement || !view.shown->key.sameTopology(wanted)) continue;
    if (view.refreshFailed && *view.refreshFailed == wanted) continue;
    const bool pointsStale = view.shown->key.points != wanted.points;
    const bool samplesStale = !dragging && view.shown->samples && view.shown->samples->points != wanted.points;
    if (!pointsStale && !samplesStale) continue;

    // Positions, patches and (once the drag is over) curvature samples on the kept hierarchy.
    const auto start = std::chrono::steady_clock::now();
    RefreshTiming timing;  // stays zero for a view sharing a surface refreshed for another
    std::shared_ptr<const BuiltSurface> surface;
    for (const auto& [old, fresh] : refreshed)
      if (old == view.shown.get()) surface = fresh;
    if (!surface) {
      try {
        surface = refreshSurface(*view.shown, model, !dragging, &timing);
      } catch (const std::exception& e) {
        // Not expected (the topology is the one it was built with); the view is rebuilt instead.
        view.refreshFailed = wanted;
        view.message = std::string("positions-only update failed (rebuilding): ") + e.what();
        continue;
      }
      refreshed.emplace_back(view.shown.get(), surface);
    }
    show(v, surface);
    view.refreshed = true;
    // The per-frame cost of moved points; retaking the curvature samples (once, at the end of a
    // drag, or with an undo) is not part of it.
    if (pointsStale) {
      positionsMoved = true;
      cost.positionsMs += timing.positionsMs;
      cost.patchesMs += timing.patchesMs;
      cost.totalMs += millisecondsSince(start) - timing.samplesMs;
      ++cost.views;
    }
  }
  if (!positionsMoved) return std::nullopt;
  return cost;
}

void SurfaceCache::takeFinishedJob(int v, const SurfaceRequest& request, const Model& model) {
  // A finished job: shown if it is still wanted, else dropped (a newer request follows). One built
  // from points edited since is shown too, then brought up to date by a positions-only update
  // (the next refreshEditedViews), so a long build is not thrown away by a drag.
  ViewSurfaces& view = views_[size_t(v)];
  std::optional<SurfaceJob::Outcome> outcome = view.job.poll();
  if (!outcome) return;
  if (!outcome->error.empty()) {
    view.failed = outcome->key;
    view.message = outcome->error;
  } else if (outcome->surface->key.sameTopology(request.wanted[size_t(v)])) {
    parkShown(v, request, model, *outcome->surface);
    keepPreviousLevel(v, request, model, *outcome->surface);
    show(v, outcome->surface);
    view.message.clear();
  }
}

void SurfaceCache::dropStale(int v, const SurfaceRequest& request, const Model& model) {
  // A parked surface of another model or older points, or of the scheme shown, is of no use; a
  // previous level likewise, or of another scheme than the one shown.
  ViewSurfaces& view = views_[size_t(v)];
  const bool visible = v < request.viewCount;
  const SurfaceKey current{model.generation, SchemeChoice::C2PS, 0, model.points};
  if (view.parked && (!visible || !sameModelAndPoints(view.parked->key, current) ||
                      (view.shown && view.shown->key.scheme == view.parked->key.scheme)))
    view.parked.reset();
  if (view.previousLevel && (!visible || !sameModelAndPoints(view.previousLevel->key, current) || !view.shown ||
                             view.shown->key.scheme != view.previousLevel->key.scheme))
    view.previousLevel.reset();
}

void SurfaceCache::satisfy(int v, const SurfaceRequest& request, const Model& model, const SurfaceKey& wanted) {
  ViewSurfaces& view = views_[size_t(v)];
  const bool zoomed = request.zoomed;
  std::shared_ptr<const BuiltSurface> twin;  // another view's surface of the same key
  for (const ViewSurfaces& other : views_)
    if (other.shown && other.shown->key == wanted) twin = other.shown;
  if (unpark(v, request, wanted)) {
    view.message.clear();
  } else if (view.previousLevel && view.previousLevel->key == wanted && !zoomed) {
    // A step back to the level shown before: its surface again (the GPU keeps the shared patches).
    std::shared_ptr<const BuiltSurface> previous = std::move(view.previousLevel);
    view.previousLevel = view.shown;
    show(v, std::move(previous));
    view.reshown = true;
    view.message.clear();
  } else if (twin) {
    parkShown(v, request, model, *twin);
    show(v, twin);
  } else if (std::string refusal = checkFaceBudget(model, wanted, faceBudget_); !refusal.empty()) {
    view.failed = wanted;
    view.message = refusal;
  } else {
    startBuild(v, request, model, wanted);
  }
}

void SurfaceCache::startBuild(int v, const SurfaceRequest& request, const Model& model, const SurfaceKey& wanted) {
  // The view's own hierarchy (same model and scheme) is stepped to the new level; so is its parked
  // one's (the parked surface goes: its hierarchy will be at another level).
  ViewSurfaces& view = views_[size_t(v)];
  auto reusableFrom = [&](const std::shared_ptr<const BuiltSurface>& surface) {
    return surface && surface->hierarchy && surface->key.model == wanted.model && surface->key.scheme == wanted.scheme;
  };
  std::shared_ptr<SurfaceHierarchy> reusable;
  if (reusableFrom(view.shown)) reusable = view.shown->hierarchy;
  else if (reusableFrom(view.parked)) reusable = view.parked->hierarchy;
  if (view.parked && view.parked->hierarchy == reusable) view.parked.reset();
  // Kept surfaces give their memory to a new refinement that would not fit beside them.
  const size_t adding = levelFaces(model, wanted.scheme, patchLevelFor(model, wanted.scheme, wanted.level, faceBudget_));
  if (facesHeld(request, model) + adding > faceBudget_)
    for (ViewSurfaces& other : views_) {
      other.parked.reset();
      other.previousLevel.reset();
    }
  view.job.start(model, wanted, faceBudget_, reusable);
}

void SurfaceCache::parkShown(int v, const SurfaceRequest& request, const Model& model, const BuiltSurface& next) {
  // Keeps the shown surface when `next` replaces it with another scheme's surface of the same model
  // and points, within the budget, so a toggle back is a swap.
  ViewSurfaces& view = views_[size_t(v)];
  if (!view.shown || !sameModelAndPoints(view.shown->key, next.key) || view.shown->key.scheme == next.key.scheme) return;
  view.parked.reset();  // the older parked surface goes first (also when this one cannot be parked)
  // A zoomed view holds other patches than the surface's on the GPU: nothing to swap back to.
  if (request.zoomed ||
      facesHeld(request, model) + levelFaces(model, next.key.scheme, next.patchLevel) > faceBudget_)
    return;
  view.parked = std::move(view.shown);
}

bool SurfaceCache::unpark(int v, const SurfaceRequest& request, const SurfaceKey& wanted) {
  ViewSurfaces& view = views_[size_t(v)];
  if (!view.parked || view.parked->key != wanted || request.zoomed) return false;
  std::swap(view.shown, view.parked);  // the one shown so far is parked in turn
  if (view.parked && !sameModelAndPoints(view.parked->key, wanted)) view.parked.reset();
  view.unparked = true;
  view.reshown = view.refreshed = false;
  view.previousLevel.reset();  // of the other scheme
  return true;
}

void SurfaceCache::keepPreviousLevel(int v, const SurfaceRequest& request, const Model& model, const BuiltSurface& next) {
  // Keeps the shown surface as the previous level when `next` is a level step of it (same model,
  // scheme and points), within the budget.
  ViewSurfaces& view = views_[size_t(v)];
  const BuiltSurface* shown = view.shown.get();
  const bool step = shown && sameModelAndPoints(shown->key, next.key) && shown->key.scheme == next.key.scheme &&
                    shown->key.level != next.key.level;
  if (!step) return;
  view.previousLevel.reset();  // the older one goes first
  if (facesHeld(request, model) + levelFaces(model, next.key.scheme, next.patchLevel) <= faceBudget_)
    view.previousLevel = view.shown;
}

void SurfaceCache::prepareNextLevel(int v, const SurfaceRequest& request, const Model& model, const SurfaceKey& wanted,
                                    bool dragging) {
  ViewSurfaces& view = views_[size_t(v)];
  if (view.prepare.running()) {
    std::optional<bool> made = view.prepare.poll();
    if (!made) return;
    if (!*made) view.prepareFailed = view.preparing;
    // Room on the GPU for the level made ahead, now while idle rather than during the step.
    if (view.shown && view.shown->hierarchy && view.shown->hierarchy->preparedLevel.load() > view.shown->patchLevel)
      view.reservation = GpuReservation{view.shown->hierarchy->preparedRegular.load(), view.shown->hierarchy->preparedCaps.load()};
  }
  // Only the active view (the one the level keys step) is made ahead: memory for one surface more.
  if (!prepareNextLevel_ || v >= request.viewCount || v != request.activeView ||
      view.job.running() || dragging || !view.shown || !view.shown->hierarchy || view.shown->key != wanted)
    return;
  if (wanted.level + 1 > view.deepestLevel) return;
  if (view.shown->hierarchy->aheadLevel.load() == wanted.level + 1) return;  // made already
  if (view.previousLevel && view.previousLevel->key.level == wanted.level + 1) return;  // kept from before
  // All views' levels and the one made ahead within one view's budget (memory stays bounded).
  const int next = patchLevelFor(model, wanted.scheme, wanted.level + 1, faceBudget_);
  if (levelFaces(model, wanted.scheme, next) + facesHeld(request, model, true) > faceBudget_) return;
  SurfaceKey key = wanted;
  key.level = wanted.level + 1;
  if (view.prepareFailed && *view.prepareFailed == key) return;
  // One view's surface ahead at a time: the other views' and the parked ones' go (the active view
  // follows the mouse).
  std::vector<std::shared_ptr<SurfaceHierarchy>> others;
  for (const ViewSurfaces& other : views_)
    for (const BuiltSurface* surface : {other.shown.get(), other.parked.get()})
      if (surface && surface->hierarchy && surface->hierarchy != view.shown->hierarchy &&
          surface->hierarchy->aheadLevel.load() >= 0)
        others.push_back(surface->hierarchy);
  view.preparing = key;
  view.prepare.start([hierarchy = view.shown->hierarchy, others = std::move(others), model, key, budget = faceBudget_] {
    for (const auto& other : others) dropAhead(*other);
    return prepareLevel(*hierarchy, model, key, budget);
  });
}

void SurfaceCache::report(int v, const Model& model, ViewStatus& status) const {
  const ViewSurfaces& view = views_[size_t(v)];
  status.message = view.message;
  status.deepestLevel = view.deepestLevel;
  status.levelLimit = model.mesh ? levelRefusal(model, view.scheme, view.deepestLevel + 1, faceBudget_) : std::string();
  status.refining = view.job.running();
  // Since the view asked for what it waits for (not since the running job, maybe an older one, began).
  status.refiningSeconds =
      !status.refining ? 0.0
      : view.waitingFor ? std::chrono::duration<double>(std::chrono::steady_clock::now() - view.waitingSince).count()
                        : view.job.runningSeconds();
  status.hasSurface = view.shown != nullptr;
  const BuiltSurface* shown = view.shown.get();
  if (!shown) return;
  status.shownScheme = shown->key.scheme;
  status.shownLevel = shown->key.level;
  status.patchCount = int(shown->patches.size());
  status.patchesPerKind = shown->patchesPerKind;
  status.controlFaces = shown->controlMesh.faceCount();
  // A surface shown again from the park or as the previous level cost nothing to build this time.
  status.unparked = view.unparked;
  status.reshown = view.reshown;
  const bool built = !view.unparked && !view.reshown;
  status.refineMs = built ? shown->refineMs : 0.0;
  status.refineOnlyMs = built ? shown->refineOnlyMs : 0.0;
  status.patchesMs = built ? shown->patchesMs : 0.0;
  status.samplesMs = built ? shown->samplesMs : 0.0;
  status.patchLevel = shown->patchLevel;
  status.polesByScheme = shown->polesByScheme;
  status.polesByCatmullClark = shown->polesByCatmullClark;
  status.fallbackReason = shown->fallbackReason;
}

std::optional<GpuReservation> SurfaceCache::takeReservation(int v) {
  std::optional<GpuReservation> reservation = views_[size_t(v)].reservation;
  views_[size_t(v)].reservation.reset();
  return reservation;
}

bool SurfaceCache::busy(const SurfaceRequest& request, const Model& model, bool dragging) const {
  for (int v = 0; v < request.viewCount; ++v) {
    const ViewSurfaces& view = views_[size_t(v)];
    if (view.job.running() || (view.prepare.running() && !view.prepare.finished())) return true;
    const SurfaceKey& wanted = request.wanted[size_t(v)];
    if (model.mesh && (!view.shown || view.shown->key != wanted) && !(view.failed && *view.failed == wanted)) return true;
    // Curvature samples still to be retaken after a drag.
    if (view.shown && view.shown->samples && view.shown->samples->points != model.points && !dragging &&
        !(view.refreshFailed && *view.refreshFailed == wanted))
      return true;
  }
  return false;
}

void SurfaceCache::pause() const {
  for (const ViewSurfaces& view : views_)
    if (view.job.running() || view.prepare.running()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      return;
    }
}

}  // namespace polarview
