// Building what a view shows, off the GL thread: refine the model with one scheme to one level,
// extract the limit patches, count them and sample their curvature for the shared colour range.
// A built surface keeps its refinement hierarchy, so that moving control points (live editing)
// recomputes positions and patches only (refreshSurface), never the topology.
// One view's background job: surface_job.h.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/mesh/poly_mesh.h"
#include "core/spline/patch.h"
#include "core/spline/patch_extraction.h"
#include "pipeline/control_net.h"
#include "pipeline/level_of_detail.h"
#include "pipeline/model.h"
#include "pipeline/scheme_choice.h"
#include "pipeline/surface_key.h"

namespace polarview {

class AdaptiveRefinement;
struct BuiltSurface;

// One model's feature-adaptive refinement with one scheme, kept while a view steps its level:
// deeper levels are added to it (AdaptiveRefinement::extend), shallower ones assembled from its
// LevelPatchCache, and the GPU keeps the patches two levels share (PatchRenderer::setPatches'
// prefix). Shared by the surfaces built from it; `mutex` guards it (jobs extend it off the GL
// thread, edits move its points on the GL thread).
struct SurfaceHierarchy {
  explicit SurfaceHierarchy(std::unique_ptr<AdaptiveRefinement> refinement);
  ~SurfaceHierarchy();
  std::mutex mutex;
  uint64_t model = 0;   // model generation
  SchemeChoice scheme = SchemeChoice::C2PS;
  uint64_t points = 0;  // the model's points revision its levels were computed at
  std::unique_ptr<AdaptiveRefinement> refinement;
  LevelPatchCache cache;
  // Names the cache's sequence of regular patches for PatchRenderer::setPatches: unique among all
  // hierarchies, renewed whenever the cache is dropped (points moved).
  uint64_t stamp = 0;
  void renewStamp();
  // The deepest level a surface was built at (edits keep the levels up to it; deeper ones were
  // made ahead and are dropped), and the deepest made (read without the mutex by the GL thread).
  int deepestShown = 0;
  std::atomic<int> deepestMade{0};
  // The level prepareLevel made ahead: its set's regular patches and caps (a viewer reserves GPU
  // room for them while idle, so the step does not grow buffers).
  std::atomic<int> preparedLevel{-1};
  std::atomic<size_t> preparedRegular{0}, preparedCaps{0};
  // The patch memory of a surface built from it that is gone, for the next assembly to reuse
  // (guarded by spareMutex: surfaces die on the GL thread while a job may assemble).
  std::mutex spareMutex;
  std::vector<Patch> spare;
  // The next level's whole surface (patches, samples), assembled while the view was idle; the
  // build of its key hands it out at once (guarded by mutex; it holds no pointer back here).
  std::shared_ptr<BuiltSurface> ahead;
  std::atomic<int> aheadLevel{-1};  // its key's level, -1 when there is none (read without the mutex)
  std::vector<NetSegment> netSegments;  // the model's control net (its topology: made once)
};

// Makes the surface of `key` (the level after the one shown) ahead of the user in `hierarchy`:
// its levels (extend), its patches and curvature samples, kept as SurfaceHierarchy::ahead for
// buildSurface, when the hierarchy is still at the model's points. False when it could not (the
// budget, memory): the level is made, or refused with a message, when the user asks for it; the
// caller should not try the same key again. [O(new levels + patches of the set)]
bool prepareLevel(SurfaceHierarchy& hierarchy, const Model& model, const SurfaceKey& key, size_t faceBudget) noexcept;
// Frees the surface made ahead (another view is made ahead now: one at a time). [O(1)]
void dropAhead(SurfaceHierarchy& hierarchy);

// Curvature samples for the automatic colour range, each with the surface area it stands for
// (small patches crowd around extraordinary points; unweighted they would dominate the range).
// End-cap patches (Catmull-Clark extraordinary vertices, where K is unbounded or forced to 0
// except at valence 4) are left out unless there is nothing else.
struct CurvatureSamples {
  std::vector<double> gaussian, mean, areas;  // double: K of a model of 1e-80 is 1e160
  uint64_t points = 0;  // the points revision they were taken at
};

struct BuiltSurface {
  BuiltSurface() = default;
  BuiltSurface(const BuiltSurface&) = default;
  // Hands its patch memory to the hierarchy (SurfaceHierarchy::spare) when it is the larger.
  ~BuiltSurface();
  SurfaceKey key;
  int patchLevel = 0;  // the level whose patch set is shown (patchLevelFor: key.level, or deeper)
  std::vector<Patch> patches;
  PolyMesh controlMesh;              // the base cage the view draws as its control net (the model)
  std::vector<NetSegment> netSegments;  // its edges once, crease edges marked (control_net.h)
  std::vector<Point> poles;          // limit positions of the poles (markers)
  std::array<int, kPatchKindCount> patchesPerKind{};
  DetailSizes detail;  // what levelToDraw needs of `patches`
  // Shared between a surface and its refreshed successors while a drag goes on (sampling every
  // frame would cost more than the edit); retaken when the drag ends.
  std::shared_ptr<const CurvatureSamples> samples;
  // The refinement the patches came from, kept for positions-only updates (refreshSurface). Only
  // the thread that owns the surface touches it (the worker while building, then the GL thread).
  std::shared_ptr<AdaptiveRefinement> refinement;
  // How each patch was made (stencils), shared the same way: a refresh recomputes control points
  // only (refreshPatches), no classification.
  std::shared_ptr<const PatchSources> sources;
  // What `refinement` belongs to, and where the patches came from in it: the first
  // `regularCount` patches are the regular patches of levels 0..key.level of the sequence that
  // LevelPatchCache kept under `stamp` (PatchRenderer::setPatches keeps them on the GPU).
  std::shared_ptr<SurfaceHierarchy> hierarchy;
  uint64_t stamp = 0;
  size_t regularCount = 0;
  // Building it: refinement (made, or stepped: extend / new points), patch set (extracted or
  // assembled, pole markers), curvature samples; refineMs is all three.
  double refineMs = 0.0, refineOnlyMs = 0.0, patchesMs = 0.0, samplesMs = 0.0;
  // Polar configurations of the model refined by the scheme / by Catmull-Clark instead (RTS and
  // BPS need valence >= 5), and why; both 0 for Catmull-Clark itself.
  int polesByScheme = 0, polesByCatmullClark = 0;
  std::string fallbackReason;
};

// Refines and extracts (worker-thread safe: touches no shared state but `reuse`, under its mutex).
// With `reuse` of the same model and scheme, the surface comes from it: extended to a deeper level,
// assembled for a shallower one (points brought to the model's first). Throws InputError when the
// level is over `faceBudget` or the mesh cannot be refined. [O(output); O(new levels + patches) with reuse]
std::shared_ptr<const BuiltSurface> buildSurface(const Model& model, const SurfaceKey& key, size_t faceBudget,
                                                 std::shared_ptr<SurfaceHierarchy> reuse = nullptr);

// What one positions-only update cost (milliseconds).
struct RefreshTiming {
  double positionsMs = 0.0;  // AdaptiveRefinement::updatePositions
  double patchesMs = 0.0;    // refreshPatches and the pole markers
  double samplesMs = 0.0;    // curvature samples (when retaken)
};

// The patch set of `level` (< shown.patchLevel) of `shown`'s hierarchy, for drawing in its place
// where the deeper levels are below a pixel (levelToDraw): its key is shown's, its samples shown's
// (the colour range stays that of the level asked for). nullptr when the hierarchy's points are not
// the model's (an edit is being applied) or the level is not made. Takes the hierarchy's mutex.
// [O(patches of the set), levels already extracted]
std::shared_ptr<const BuiltSurface> drawnSurface(const BuiltSurface& shown, const Model& model, int level);

// `surface` for the model's current points: updatePositions on its refinement (topology untouched),
// refreshPatches (control points from the recorded stencils), pole markers; the curvature samples are retaken when `resample`, else shared with
// `surface`. The key takes the model's points revision. `surface.key` must have the model's
// generation (std::invalid_argument otherwise). Mutates the shared refinement: call from the thread
// that owns the surface. [O(faces of all levels)]
std::shared_ptr<const BuiltSurface> refreshSurface(const BuiltSurface& surface, const Model& model, bool resample,
                                                   RefreshTiming* timing = nullptr);

}  // namespace polarview
