// The viewer's surface cache: the one owner of every surface the views hold, and of the policy that
// decides what is built, kept and dropped, under one face budget (facesHeld). Per view:
//   shown          what the view shows;
//   parked         the surface it showed before its scheme changed: toggling back swaps the two
//                  (no refinement; the window keeps its GPU copy too);
//   previousLevel  the surface of the level shown before the last level step: a step back shows it
//                  again (nothing built);
//   made ahead     the next level of the active view, made while idle (SurfaceHierarchy::ahead).
// No GL: the window mirrors `shown` and `parked` on the GPU (ViewerApp's GPU mirror) after each
// update, so the whole policy is tested without a display (tests/session/surface_cache_test.cpp).
#pragma once

#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include "pipeline/model.h"
#include "pipeline/surface_key.h"
#include "pipeline/surface_build.h"
#include "pipeline/surface_job.h"
#include "pipeline/background_job.h"
#include "session/viewer_settings.h"
#include "session/viewer_status.h"

namespace polarview {

// What one positions-only update of the shown views cost after control points moved (ms): the
// refinements' positions, patch extraction (with pole markers) and the upload (the window adds
// it), every view together (a surface two views share is updated once, uploaded twice).
struct EditCost {
  double positionsMs = 0.0, patchesMs = 0.0, uploadMs = 0.0, totalMs = 0.0;
  int views = 0;
};

// GPU room to reserve for a level made ahead (PatchRenderer::reserveFor), so the step does not grow
// buffers.
struct GpuReservation {
  size_t regularPatches = 0, capPatches = 0;
};

// What the views ask the cache for this frame (from ViewerSettings): each view's surface, how many
// views are visible, the active one (its next level is made ahead), and whether a pole zoom is on
// (zoomed views hold other patches on the GPU: nothing is parked or reshown).
struct SurfaceRequest {
  std::array<SurfaceKey, kMaxViews> wanted{};
  int viewCount = 1;
  int activeView = 0;
  bool zoomed = false;
};
SurfaceRequest surfaceRequest(const ViewerSettings& settings, const Model& model);

// What one frame of the cache did for the session: the cost of positions-only updates when points
// moved, and the views whose refused or failed request reverts to what they show (so the controls
// tell the truth: the session writes these back into the settings).
struct SurfaceUpdate {
  std::optional<EditCost> editCost;
  std::array<std::optional<SurfaceKey>, kMaxViews> reverted{};
};

class SurfaceCache {
 public:
  SurfaceCache(size_t faceBudget, bool prepareNextLevel) : faceBudget_(faceBudget), prepareNextLevel_(prepareNextLevel) {}
  ~SurfaceCache();  // waits for running jobs
  SurfaceCache(const SurfaceCache&) = delete;
  SurfaceCache& operator=(const SurfaceCache&) = delete;

  // One frame: positions-only updates of edited views, finished jobs shown, wanted surfaces taken
  // from what is kept or started in the background, kept surfaces dropped when stale or over the
  // budget, the next level made ahead. [O(views) a frame; O(faces of all levels) per edited view]
  SurfaceUpdate update(SurfaceRequest request, const Model& model, bool dragging);
  // View v's part of its status (all but the GPU's fields), written into `status`.
  void report(int v, const Model& model, ViewStatus& status) const;
  // A new model: failures of the old one are forgotten (surfaces go as they become stale).
  void modelChanged();
  // True while a job runs or a visible view does not show what its settings ask for.
  bool busy(const SurfaceRequest& request, const Model& model, bool dragging) const;
  // Blocks briefly while jobs run (waitUntilIdle's loop).
  void pause() const;

  const std::shared_ptr<const BuiltSurface>& shown(int v) const { return views_[size_t(v)].shown; }
  const std::shared_ptr<const BuiltSurface>& parked(int v) const { return views_[size_t(v)].parked; }
  const std::shared_ptr<const BuiltSurface>& previousLevel(int v) const { return views_[size_t(v)].previousLevel; }
  // How view v's shown surface last changed: from its park, its previous level, or a positions-only
  // update (no patch stayed on the GPU: other points).
  bool unparked(int v) const { return views_[size_t(v)].unparked; }
  bool reshown(int v) const { return views_[size_t(v)].reshown; }
  // The key view v's running job builds (nullopt when none runs).
  std::optional<SurfaceKey> refiningKey(int v) const {
    return views_[size_t(v)].job.running() ? std::optional<SurfaceKey>(views_[size_t(v)].job.runningKey()) : std::nullopt;
  }
  bool refreshed(int v) const { return views_[size_t(v)].refreshed; }
  // GPU room for the level made ahead of view v, once, when its job has finished.
  std::optional<GpuReservation> takeReservation(int v);

  // The faces everything kept holds: each parked surface's hierarchy (every level it made), each
  // previous level, and each visible view's shown surface, or (`wantedLevels`) the level its
  // settings ask for; all against faceBudget(). The one sum the policy uses.
  size_t facesHeld(const SurfaceRequest& request, const Model& model, bool wantedLevels = false) const;
  size_t faceBudget() const { return faceBudget_; }

 private:
  struct ViewSurfaces {
    std::shared_ptr<const BuiltSurface> shown, parked, previousLevel;
    SurfaceJob job;
    std::optional<SurfaceKey> failed;         // last key that failed or was refused (not retried)
    std::optional<SurfaceKey> refreshFailed;  // a positions-only update failed here: rebuild instead
    BackgroundJob<bool> prepare;              // the next level made ahead (prepareLevel), if running
    std::optional<SurfaceKey> prepareFailed;  // a key prepareLevel could not make (not retried)
    SurfaceKey preparing;                     // the key of the running (or last) prepare
    std::optional<GpuReservation> reservation;
    bool unparked = false, reshown = false, refreshed = false;
    // What the view waits for while a job runs, and since when: the job may be an older request's
    // (keys 9 then 10: 10 starts when 9 is done), so its own running time undercounts the wait.
    std::optional<SurfaceKey> waitingFor;
    std::chrono::steady_clock::time_point waitingSince;
    // What the view's status reports: why its request was refused or failed, and how deep its
    // scheme goes on this model.
    std::string message;
    int deepestLevel = kMaxLevel;
    SchemeChoice scheme = SchemeChoice::C2PS;  // the scheme asked for (its next level's refusal is reported)
  };

  size_t levelFaces(const Model& model, SchemeChoice scheme, int level) const;
  void show(int v, std::shared_ptr<const BuiltSurface> surface);
  std::optional<EditCost> refreshEditedViews(const SurfaceRequest& request, const Model& model, bool dragging);
  void takeFinishedJob(int v, const SurfaceRequest& request, const Model& model);
  void dropStale(int v, const SurfaceRequest& request, const Model& model);
  // Shows what view v's settings ask for from what is kept, or starts building it.
  void satisfy(int v, const SurfaceRequest& request, const Model& model, const SurfaceKey& wanted);
  void startBuild(int v, const SurfaceRequest& request, const Model& model, const SurfaceKey& wanted);
  void parkShown(int v, const SurfaceRequest& request, const Model& model, const BuiltSurface& next);
  bool unpark(int v, const SurfaceRequest& request, const SurfaceKey& wanted);
  void keepPreviousLevel(int v, const SurfaceRequest& request, const Model& model, const BuiltSurface& next);
  void prepareNextLevel(int v, const SurfaceRequest& request, const Model& model, const SurfaceKey& wanted, bool dragging);

  size_t faceBudget_;
  bool prepareNextLevel_;
  std::array<ViewSurfaces, kMaxViews> views_;
};


}  // namespace polarview
