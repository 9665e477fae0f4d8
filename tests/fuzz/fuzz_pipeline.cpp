// libFuzzer target over the whole pipeline (tests/fuzz/README.md): OBJ bytes -> parseObjText ->
// buildTopology -> findPolarConfigs -> every scheme (cc, c2ps, c2ps-u, rts, rts-u, bps) at one
// level in 1..3 (picked by a hash of the input), uniform (Refinement) and feature-adaptive
// (AdaptiveRefinement) -> extractPatches (and refreshPatches after a base point moves) -> the pole
// analysis of `polarview pole` (Taylor coefficients, analyzePole, ringCurvatures).
//
// Expected: polarview::InputError for bad input or a level over the face budget. A finding: any
// other exception (std::logic_error, std::invalid_argument from inside the pipeline, whose
// arguments are all valid here), a crash, ASan/UBSan report, a hang, or a broken invariant:
//  * every patch control point, evaluated position, pole limit and normal is finite (the reader
//    bounds coordinates by kMaxObjCoordinate for exactly that); the pole's K and H whenever
//    analyzePole says they are defined; the patches' and rings' K and H for coordinates <= 1e6
//    and none tiny (0 < |x| < 1e-100: two points 1e-300 apart make K ~ 1e600, past a double);
//  * the adaptive patch set equals the uniform one (count per kind, and the sum of all B-spline
//    control points, which face numbering and quarter turns do not change) for levels <= 3;
//  * refreshPatches after updatePositions equals a fresh extractPatches;
//  * the parsed mesh keeps the reader's guarantees and the polar configurations theirs
//    (checkParsedMesh, checkPolarConfigs in fuzz_common.h).
// Each input is bounded (bytes, faces, vertices, finest-level faces) so one run stays fast; the
// fast targets (fuzz_obj, fuzz_topology, fuzz_poles, fuzz_estimate) fuzz the first stages alone.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/mesh/input_error.h"
#include "core/mesh/manifold_split.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/topology.h"
#include "core/spline/patch_extraction.h"
#include "core/spline/pole_taylor.h"
#include "core/spline/ring_curvature.h"
#include "core/subdiv/adaptive_refiner.h"
#include "core/subdiv/polar_config.h"
#include "core/subdiv/refiner.h"
#include "fuzz_common.h"
#include "obj_mutator.h"

using namespace polarview;
using namespace polarview::fuzz;

namespace {

// Inputs over 16 KiB, 200 faces or 400 vertices are skipped (the whole seed corpus fits).
constexpr InputLimits kLimits{16 << 10, 200, 400};
constexpr size_t kMaxFinestFaces = 4096;    // Refinement's budget (finest level)
constexpr size_t kMaxAdaptiveFaces = 8192;  // AdaptiveRefinement's budget (all levels)
constexpr int kMaxLevel = 3;
constexpr int kMaxRings = 3;           // ringCurvatures
constexpr int kMaxRingValence = 4096;  // C2PS doubles the valence per ring
constexpr double kModerate = 1e6;      // coordinates up to this (and none under kTiny): K and H finite too
constexpr double kTiny = 1e-100;       // a coordinate under this, not 0, may make a feature 1e-300 wide

struct Variant {
  Scheme scheme;
  bool uniformFirstStep;
  const char* name;
};
constexpr Variant kVariants[] = {
    {Scheme::CatmullClark, false, "cc"}, {Scheme::C2PS, false, "c2ps"}, {Scheme::C2PS, true, "c2ps-u"},
    {Scheme::RTS, false, "rts"},         {Scheme::RTS, true, "rts-u"},  {Scheme::BPS, false, "bps"},
};

// Control points finite; positions finite at the corners and the centre; K and H finite too when
// the input is of moderate size (a degenerate frame gives normal 0, K = H = 0, not NaN). Messages
// are only built for a finding: this runs on every patch.
void checkPatchSet(const PatchSet& set, bool moderate) {
  size_t counted = 0;
  for (size_t k = 0; k < set.kindCounts.size(); ++k) counted += set.kindCounts[k];
  if (counted != set.patches.size())
    fail("kindCounts sum to " + std::to_string(counted) + " for " + std::to_string(set.patches.size()) + " patches");
  auto name = [&](size_t i) { return std::string(patchKindName(set.patches[i].kind)) + " patch " + std::to_string(i); };
  constexpr double kSamples[5][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}};
  for (size_t i = 0; i < set.patches.size(); ++i) {
    const Patch& patch = set.patches[i];
    for (int c = 0; c < 16; ++c)
      if (!allFinite(patch.cp[c] + patch.origin)) requireFinite(patch.cp[c] + patch.origin, name(i) + " cp[" + std::to_string(c) + "]");
    for (const auto& uv : kSamples) {
      const SurfacePoint sp = evaluatePatch(patch, uv[0], uv[1]);
      const bool ok = allFinite(sp.position) &&
                      (!moderate || (allFinite(sp.normal) && std::isfinite(sp.gaussian) && std::isfinite(sp.mean)));
      if (ok) continue;
      const std::string at = name(i) + " at (" + std::to_string(uv[0]) + ", " + std::to_string(uv[1]) + ")";
      requireFinite(sp.position, at + " position");
      requireFinite(sp.normal, at + " normal");
      requireFinite(sp.gaussian, at + " K");
      requireFinite(sp.mean, at + " H");
    }
  }
}

// Sum of the B-spline control points of every face-based patch: independent of face ids and of
// which corner a patch starts at. Caps are compared by count only (their columns may start
// elsewhere).
Point controlPointSum(const PatchSet& set, double& magnitude) {
  Point sum(0.0);
  magnitude = 0.0;
  for (const Patch& patch : set.patches) {
    if (patch.kind == PatchKind::PoleCap) continue;
    for (const Point& relative : patch.cp) {
      const Point p = patch.origin + relative;
      sum += p, magnitude += std::abs(p.x) + std::abs(p.y) + std::abs(p.z);
    }
  }
  return sum;
}

void compareUniformAdaptive(const PatchSet& uniform, const PatchSet& adaptive) {
  for (size_t k = 0; k < uniform.kindCounts.size(); ++k)
    if (uniform.kindCounts[k] != adaptive.kindCounts[k])
      fail(std::string("adaptive has ") + std::to_string(adaptive.kindCounts[k]) + " " + patchKindName(PatchKind(k)) +
           " patches, uniform " + std::to_string(uniform.kindCounts[k]));
  double mu = 0.0, ma = 0.0;
  const Point su = controlPointSum(uniform, mu), sa = controlPointSum(adaptive, ma);
  const double tolerance = 1e-9 * std::max(mu, ma) + 1e-300;
  if (glm::length(su - sa) > tolerance)
    fail("adaptive control points sum differs from uniform's by " + std::to_string(glm::length(su - sa)) +
         " (tolerance " + std::to_string(tolerance) + ")");
}

void compareRefreshed(const PatchSet& refreshed, const PatchSet& fresh) {
  if (refreshed.patches.size() != fresh.patches.size())
    fail("refreshPatches kept " + std::to_string(refreshed.patches.size()) + " patches, fresh extraction has " +
         std::to_string(fresh.patches.size()));
  for (size_t i = 0; i < fresh.patches.size(); ++i) {
    const Patch a = withAbsolutePositions(refreshed.patches[i]), b = withAbsolutePositions(fresh.patches[i]);
    if (a.kind != b.kind || a.level != b.level || a.edgeLevelDelta != b.edgeLevelDelta)
      fail("refreshed patch " + std::to_string(i) + " differs in kind, level or level jumps from a fresh extraction");
    double scale = 0.0, diff = 0.0;
    for (int c = 0; c < 16; ++c) {
      scale = std::max(scale, glm::length(b.cp[c]));
      diff = std::max(diff, glm::length(a.cp[c] - b.cp[c]));
    }
    if (diff > 1e-9 * scale + 1e-300)
      fail("refreshed patch " + std::to_string(i) + " (" + patchKindName(b.kind) +
           ") differs from a fresh extraction by " + std::to_string(diff) + " (scale " + std::to_string(scale) + ")");
  }
}

// Uniform and adaptive refinement of one scheme and level, their patches, and a live edit.
void runRefinements(const PolyMesh& mesh, const Variant& variant, int levels, bool moderate, double size) {
  const RefineOptions options{variant.scheme, levels, variant.uniformFirstStep};
  const std::string where = std::string(variant.name) + " level " + std::to_string(levels);

  gStage = where + ": Refinement";
  PatchSet uniform;
  bool haveUniform = false;
  try {
    // Every other input as `refine` and `bench` make it: the finest level's rings left out, then
    // made on demand (both paths stay fuzzed).
    RefineOptions uniformOptions = options;
    uniformOptions.fullFinestTopology = (mesh.faceVerts.size() + size_t(levels)) % 2 == 0;
    Refinement refinement(mesh, uniformOptions, kSource, kMaxFinestFaces);
    gStage = where + ": completeFinestTopology";
    refinement.completeFinestTopology();
    gStage = where + ": extractPatches(uniform)";
    uniform = extractPatches(refinement);
    haveUniform = true;
    checkPatchSet(uniform, moderate);
  } catch (const InputError&) {  // over the budget
  }

  gStage = where + ": AdaptiveRefinement";
  try {
    AdaptiveRefinement refinement(mesh, options, kSource, kMaxAdaptiveFaces);
    gStage = where + ": extractPatches(adaptive)";
    PatchSources sources;
    PatchSet adaptive = extractPatches(refinement, &sources);
    checkPatchSet(adaptive, moderate);
    // Both refiners apply crease and corner tags (Catmull-Clark's); under Chaikin's rule the adaptive
    // one decays half edges at the rim of a copied-out part from an incomplete ring (docs/schemes.md),
    // so only CREASE_UNIFORM is compared.
    const bool chaikin = variant.scheme == Scheme::CatmullClark && mesh.tags.creaseMethod == CreaseMethod::Chaikin &&
                         mesh.tags.hasSharpFeatures();
    if (haveUniform && !chaikin) {
      gStage = where + ": adaptive vs uniform";
      compareUniformAdaptive(uniform, adaptive);
    }

    // Live edit: move the first vertex of the first face by 1% of the model's size.
    gStage = where + ": updatePositions + refreshPatches";
    std::vector<Point> moved = mesh.points;
    moved[size_t(mesh.faceVerts[0])] += Point(0.01 * size, -0.007 * size, 0.003 * size);
    refinement.updatePositions(moved);
    refreshPatches(refinement, sources, adaptive);
    checkPatchSet(adaptive, moderate);
    gStage = where + ": extractPatches after the edit";
    compareRefreshed(adaptive, extractPatches(refinement));
  } catch (const InputError&) {  // over the budget
  }
}

// `polarview pole`: the level-0 Taylor expansion of each pole, its differential, and rings 1..M.
void runPoleAnalysis(const PolyMesh& mesh, const Variant& variant, bool moderate) {
  const std::string where = std::string(variant.name) + " pole";
  gStage = where + ": Refinement level 0";
  Refinement refinement(mesh, {variant.scheme, 0, variant.uniformFirstStep}, kSource, kMaxFinestFaces);
  const RefinedLevel& level = refinement.level(0);
  if (level.poleTaylor.size() != level.poles.size() || level.poleGrids.size() != level.poles.size())
    fail(std::to_string(level.poles.size()) + " poles with " + std::to_string(level.poleTaylor.size()) +
         " expansions and " + std::to_string(level.poleGrids.size()) + " grids");
  for (size_t k = 0; k < level.poles.size(); ++k) {
    const std::string pole = where + " " + std::to_string(level.poles[k].pole);
    gStage = pole + ": analyzePole";
    const TaylorCoefficients& t = level.poleTaylor[k];
    for (int i = 0; i < 6; ++i) requireFinite(t.p[size_t(i)], "p" + std::to_string(i));
    const PoleDifferential d = analyzePole(t);
    requireFinite(d.limit, "pole limit");
    requireFinite(d.normal, "pole normal");
    // K and H can exceed a double (a pole 1e-200 wide has K ~ 1e400): then curvatureDefined is false.
    if (d.curvatureDefined)
      requireFinite(d.gaussian, "pole K"), requireFinite(d.mean, "pole H");
    else if (d.gaussian != 0.0 || d.mean != 0.0)
      fail("undefined pole curvature is not K = H = 0");

    const PolarGrid& grid = level.poleGrids[k];
    int rings = kMaxRings;
    while (rings > 0 && variant.scheme == Scheme::C2PS && double(grid.n) * std::pow(2.0, rings) > kMaxRingValence)
      --rings;
    if (rings == 0) continue;
    gStage = pole + ": ringCurvatures";
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<RingCurvature> stats =
        ringCurvatures(grid, variant.scheme, variant.uniformFirstStep, rings, d.curvatureDefined ? d.gaussian : nan,
                       d.curvatureDefined ? d.mean : nan, d.normal, 3);
    if (!moderate) continue;  // rings of a huge or tiny model may have K over a double
    for (const RingCurvature& r : stats) {
      const std::string ring = "ring " + std::to_string(r.m) + " ";
      requireFinite(r.minK, ring + "K min");
      requireFinite(r.maxK, ring + "K max");
      requireFinite(r.minH, ring + "H min");
      requireFinite(r.maxH, ring + "H max");
      if (d.curvatureDefined)
        requireFinite(r.maxAbsDeltaK, ring + "max |K - K0|"), requireFinite(r.maxAbsDeltaH, ring + "max |H - H0|");
    }
  }
}

// One level L in 1..3 per input, from a hash of its bytes (so a reproducer reproduces): level 3
// costs about 16 times level 1, and running all three would cut executions per second by 3.
void runPipeline(const uint8_t* data, size_t size) {
  PolyMesh mesh;
  std::vector<std::string> warnings;
  if (!parseInput(data, size, kLimits, mesh, &warnings)) return;
  checkParsedMesh(mesh);
  // The model's size: of the vertices its faces use (an unused one far away does not make a model
  // 1e-300 wide moderate); whether a coordinate is tiny but not 0 (then two points may be 1e-300
  // apart: a feature whose K, ~1e600, no double holds, however large the model).
  double maxCoordinate = 0.0;
  bool tiny = false;
  Point lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const Index v : mesh.faceVerts) {
    const Point& p = mesh.points[size_t(v)];
    for (int k = 0; k < 3; ++k) tiny = tiny || (p[k] != 0.0 && std::abs(p[k]) < kTiny);
    maxCoordinate = std::max({maxCoordinate, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    lo = glm::min(lo, p), hi = glm::max(hi, p);
  }

  // Non-manifold input goes through its manifold split, as the refiners take it (manifold_split.h).
  gStage = "splitNonManifold + buildTopology";
  MeshTopology topology;
  ManifoldSplit split;
  const PolyMesh* refinable = &mesh;
  try {
    refinable = &refinableMesh(mesh, split, topology, kSource);
  } catch (const InputError&) {
    return;
  }

  gStage = "findPolarConfigs";
  checkPolarConfigs(*refinable, topology, findPolarConfigs(*refinable, topology));

  // Moderate inputs (coordinates <= 1e6, none tiny, the model not tinier than 1e-6) must give finite
  // curvature everywhere; the edit moves a vertex by 1% of the model's size.
  // The largest extent: a box's diagonal (glm::length) underflows to 0 for a model 1e-300 wide.
  const Point extent = hi - lo;
  const double box = std::max({extent.x, extent.y, extent.z});
  const bool moderate = maxCoordinate <= kModerate && !tiny && (box == 0.0 || box >= 1.0 / kModerate);
  const int levels = 1 + int(inputHash(data, size) % kMaxLevel);
  const double modelSize = std::max(box, 1e-3);
  for (const Variant& variant : kVariants) {
    runRefinements(mesh, variant, levels, moderate, modelSize);
    if (variant.scheme != Scheme::CatmullClark) runPoleAnalysis(mesh, variant, moderate);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return runInput([&] { runPipeline(data, size); });
}
