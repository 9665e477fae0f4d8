#include "pipeline/surface_build.h"


#include "core/subdiv/parallel_for.h"

#include "pipeline/stopwatch.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/mesh/input_error.h"
#include "core/mesh/manifold_split.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/topology.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/adaptive_refiner.h"
#include "core/subdiv/polar_config.h"
#include "core/subdiv/refiner.h"
#include "pipeline/level_limits.h"
#include "pipeline/model_analysis.h"
#include "pipeline/weighted_statistics.h"

namespace polarview {
namespace {

// Samples per patch (per direction) for the colour range: enough for a robust percentile, capped
// at about 200k evaluations so a level-6 model still builds in well under a second.
int curvatureSamplesPerPatch(size_t patchCount) {
  if (patchCount == 0) return 1;
  double perPatch = 200000.0 / double(patchCount);
  return std::clamp(int(std::sqrt(perPatch)), 1, 4);
}

// Pole markers: the cap's p0 is the exact limit of the pole (paper (32)); schemes without caps
// (Catmull-Clark) mark the pole vertices of the finest control mesh.
std::vector<Point> polePositions(const std::vector<Patch>& patches, const RefinedLevel& finest) {
  std::map<int32_t, Point> capPoles;
  for (const Patch& patch : patches) {
    if (patch.kind == PatchKind::PoleCap) capPoles.emplace(patch.pole, patch.origin + patch.cp[0]);
  }
  std::vector<Point> poles;
  for (const auto& [index, position] : capPoles) poles.push_back(position);
  if (poles.empty()) {
    for (const PolarConfig& config : finest.poles) poles.push_back(finest.absolutePoint(config.pole));
  }
  return poles;
}

// Polar configurations the scheme refines, and those Catmull-Clark refines instead (RTS and BPS
// below valence 5), with the reason, so the view's title can say so.
void countPoleFallbacks(BuiltSurface& surface, const std::vector<PolarConfig>& configs, Scheme scheme) {
  if (scheme == Scheme::CatmullClark) return;
  for (const PolarConfig& config : configs) {
    if (config.rejection == PolarRejection::SharpFeature || config.rejection == PolarRejection::Hole) {  // a pole, but tags keep the scheme off it
      ++surface.polesByCatmullClark;
      surface.fallbackReason = config.reason;
      continue;
    }
    if (!config.refinable) continue;  // a plain extraordinary vertex, not a polar configuration
    std::string why;
    if (schemeRefinesPole(scheme, config, &why)) {
      ++surface.polesByScheme;
    } else {
      ++surface.polesByCatmullClark;
      surface.fallbackReason = why;
    }
  }
}

constexpr size_t kMostSampledPatches = 60000;

// |du x dv| without underflow or overflow: through derivatives scaled by a power of two (exact) to
// size ~1 (a model of 1e-150 has an area element of 1e-300, whose squares glm::length would square).
double areaElement(const Point& du, const Point& dv) {
  const double largest = std::max({std::abs(du.x), std::abs(du.y), std::abs(du.z), std::abs(dv.x), std::abs(dv.y), std::abs(dv.z)});
  if (!(largest > 0.0) || !std::isfinite(largest)) return 0.0;
  const int exponent = std::ilogb(largest);
  const double scale = std::ldexp(1.0, -exponent);
  return std::ldexp(glm::length(glm::cross(scale * du, scale * dv)), 2 * exponent);
}

// K, H and area element at the centres of an s x s grid of cells per patch (exact derivatives).
// End caps are skipped when other patches exist: at a Catmull-Clark extraordinary vertex K is
// unbounded (valence 3) or forced to zero (valence > 4), so their values say nothing about the
// shape's curvature scale and, at a valence-3 corner, would stretch the range until the rest of the
// model is one colour. They still saturate visibly in the picture.
std::shared_ptr<const CurvatureSamples> sampleCurvatures(const std::vector<Patch>& patches, int s, uint64_t points) {
  auto samples = std::make_shared<CurvatureSamples>();
  samples->points = points;
  const bool onlyEndCaps =
      std::all_of(patches.begin(), patches.end(), [](const Patch& p) { return p.kind == PatchKind::EndCap; });
  // Deep levels hold hundreds of thousands of patches: every stride-th one is sampled, standing
  // for the area of `stride` patches (the percentiles are of the area, the patches come level by level).
  const size_t stride = std::max<size_t>(1, patches.size() / kMostSampledPatches);
  const size_t sampled = (patches.size() + stride - 1) / stride;
  // Split over the cores in contiguous parts, joined in order: the same samples as one thread's.
  const unsigned parts = threadsFor(sampled * size_t(s) * size_t(s) * 8);
  std::vector<CurvatureSamples> part(parts);
  runParts(parts, [&](unsigned k) {
    CurvatureSamples& out = part[k];
    for (size_t n = size_t(partBound(Index(sampled), parts, k)); n < size_t(partBound(Index(sampled), parts, k + 1)); ++n) {
      const Patch& patch = patches[n * stride];
      if (patch.kind == PatchKind::EndCap && !onlyEndCaps) continue;
      for (int j = 0; j < s; ++j) {
        for (int i = 0; i < s; ++i) {
          SurfacePoint p = evaluatePatch(patch, (i + 0.5) / s, (j + 0.5) / s);
          double area = areaElement(p.du, p.dv) * double(stride) / double(s * s);
          if (!std::isfinite(p.gaussian) || !std::isfinite(p.mean) || !std::isfinite(area)) continue;
          out.gaussian.push_back(p.gaussian);
          out.mean.push_back(p.mean);
          out.areas.push_back(area);
        }
      }
    }
  });
  for (const CurvatureSamples& from : part) {
    samples->gaussian.insert(samples->gaussian.end(), from.gaussian.begin(), from.gaussian.end());
    samples->mean.insert(samples->mean.end(), from.mean.begin(), from.mean.end());
    samples->areas.insert(samples->areas.end(), from.areas.begin(), from.areas.end());
  }
  return samples;
}

}  // namespace

SurfaceHierarchy::SurfaceHierarchy(std::unique_ptr<AdaptiveRefinement> made) : refinement(std::move(made)) { renewStamp(); }
SurfaceHierarchy::~SurfaceHierarchy() = default;

BuiltSurface::~BuiltSurface() {
  if (!hierarchy || patches.capacity() == 0) return;
  const std::lock_guard<std::mutex> lock(hierarchy->spareMutex);
  if (patches.capacity() > hierarchy->spare.capacity()) hierarchy->spare = std::move(patches);
}

void SurfaceHierarchy::renewStamp() {
  static std::atomic<uint64_t> next{1};
  stamp = next.fetch_add(1);
}

namespace {

// The surface of `key` at patch level `level` from `hierarchy` (its mutex held, its points the
// model's): patches, poles, statistics and curvature samples; the hierarchy pointers are the
// caller's to set. Adds the time of each part to the surface's counters.
std::shared_ptr<BuiltSurface> assembleSurface(const Model& model, const SurfaceKey& key, SurfaceHierarchy& hierarchy, int level,
                                              bool sample = true) {
  auto surface = std::make_shared<BuiltSurface>();
  surface->key = key;
  surface->key.points = model.points;
  surface->patchLevel = level;
  AdaptiveRefinement& refinement = *hierarchy.refinement;
  const auto patchesStart = std::chrono::steady_clock::now();
  auto sources = std::make_shared<PatchSources>();
  std::vector<Patch> storage;
  {
    const std::lock_guard<std::mutex> spareLock(hierarchy.spareMutex);
    storage = std::move(hierarchy.spare);
  }
  // A new hierarchy's first surface is extracted once, straight into its set: through the cache
  // every patch would be written twice into fresh memory (page faults are half of it). The set is
  // the same patch for patch; the cache takes the levels when the next one is made ahead.
  const bool firstBuild = hierarchy.cache.empty() && refinement.levelCount() - 1 == level;
  PatchSet patchSet = firstBuild ? extractPatches(refinement, sources.get())
                                 : hierarchy.cache.patchSet(refinement, level, sources.get(), std::move(storage));
  // The regular patches of levels 0..level lead the set (the renderer keeps them across steps).
  surface->regularCount = patchSet.patches.size() - patchSet.count(PatchKind::PoleCap) - patchSet.count(PatchKind::EndCap);
  surface->stamp = hierarchy.stamp;
  surface->sources = std::move(sources);
  surface->patches = std::move(patchSet.patches);
  surface->controlMesh = *model.mesh;  // the base cage: what the user edits (deep levels are partial)
  if (hierarchy.netSegments.empty()) hierarchy.netSegments = controlNetSegments(surface->controlMesh);
  surface->netSegments = hierarchy.netSegments;
  surface->poles = polePositions(surface->patches, refinement.level(level));
  countPoleFallbacks(*surface, analysisOf(model).polarConfigs(), refinement.options().scheme);
  surface->detail = detailSizes(surface->patches);
  surface->patchesMs = millisecondsSince(patchesStart);
  if (!sample) return surface;

  // Statistics and curvature samples (the shared automatic colour range is taken over all views).
  const auto samplesStart = std::chrono::steady_clock::now();
  for (const Patch& patch : surface->patches) ++surface->patchesPerKind[size_t(patch.kind)];
  surface->samples = sampleCurvatures(surface->patches, curvatureSamplesPerPatch(surface->patches.size()), model.points);
  surface->samplesMs = millisecondsSince(samplesStart);
  return surface;
}

}  // namespace

std::shared_ptr<const BuiltSurface> buildSurface(const Model& model, const SurfaceKey& key, size_t faceBudget,
                                                 std::shared_ptr<SurfaceHierarchy> reuse) {
  auto start = std::chrono::steady_clock::now();

  // Refine feature-adaptively and extract the limit patches. The level limit (deepestLevel) comes
  // from the estimate; the refiner's own hard limit leaves it room (the estimate is an upper bound
  // at the measured levels, an extrapolation beyond). The refinement stays with the surface for
  // positions-only updates while the user drags a control point, and for the next level step.
  const std::string refusal = levelRefusal(model, key.scheme, key.level, faceBudget);
  if (!refusal.empty()) throw InputError(model.name, 0, refusal);
  if (!reuse || reuse->model != model.generation || reuse->scheme != key.scheme) {
    // From the model's tables and poles; a mesh the analysis could not refine goes to the refiner
    // for its InputError (what the view shows).
    const ModelAnalysis& analysis = analysisOf(model);
    const RefineOptions options = refineOptionsFor(key.scheme, key.level);
    reuse = std::make_shared<SurfaceHierarchy>(
        analysis.error().empty()
            ? std::make_unique<AdaptiveRefinement>(*model.mesh, analysis.preparedBase(*model.mesh), options, model.name, 2 * faceBudget)
            : std::make_unique<AdaptiveRefinement>(*model.mesh, options, model.name, 2 * faceBudget));
    reuse->model = model.generation;
    reuse->scheme = key.scheme;
    reuse->points = model.points;
  }
  SurfaceHierarchy& hierarchy = *reuse;
  const std::lock_guard<std::mutex> lock(hierarchy.mutex);
  AdaptiveRefinement& refinement = *hierarchy.refinement;
  if (hierarchy.points != model.points) {  // built before the last edits: their points first
    refinement.updatePositions(model.mesh->points);
    hierarchy.cache.forget();
    hierarchy.renewStamp();
    hierarchy.points = model.points;
    hierarchy.ahead.reset();
    hierarchy.aheadLevel = -1;
  }
  const int level = patchLevelFor(model, key.scheme, key.level, faceBudget);
  // Made ahead while the view was idle (prepareLevel): handed out as it is.
  std::shared_ptr<BuiltSurface> surface = std::move(hierarchy.ahead);
  hierarchy.ahead.reset();
  hierarchy.aheadLevel = -1;
  const bool madeAhead = surface && surface->key.sameTopology(key) && surface->key.points == model.points &&
                         surface->stamp == hierarchy.stamp;
  if (madeAhead) {
    surface->refineOnlyMs = surface->patchesMs = surface->samplesMs = 0.0;
  } else {
    surface.reset();  // a stale one goes (its memory with it)
    if (refinement.levelCount() - 1 < level) refinement.extend(level - (refinement.levelCount() - 1), 2 * faceBudget);
    hierarchy.deepestMade = refinement.levelCount() - 1;
    const double refineMs = millisecondsSince(start);
    surface = assembleSurface(model, key, hierarchy, level);
    surface->refineOnlyMs = refineMs;
  }
  hierarchy.deepestShown = std::max(hierarchy.deepestShown, level);
  surface->refinement = std::shared_ptr<AdaptiveRefinement>(reuse, hierarchy.refinement.get());
  surface->hierarchy = std::move(reuse);
  surface->refineMs = millisecondsSince(start);
  return surface;
}

std::shared_ptr<const BuiltSurface> drawnSurface(const BuiltSurface& shown, const Model& model, int level) {
  if (!shown.hierarchy || level < 0 || level >= shown.patchLevel) return nullptr;
  SurfaceHierarchy& hierarchy = *shown.hierarchy;
  const std::lock_guard<std::mutex> lock(hierarchy.mutex);
  if (hierarchy.points != model.points || hierarchy.refinement->levelCount() - 1 < level) return nullptr;
  std::shared_ptr<BuiltSurface> surface = assembleSurface(model, shown.key, hierarchy, level, false);
  surface->samples = shown.samples;
  surface->hierarchy = shown.hierarchy;
  surface->refinement = shown.refinement;
  return surface;
}

std::shared_ptr<const BuiltSurface> refreshSurface(const BuiltSurface& surface, const Model& model, bool resample,
                                                   RefreshTiming* timing) {
  if (surface.key.model != model.generation || !surface.hierarchy)
    throw std::invalid_argument("refreshSurface: the surface was not built from this model's topology");
  RefreshTiming measured;
  // Everything of the topology stays (counts, fallbacks, level, hierarchy, sources, timings).
  auto refreshed = std::make_shared<BuiltSurface>(surface);
  refreshed->key.points = model.points;

  // Positions of every level from the new base points; the levels' meshes and tables stay. The
  // hierarchy may be shared with surfaces of other levels: whichever comes first moves its points.
  SurfaceHierarchy& hierarchy = *surface.hierarchy;
  const std::lock_guard<std::mutex> lock(hierarchy.mutex);
  auto start = std::chrono::steady_clock::now();
  AdaptiveRefinement& refinement = *hierarchy.refinement;
  if (hierarchy.points != model.points) {
    // Levels made ahead would only slow every drag frame down: gone (made again when asked for).
    if (refinement.levelCount() - 1 > hierarchy.deepestShown) refinement.truncate(hierarchy.deepestShown);
    hierarchy.deepestMade = refinement.levelCount() - 1;
    refinement.updatePositions(model.mesh->points);
    hierarchy.cache.forget();  // its patches are of the old points
    hierarchy.renewStamp();
    hierarchy.points = model.points;
    hierarchy.ahead.reset();  // of the old points too
    hierarchy.aheadLevel = -1;
  }
  measured.positionsMs = millisecondsSince(start);

  // The patches and pole markers of the moved points; counts and fallbacks are the topology's.
  start = std::chrono::steady_clock::now();
  PatchSet patchSet;
  patchSet.patches = std::move(refreshed->patches);  // the copy made above, refreshed in place
  refreshPatches(refinement, *surface.sources, patchSet);
  refreshed->patches = std::move(patchSet.patches);
  refreshed->poles = polePositions(refreshed->patches, refinement.level(surface.patchLevel));
  measured.patchesMs = millisecondsSince(start);
  refreshed->controlMesh = *model.mesh;
  refreshed->stamp = hierarchy.stamp;  // new points: nothing on the GPU is theirs

  start = std::chrono::steady_clock::now();
  refreshed->samples = resample ? sampleCurvatures(refreshed->patches, curvatureSamplesPerPatch(refreshed->patches.size()),
                                                   model.points)
                                : surface.samples;
  measured.samplesMs = resample ? millisecondsSince(start) : 0.0;
  if (timing) *timing = measured;
  return refreshed;
}

bool prepareLevel(SurfaceHierarchy& hierarchy, const Model& model, const SurfaceKey& key, size_t faceBudget) noexcept {
  // Locked across the failure path too: a step's build may be taking `ahead` meanwhile.
  const std::lock_guard<std::mutex> lock(hierarchy.mutex);
  try {
    AdaptiveRefinement& refinement = *hierarchy.refinement;
    if (hierarchy.points != model.points) return true;  // an edit came first: nothing to make
    const int level = patchLevelFor(model, key.scheme, key.level, faceBudget);
    if (refinement.levelCount() - 1 < level) refinement.extend(level - (refinement.levelCount() - 1), 2 * faceBudget);
    hierarchy.deepestMade = refinement.levelCount() - 1;
    hierarchy.cache.prepare(refinement, level);
    const auto [regular, caps] = hierarchy.cache.preparedCounts(level);
    hierarchy.preparedRegular = regular;
    hierarchy.preparedCaps = caps;
    hierarchy.preparedLevel = level;
    hierarchy.ahead.reset();  // an older one's memory first
    hierarchy.aheadLevel = -1;
    hierarchy.ahead = assembleSurface(model, key, hierarchy, level);
    hierarchy.aheadLevel = key.level;
    return true;
  } catch (...) {
    // Over the budget, or out of memory: the level is made (or refused) when the user asks for it.
    hierarchy.ahead.reset();
    hierarchy.aheadLevel = -1;
    hierarchy.preparedLevel = -1;
    return false;
  }
}

void dropAhead(SurfaceHierarchy& hierarchy) {
  const std::lock_guard<std::mutex> lock(hierarchy.mutex);
  hierarchy.ahead.reset();
  hierarchy.aheadLevel = -1;
}

}  // namespace polarview
