// Feature-adaptive refinement against the uniform one: the same patch set, patch for patch.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/mesh/obj_io.h"
#include "core/mesh/shapes.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/adaptive_refiner.h"

using namespace polarview;

namespace {

double modelSize(const PolyMesh& mesh) {
  Point lo(1e300), hi(-1e300);
  for (const Point& p : mesh.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return glm::length(hi - lo);
}

// Patches keyed by what identifies them independently of face numbering: kind, level, ring, pole
// and the rounded centroid of their control points.
using PatchKey = std::tuple<int, int, int, int, long long, long long, long long>;
PatchKey keyOf(const Patch& patch, double scale) {
  Point centroid(0.0);
  for (const Point& p : patch.cp) centroid += p / 16.0;
  if (patch.kind == PatchKind::PoleCap) centroid = patch.cp[7] + patch.cp[10];  // boundary point + sector
  auto q = [&](double x) { return (long long)std::llround(x / scale * 1e7); };
  return {int(patch.kind), int(patch.level), patch.ring, patch.pole, q(centroid.x), q(centroid.y), q(centroid.z)};
}

// The same patch with its face's loop started `turns` corners later (a face copied out of a globe's
// far half is numbered from the other pole): (i, j) <- (3 - j, i) per turn, edges shift by one.
Patch quarterTurns(const Patch& patch, int turns) {
  Patch out = patch;
  for (int t = 0; t < turns; ++t) {
    const Patch in = out;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) out.cp[4 * j + i] = in.cp[4 * i + (3 - j)];
    for (int s = 0; s < 4; ++s) out.edgeLevelDelta[s] = in.edgeLevelDelta[(s + 1) % 4];
  }
  return out;
}

// Compares the two patch sets: same count per kind, and every uniform patch has an adaptive twin
// with the same control points (to round-off) and level jumps. Returns the largest cp difference.
double comparePatchSets(const PatchSet& uniform, const PatchSet& adaptive, double size, const std::string& what) {
  INFO(what);
  for (size_t k = 0; k < uniform.kindCounts.size(); ++k) CHECK(uniform.kindCounts[k] == adaptive.kindCounts[k]);
  REQUIRE(uniform.patches.size() == adaptive.patches.size());
  std::multimap<PatchKey, const Patch*> byKey;
  for (const Patch& patch : adaptive.patches) byKey.emplace(keyOf(patch, size), &patch);
  double worst = 0.0;
  size_t missing = 0, deltaMismatch = 0;
  for (const Patch& patch : uniform.patches) {
    auto range = byKey.equal_range(keyOf(patch, size));
    const Patch* best = nullptr;
    double bestDiff = 1e300;
    int bestTurn = 0;
    for (auto it = range.first; it != range.second; ++it)
      for (int turn = 0; turn < 4; ++turn) {
        const Patch rotated = quarterTurns(*it->second, turn);
        double diff = 0.0;
        for (int k = 0; k < 16; ++k) diff = std::max(diff, glm::length(rotated.cp[k] - patch.cp[k]));
        if (diff < bestDiff) bestDiff = diff, best = it->second, bestTurn = turn;
        if (patch.kind == PatchKind::PoleCap) break;  // caps have no corners to turn
      }
    if (!best) {
      ++missing;
      continue;
    }
    worst = std::max(worst, bestDiff);
    if (quarterTurns(*best, bestTurn).edgeLevelDelta != patch.edgeLevelDelta) ++deltaMismatch;
  }
  CHECK(missing == 0);
  CHECK(deltaMismatch == 0);
  CHECK(worst <= 1e-11 * size);
  return worst;
}

void checkAgainstUniform(const PolyMesh& mesh, const std::string& name, int maxLevel) {
  const double size = modelSize(mesh);
  for (Scheme scheme : {Scheme::CatmullClark, Scheme::C2PS, Scheme::RTS, Scheme::BPS})
    for (bool uniformFirst : {false, true}) {
      if (uniformFirst && scheme != Scheme::C2PS) continue;
      for (int level = 0; level <= maxLevel; ++level) {
        const RefineOptions options{scheme, level, uniformFirst};
        const std::string what = name + " " + schemeName(scheme) + (uniformFirst ? "-u" : "") + " level " + std::to_string(level);
        const PatchSet uniform = extractPatches(Refinement(mesh, options));
        PatchSet adaptive;
        REQUIRE_NOTHROW(adaptive = extractPatches(AdaptiveRefinement(mesh, options)));
        comparePatchSets(uniform, adaptive, size, what);
      }
    }
}

}  // namespace

TEST_CASE("adaptive: the same patches as uniform refinement on generated shapes, every scheme, levels 0-5") {
  checkAgainstUniform(shapes::mushroom(12), "mushroom", 5);
  checkAgainstUniform(shapes::globe(8, 5), "globe", 5);
  checkAgainstUniform(shapes::polarCap(6, 3), "cap", 5);
  checkAgainstUniform(shapes::cube(), "cube", 5);
  checkAgainstUniform(shapes::grid(3, 2, [](double x, double y) { return x * y; }), "grid", 4);
  checkAgainstUniform(shapes::torus(6, 4), "torus", 3);
}

TEST_CASE("adaptive: the same patches as uniform refinement on the shipped models, every scheme, levels 0-5") {
  for (const char* name : {"default.obj", "globe.obj"}) {
    const std::string path = std::string(POLARVIEW_ASSET_DIR) + "/" + name;
    checkAgainstUniform(loadObj(path), name, 5);
  }
}
