// Building what a view shows, off the GL thread: refine the model with one scheme to one level,
// extract the limit patches, count them and sample their curvature for the shared colour range.
// SurfaceJobs keeps one job per view in flight (std::async) so the window never waits on it.
// A built surface keeps its refinement hierarchy, so that moving control points (live editing)
// recomputes positions and patches only (refreshSurface), never the topology.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/mesh/poly_mesh.h"
#include "core/spline/patch.h"
#include "core/spline/patch_extraction.h"
#include "pipeline/background_job.h"
#include "pipeline/control_net.h"
#include "pipeline/level_of_detail.h"
#include "pipeline/scheme_choice.h"
#include "pipeline/shading.h"

namespace polarview {

class AdaptiveRefinement;
class ModelAnalysis;

// One model's feature-adaptive refinement with one scheme, kept while a view steps its level:
// deeper levels are added to it (AdaptiveRefinement::extend), shallower ones assembled from its
// LevelPatchCache, and the GPU keeps the patches two levels share (PatchRenderer::setPatches'
// prefix). Shared by the surfaces built from it; `mutex` guards it (jobs extend it off the GL
// thread, edits move its points on the GL thread).
struct BuiltSurface;
struct Model;
struct SurfaceKey;

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

// Memory one view's surface may take while it is built, and what a face of the feature-adaptive
// refinement costs there (its levels and the patches: peak RSS 500-514 bytes a face, C2PS level 12
// on the default model, a valence-64 cap at level 10 and catmark_car at level 8, `bench --adaptive`;
// the sparse steps make about 2 faces a patch, so a face carries half a patch). The face budget of
// a level (all its adaptive levels together) follows; above it a level is refused with a message.
constexpr size_t kViewMemoryBudget = size_t(640) << 20;
constexpr size_t kBytesPerAdaptiveFace = 520;
constexpr size_t kDefaultFaceBudget = kViewMemoryBudget / kBytesPerAdaptiveFace;
// What a face of the finest level of a uniform refinement costs (`refine`'s measure: 236-248 bytes
// of peak memory a face, Catmull-Clark on a cube): the viewer's "refined control mesh" export
// refuses levels whose uniform mesh would not fit the view's memory budget.
constexpr size_t kBytesPerUniformFace = 300;

// RTS and BPS are not C2 at the pole, so their Taylor cap (docs/rings-and-pole.md) has a curvature of
// its own, and its seam with the last ring shows as a ring in curvature maps at shallow levels. The
// views close their holes at this level at the least: the rings in between are exact pieces of the
// limit surface (RTS/BPS refine radially: a ring a level), and the cap there spans ~3e-5 of the
// first ring, below a pixel unless the user zooms in (then a deeper level moves it further in).
constexpr int kNonC2CapLevel = 16;

// What a surface is a function of.
struct SurfaceKey {
  uint64_t model = 0;  // model generation (bumped on every load; the topology)
  SchemeChoice scheme = SchemeChoice::C2PS;
  int level = 0;
  uint64_t points = 0;  // revision of the model's points (bumped by every edit)
  bool operator==(const SurfaceKey& o) const { return sameTopology(o) && points == o.points; }
  bool operator!=(const SurfaceKey& o) const { return !(*this == o); }
  // Same model, scheme and level: the surfaces differ at most in their points, so one is the other
  // after refreshSurface.
  bool sameTopology(const SurfaceKey& o) const { return model == o.model && scheme == o.scheme && level == o.level; }
};

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

// The model every view refines: the mesh, where it came from and what its faces determine. An edit
// replaces `mesh` by a copy with new points (the faces stay) and bumps `points`, keeping the
// analysis; a load makes a new Model (makeModel) and bumps `generation`.
struct Model {
  std::shared_ptr<const PolyMesh> mesh;
  std::string name;        // file path or "default: ..."
  uint64_t generation = 0;
  uint64_t points = 0;     // revision of mesh->points within this generation
  bool radialForRtsBps = false;  // RTS/BPS refine the whole mesh radially (faces x2 a level, not x4)
  // Tables, poles and face estimates, made once for the faces and shared by copies and edits of
  // this model (a view of a Model without one throws std::invalid_argument).
  std::shared_ptr<const ModelAnalysis> analysis;
  // The OBJ text the mesh was read from, as read at load time (null for generated models and
  // conversions): Save OBJ writes the edited points into it (obj_io.h saveObjEdited).
  std::shared_ptr<const std::string> sourceText;
};

// The Model of a mesh (read and checked: checkModelMesh) with its analysis: the one way to make a
// Model views can refine. [O(corners log corners)]
Model makeModel(std::shared_ptr<const PolyMesh> mesh, std::string name, uint64_t generation);

// A model file read and checked off the UI thread: the mesh, or the error of the first problem.
struct LoadedModel {
  std::string path;
  // The mesh with its analysis and the file's bytes as read (Model::sourceText), made on the worker
  // thread: the window only adopts it (its generation is the adopter's to set).
  Model model;
  std::vector<std::string> warnings;  // non-fatal findings of the OBJ reader
  std::string error;                  // empty when the mesh is usable
};

// Reads an OBJ and checks it the way the viewer needs (manifold, supported, has faces); worker-
// thread safe. Never throws: failures come back in LoadedModel::error. [O(file)]
LoadedModel readModelFile(const std::string& path);
// The smallest extent (largest coordinate difference) of a model the viewer and `render` take.
constexpr double kSmallestModelExtent = 1e-150;
// Checks a mesh for the viewer (the topology the refiners need, at least one face, an extent of at
// least kSmallestModelExtent); returns the error message, empty when usable. [O(mesh)]
std::string checkModelMesh(const PolyMesh& mesh, const std::string& name);
// The same faces-and-extent check for the commands that compute curvature (continuity, export to
// ply and glb): throws InputError(name, 0, ...) for a mesh without faces or smaller than
// kSmallestModelExtent. [O(mesh)]
void requireCurvatureExtent(const PolyMesh& mesh, const std::string& name);
// The same for a model made with makeModel: its analysis has built the tables already. [O(points)]
std::string checkModel(const Model& model);

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

// `surface` for the model's current points: updatePositions on its refinement (topology untouched),
// refreshPatches (control points from the recorded stencils), pole markers; the curvature samples are retaken when `resample`, else shared with
// `surface`. The key takes the model's points revision. `surface.key` must have the model's
// generation (std::invalid_argument otherwise). Mutates the shared refinement: call from the thread
// that owns the surface. [O(faces of all levels)]
// The patch set of `level` (< shown.patchLevel) of `shown`'s hierarchy, for drawing in its place
// where the deeper levels are below a pixel (levelToDraw): its key is shown's, its samples shown's
// (the colour range stays that of the level asked for). nullptr when the hierarchy's points are not
// the model's (an edit is being applied) or the level is not made. Takes the hierarchy's mutex.
// [O(patches of the set), levels already extracted]
std::shared_ptr<const BuiltSurface> drawnSurface(const BuiltSurface& shown, const Model& model, int level);

std::shared_ptr<const BuiltSurface> refreshSurface(const BuiltSurface& surface, const Model& model, bool resample,
                                                   RefreshTiming* timing = nullptr);

// The symmetric colour range max(-P(1 - quantile), P(quantile)) of the weighted percentiles P of
// the signed values (quantile 0.95: the 5th and 95th percentiles), so each tail may saturate on at
// most 1 - quantile of the weight; 1 when there is no weight or the range would be 0. [O(n log n)]
double weightedSymmetricRange(const std::vector<double>& values, const std::vector<double>& weights, float quantile);

// The faces the feature-adaptive refinement of `scheme` holds at `level` on the model (all levels
// together; the estimate deepestLevel uses); faceBudget + 1 for a level over `faceBudget`, which
// the estimate does not make. [O(1) after the first call per model, scheme and budget]
size_t estimatedLevelFaces(const Model& model, SchemeChoice scheme, int level, size_t faceBudget = kDefaultFaceBudget);
// The level whose patches a view of `scheme` at `level` shows: `level`, or kNonC2CapLevel for
// schemes that are not C2 at the pole when the model has poles they refine (within the budget).
int patchLevelFor(const Model& model, SchemeChoice scheme, int level, size_t faceBudget);
// The deepest level of `scheme` on `mesh` whose estimated faces fit `faceBudget`, at most kMaxLevel:
// the one limit of the level slider, the keys, `view` and `render`. [O(1) per level]
int deepestLevel(const Model& model, SchemeChoice scheme, size_t faceBudget);
// Empty when `level` is within deepestLevel, else the one-line refusal, e.g. "level 24 refused: C2PS
// stops at level 13 on this model (level 14 would make about 1967589 faces, over the budget of 1290555)".
std::string levelRefusal(const Model& model, SchemeChoice scheme, int level, size_t faceBudget);
// The weighted percentile: the first value (in order) where the running weight reaches `fraction` of
// the total; 0 when there is no weight. [O(n log n)]
double weightedPercentile(const std::vector<double>& values, const std::vector<double>& weights, double fraction);
// Area-weighted histogram over the colour bar of `range` (two slopes or one-sided, as the map:
// colourBarPosition; values beyond go to the end bins), scaled so the largest bin is 1. [O(n)]
std::vector<float> weightedHistogram(const std::vector<double>& values, const std::vector<double>& weights,
                                     const ColourInterval& range, int bins);
// Returns the refusal message when `key` would exceed the budget, empty when it fits. [O(mesh)]
std::string checkFaceBudget(const Model& model, const SurfaceKey& key, size_t faceBudget);

// One view's background job (a BackgroundJob with its key): at most one in flight; a newer
// request waits for it (jobs are never dropped, only their results).
class SurfaceJob {
 public:
  bool running() const { return job_.running(); }
  const SurfaceKey& runningKey() const { return key_; }
  double runningSeconds() const { return job_.runningSeconds(); }
  // Starts building `key` (only when nothing is running), from `reuse` where it fits (buildSurface).
  void start(const Model& model, const SurfaceKey& key, size_t faceBudget, std::shared_ptr<SurfaceHierarchy> reuse = nullptr);
  // The finished result, or nullopt while running / idle. On failure: the error message.
  struct Outcome {
    std::shared_ptr<const BuiltSurface> surface;
    std::string error;
    SurfaceKey key;
  };
  std::optional<Outcome> poll();
  // Blocks until the running job (if any) has finished and returns its outcome.
  std::optional<Outcome> wait();

 private:
  std::optional<Outcome> outcome(bool block);
  BackgroundJob<std::shared_ptr<const BuiltSurface>> job_;
  SurfaceKey key_;
};

}  // namespace polarview
