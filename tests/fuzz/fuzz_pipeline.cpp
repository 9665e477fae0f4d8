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
//    analyzePole says they are defined; the patches' and rings' K and H for coordinates <= 1e6;
//  * the adaptive patch set equals the uniform one (count per kind, and the sum of all B-spline
//    control points, which face numbering and quarter turns do not change) for levels <= 3;
//  * refreshPatches after updatePositions equals a fresh extractPatches;
//  * refinable polar configurations are well formed (links in range, valence >= 3).
// Each input is bounded (bytes, faces, vertices, finest-level faces) so one run stays fast.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
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

using namespace polarview;

namespace {

constexpr size_t kMaxInputBytes = 1 << 16;
constexpr Index kMaxBaseFaces = 2000;
constexpr Index kMaxBaseVertices = 4000;
constexpr size_t kMaxFinestFaces = 4096;    // Refinement's budget (finest level)
constexpr size_t kMaxAdaptiveFaces = 8192;  // AdaptiveRefinement's budget (all levels)
constexpr int kMaxLevel = 3;
constexpr int kMaxRings = 3;           // ringCurvatures
constexpr int kMaxRingValence = 4096;  // C2PS doubles the valence per ring
constexpr double kModerate = 1e6;      // coordinates up to this: K and H must be finite too
const char* const kSource = "fuzz.obj";

struct Variant {
  Scheme scheme;
  bool uniformFirstStep;
  const char* name;
};
constexpr Variant kVariants[] = {
    {Scheme::CatmullClark, false, "cc"}, {Scheme::C2PS, false, "c2ps"}, {Scheme::C2PS, true, "c2ps-u"},
    {Scheme::RTS, false, "rts"},         {Scheme::RTS, true, "rts-u"},  {Scheme::BPS, false, "bps"},
};

// What the pipeline was doing, for the report of a finding.
std::string gStage;

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "\nFUZZ FINDING at [%s]: %s\n", gStage.c_str(), what.c_str());
  std::fflush(stderr);
  std::abort();
}

bool allFinite(const Point& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }
void requireFinite(const Point& p, const std::string& what) {
  if (!allFinite(p))
    fail(what + " is not finite (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
         ")");
}
void requireFinite(double x, const std::string& what) {
  if (!std::isfinite(x)) fail(what + " is not finite (" + std::to_string(x) + ")");
}

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

void checkPolarConfigs(const PolyMesh& mesh, const std::vector<PolarConfig>& configs) {
  for (const PolarConfig& c : configs) {
    if (c.pole < 0 || c.pole >= mesh.vertexCount()) fail("polar config with pole " + std::to_string(c.pole));
    if (!c.refinable) continue;
    if (c.valence < 3) fail("refinable pole " + std::to_string(c.pole) + " of valence " + std::to_string(c.valence));
    if (c.linkCount < 2)
      fail("refinable pole " + std::to_string(c.pole) + " with " + std::to_string(c.linkCount) + " links");
    if (c.links.size() != size_t(c.linkCount) * size_t(c.valence))
      fail("pole " + std::to_string(c.pole) + ": " + std::to_string(c.links.size()) + " link ids for " +
           std::to_string(c.linkCount) + " links of valence " + std::to_string(c.valence));
    for (Index v : c.links)
      if (v < 0 || v >= mesh.vertexCount())
        fail("pole " + std::to_string(c.pole) + ": link vertex " + std::to_string(v));
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
    uniformOptions.finestVertexRings = (mesh.faceVerts.size() + size_t(levels)) % 2 == 0;
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
int levelFor(const std::string& text) {
  uint32_t hash = 2166136261u;  // FNV-1a
  for (unsigned char c : text) hash = (hash ^ c) * 16777619u;
  return 1 + int(hash % kMaxLevel);
}

void runPipeline(const std::string& text) {
  gStage = "parseObjText";
  std::vector<std::string> warnings;
  PolyMesh mesh;
  try {
    mesh = parseObjText(text, kSource, &warnings);
  } catch (const InputError&) {
    return;
  }
  if (mesh.faceCount() > kMaxBaseFaces || mesh.vertexCount() > kMaxBaseVertices) return;
  double maxCoordinate = 0.0;
  Point lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const Point& p : mesh.points) {
    requireFinite(p, "parsed point");
    maxCoordinate = std::max({maxCoordinate, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    if (maxCoordinate > kMaxObjCoordinate)
      fail("parsed coordinate over kMaxObjCoordinate: " + std::to_string(maxCoordinate));
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
  if (mesh.faceCount() == 0) return;

  gStage = "findPolarConfigs";
  checkPolarConfigs(*refinable, findPolarConfigs(*refinable, topology));

  // Moderate inputs (coordinates <= 1e6, the model not tinier than 1e-6) must give finite curvature
  // everywhere; the edit moves a vertex by 1% of the model's size.
  const double box = mesh.points.empty() ? 0.0 : glm::length(hi - lo);
  const bool moderate = maxCoordinate <= kModerate && (box == 0.0 || box >= 1.0 / kModerate);
  const int levels = levelFor(text);
  const double size = std::max(box, 1e-3);
  for (const Variant& variant : kVariants) {
    runRefinements(mesh, variant, levels, moderate, size);
    if (variant.scheme != Scheme::CatmullClark) runPoleAnalysis(mesh, variant, moderate);
  }
}

// [SECTION] Structure-aware mutation
// Half of the mutations edit the OBJ as a mesh (libFuzzer's byte-level ones rarely keep it valid):
// move a coordinate (scaled, zeroed, copied, made nearly equal), retarget a face index, flip a
// face, delete or duplicate a line, split a polygon into a triangle fan, poke a face (a new
// triangle fan around its centre: a new polar candidate of the face's valence), merge two
// vertices, or start a face at another corner. Indices written are 1-based and positive.

struct ObjLines {
  std::vector<std::string> lines;
  std::vector<size_t> vertexLines, faceLines;
};

ObjLines splitObj(const uint8_t* data, size_t size) {
  ObjLines obj;
  std::string line;
  for (size_t i = 0; i <= size; ++i) {
    if (i == size || data[i] == '\n') {
      if (line.rfind("v ", 0) == 0) obj.vertexLines.push_back(obj.lines.size());
      if (line.rfind("f ", 0) == 0) obj.faceLines.push_back(obj.lines.size());
      obj.lines.push_back(line);
      line.clear();
    } else {
      line += char(data[i]);
    }
  }
  return obj;
}

std::vector<std::string> tokens(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string t; in >> t;) out.push_back(t);
  return out;
}

// The vertex part of a face corner ("12/3/4" -> 12), made positive against `vertexCount`.
long cornerIndex(const std::string& corner, long vertexCount) {
  const long i = std::strtol(corner.c_str(), nullptr, 10);
  return i < 0 ? vertexCount + 1 + i : i;
}

std::string joinFace(const std::vector<long>& loop) {
  std::string line = "f";
  for (long i : loop) line += " " + std::to_string(i);
  return line;
}

std::vector<long> faceLoop(const std::string& line, long vertexCount) {
  std::vector<std::string> t = tokens(line);
  std::vector<long> loop;
  for (size_t k = 1; k < t.size(); ++k) loop.push_back(cornerIndex(t[k], vertexCount));
  return loop;
}

bool mutateObj(ObjLines& obj, std::minstd_rand& rng) {
  auto pick = [&](size_t n) { return size_t(rng() % n); };
  const long vertexCount = long(obj.vertexLines.size());
  std::vector<std::string>& lines = obj.lines;
  switch (rng() % 9) {
    case 0: {  // move one coordinate
      if (obj.vertexLines.empty()) return false;
      const size_t v = obj.vertexLines[pick(obj.vertexLines.size())];
      std::vector<std::string> t = tokens(lines[v]);
      if (t.size() < 4) return false;
      const size_t c = 1 + pick(3);
      const double x = std::strtod(t[c].c_str(), nullptr);
      const double other =
          std::strtod(tokens(lines[obj.vertexLines[pick(obj.vertexLines.size())]]).back().c_str(), nullptr);
      const double choices[] = {0.0,     -x,       2.0 * x, x * (1.0 + 1e-12),         x + 1e-9,
                                x * 1e6, x * 1e-6, other,   double(int(rng() % 7) - 3)};
      char buffer[40];
      std::snprintf(buffer, sizeof buffer, "%.17g", choices[pick(9)]);
      t[c] = buffer;
      std::string line = t[0];
      for (size_t k = 1; k < t.size(); ++k) line += " " + t[k];
      lines[v] = line;
      return true;
    }
    case 1: {  // retarget one index of a face
      if (obj.faceLines.empty() || vertexCount == 0) return false;
      const size_t f = obj.faceLines[pick(obj.faceLines.size())];
      std::vector<long> loop = faceLoop(lines[f], vertexCount);
      if (loop.empty()) return false;
      loop[pick(loop.size())] = 1 + long(pick(size_t(vertexCount)));
      lines[f] = joinFace(loop);
      return true;
    }
    case 2: {  // flip a face
      if (obj.faceLines.empty()) return false;
      const size_t f = obj.faceLines[pick(obj.faceLines.size())];
      std::vector<long> loop = faceLoop(lines[f], vertexCount);
      std::reverse(loop.begin(), loop.end());
      lines[f] = joinFace(loop);
      return true;
    }
    case 3: {  // delete a face or a vertex line
      const std::vector<size_t>& from = rng() % 4 ? obj.faceLines : obj.vertexLines;
      if (from.empty()) return false;
      lines.erase(lines.begin() + long(from[pick(from.size())]));
      return true;
    }
    case 4: {  // duplicate a face
      if (obj.faceLines.empty()) return false;
      const std::string line = lines[obj.faceLines[pick(obj.faceLines.size())]];
      lines.push_back(line);
      return true;
    }
    case 5: {  // split a polygon into a fan of triangles from one corner
      if (obj.faceLines.empty()) return false;
      const size_t f = obj.faceLines[pick(obj.faceLines.size())];
      std::vector<long> loop = faceLoop(lines[f], vertexCount);
      if (loop.size() < 4) return false;
      std::rotate(loop.begin(), loop.begin() + long(pick(loop.size())), loop.end());
      lines[f] = joinFace({loop[0], loop[1], loop[2]});
      for (size_t k = 2; k + 1 < loop.size(); ++k) lines.push_back(joinFace({loop[0], loop[k], loop[k + 1]}));
      return true;
    }
    case 6: {  // poke a face: a vertex at its centre (lifted a little) and a triangle fan around it
      if (obj.faceLines.empty()) return false;
      const size_t f = obj.faceLines[pick(obj.faceLines.size())];
      std::vector<long> loop = faceLoop(lines[f], vertexCount);
      if (loop.size() < 3) return false;
      double centre[3] = {0, 0, 0};
      for (long i : loop) {
        if (i < 1 || i > vertexCount) return false;
        std::vector<std::string> t = tokens(lines[obj.vertexLines[size_t(i - 1)]]);
        for (size_t c = 0; c < 3 && c + 1 < t.size(); ++c)
          centre[c] += std::strtod(t[c + 1].c_str(), nullptr) / double(loop.size());
      }
      char buffer[120];
      std::snprintf(buffer, sizeof buffer, "v %.17g %.17g %.17g", centre[0], centre[1],
                    centre[2] + 0.01 * double(rng() % 3));
      lines.insert(lines.begin() + long(obj.vertexLines.back()) + 1, buffer);  // keeps earlier faces' indices
      const long pole = vertexCount + 1;
      lines[f + (f > obj.vertexLines.back() ? 1 : 0)] = joinFace({pole, loop[0], loop[1]});
      for (size_t k = 1; k < loop.size(); ++k) lines.push_back(joinFace({pole, loop[k], loop[(k + 1) % loop.size()]}));
      return true;
    }
    case 7: {  // merge vertex a into b in every face
      if (vertexCount < 2 || obj.faceLines.empty()) return false;
      const long a = 1 + long(pick(size_t(vertexCount))), b = 1 + long(pick(size_t(vertexCount)));
      for (size_t f : obj.faceLines) {
        std::vector<long> loop = faceLoop(lines[f], vertexCount);
        std::vector<long> merged;
        for (long i : loop)
          if ((i == a ? b : i) != (merged.empty() ? 0 : merged.back())) merged.push_back(i == a ? b : i);
        if (merged.size() > 1 && merged.front() == merged.back()) merged.pop_back();
        lines[f] = merged.size() >= 3 ? joinFace(merged) : "";
      }
      return true;
    }
    default: {  // start a face at its next corner (the same face: nothing may change but numbering)
      if (obj.faceLines.empty()) return false;
      const size_t f = obj.faceLines[pick(obj.faceLines.size())];
      std::vector<long> loop = faceLoop(lines[f], vertexCount);
      if (loop.empty()) return false;
      std::rotate(loop.begin(), loop.begin() + 1, loop.end());
      lines[f] = joinFace(loop);
      return true;
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > kMaxInputBytes) return 0;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    runPipeline(text);
  } catch (const InputError&) {
    // Bad input, found past the reader and topology (e.g. by a refiner): expected.
  } catch (const std::exception& e) {
    fail(std::string("unexpected exception: ") + e.what());
  } catch (...) {
    fail("unexpected non-std exception");
  }
  return 0;
}

extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t maxSize);

// Half libFuzzer's own byte-level mutations, half mesh edits (mutateObj above).
extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size, size_t maxSize, unsigned int seed) {
  std::minstd_rand rng(seed);
  if (rng() % 2 == 0) return LLVMFuzzerMutate(data, size, maxSize);
  ObjLines obj = splitObj(data, size);
  if (!mutateObj(obj, rng)) return LLVMFuzzerMutate(data, size, maxSize);
  std::string text;
  for (size_t k = 0; k < obj.lines.size(); ++k) text += obj.lines[k] + (k + 1 < obj.lines.size() ? "\n" : "");
  if (text.size() > maxSize) return LLVMFuzzerMutate(data, size, maxSize);
  std::copy(text.begin(), text.end(), data);
  return text.size();
}
