// Feature-adaptive refinement against the uniform one: the same patch set, patch for patch.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <tuple>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/mesh/obj_io.h"
#include "core/mesh/shapes.h"
#include "core/mesh/topology.h"
#include "core/spline/patch_extraction.h"
#include "core/spline/pole_taylor.h"
#include "core/spline/ring_curvature.h"
#include "core/subdiv/adaptive_refiner.h"
#include "core/subdiv/parallel_for.h"
#include "support/osd_shapes.h"

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
  if (patch.kind == PatchKind::PoleCap)  // boundary point + sector
    centroid = patch.cp[7] + Point(double(patch.sector) / patch.sectorCount, 1.0 / patch.sectorCount, 0.0);
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
// `tailMeets` >= 0: the level whose polar ring patches meet the RTS/BPS tail, where the adaptive
// side has no level jump (the tail keeps the columns) and the uniform side has one.
double comparePatchSets(const PatchSet& uniform, const PatchSet& relativeAdaptive, double size, const std::string& what,
                        int tailMeets = -1) {
  INFO(what);
  PatchSet adaptive = relativeAdaptive;  // adaptive patches are relative to their frames' origins
  for (Patch& patch : adaptive.patches) patch = withAbsolutePositions(patch);
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
    const bool exempt = patch.kind == PatchKind::PolarRing && patch.level == tailMeets;
    if (!exempt && quarterTurns(*best, bestTurn).edgeLevelDelta != patch.edgeLevelDelta) ++deltaMismatch;
  }
  CHECK(missing == 0);
  CHECK(deltaMismatch == 0);
  CHECK(worst <= 1e-11 * size);
  return worst;
}

// RTS/BPS outside caps and globes beyond level 5 (the tail, adaptive_refiner.cpp): a pole's ring
// patch of level m spans 2^(m-5) uniform ring patches of the same surface. Checks that every
// uniform ring and cap patch deeper than level 5 samples (corners, edge midpoints, centre) onto
// points of the adaptive tail patches of its level and pole, that the counts are in that ratio, and
// that all other patches match control point for control point.
void compareTail(const PatchSet& uniform, const PatchSet& adaptive, double size, const std::string& what) {
  INFO(what);
  auto inTail = [](const Patch& p) { return p.level > 5 && (p.kind == PatchKind::PolarRing || p.kind == PatchKind::PoleCap); };
  PatchSet uniformRest, adaptiveRest;
  std::map<std::tuple<int, int, int>, size_t> uniformTail, adaptiveTail;  // (kind, level, pole) -> count
  for (const Patch& p : uniform.patches) {
    if (inTail(p)) ++uniformTail[{int(p.kind), p.level, p.pole}];
    else uniformRest.patches.push_back(p), ++uniformRest.kindCounts[size_t(p.kind)];
  }
  for (const Patch& p : adaptive.patches) {
    if (inTail(p)) ++adaptiveTail[{int(p.kind), p.level, p.pole}];
    else adaptiveRest.patches.push_back(p), ++adaptiveRest.kindCounts[size_t(p.kind)];
  }
  comparePatchSets(uniformRest, adaptiveRest, size, what + " (outside the tail)", 5);
  REQUIRE(uniformTail.size() == adaptiveTail.size());
  for (const auto& [key, count] : uniformTail) {
    const size_t tail = adaptiveTail[key];
    REQUIRE(tail > 0);
    CHECK(count % tail == 0);
    CHECK(count / tail == size_t(1) << (std::get<1>(key) - 5));
  }
  // Points of the tail patches on a grid fine enough to hold every uniform sample, quantised.
  const double cell = 1e-9 * size;
  auto cellOf = [&](const Point& x) {
    return std::make_tuple((long long)std::floor(x.x / cell), (long long)std::floor(x.y / cell), (long long)std::floor(x.z / cell));
  };
  std::map<std::tuple<long long, long long, long long>, Point> samples;
  for (const Patch& p : adaptive.patches) {
    if (!inTail(p)) continue;
    const int fine = 2 << (p.level - 5);  // half-steps of the uniform patches it spans
    for (int a = 0; a <= 2; ++a)
      for (int b = 0; b <= fine; ++b)
        for (bool swapped : {false, true}) {
          if (swapped && p.kind == PatchKind::PoleCap) continue;  // caps: u is always radial
          const double u = a / 2.0, v = double(b) / fine;
          const Point x = swapped ? evaluatePatch(p, v, u).position : evaluatePatch(p, u, v).position;
          samples[cellOf(x)] = x;
        }
  }
  size_t missing = 0;
  for (const Patch& p : uniform.patches) {
    if (!inTail(p)) continue;
    for (int a = 0; a <= 2; ++a)
      for (int b = 0; b <= 2; ++b) {
        const Point x = evaluatePatch(p, a / 2.0, b / 2.0).position;
        const auto [i, j, k] = cellOf(x);
        bool found = false;
        for (long long di = -1; di <= 1 && !found; ++di)
          for (long long dj = -1; dj <= 1 && !found; ++dj)
            for (long long dk = -1; dk <= 1 && !found; ++dk) {
              auto it = samples.find({i + di, j + dj, k + dk});
              found = it != samples.end() && glm::length(it->second - x) <= 1e-9 * size;
            }
        missing += !found;
      }
  }
  CHECK(missing == 0);
}

// Two tables of the same mesh, entry for entry.
void checkEqualTables(const MeshTopology& built, const MeshTopology& t) {
  CHECK(built.edgeCount == t.edgeCount);
  CHECK(built.cornerEdge == t.cornerEdge);
  CHECK(built.cornerFace == t.cornerFace);
  CHECK(built.edgeVerts == t.edgeVerts);
  CHECK(built.edgeFaces == t.edgeFaces);
  CHECK(built.vertexFaceStart == t.vertexFaceStart);
  CHECK(built.vertexFaces == t.vertexFaces);
  CHECK(built.vertexCorners == t.vertexCorners);
  CHECK(built.vertexEdgeStart == t.vertexEdgeStart);
  CHECK(built.vertexEdges == t.vertexEdges);
  CHECK(built.vertexOnBoundary == t.vertexOnBoundary);
  CHECK(built.vertexUsed == t.vertexUsed);
}

// Every level's tables (the sparse steps derive them from the parent's twins) equal those built
// from its mesh, entry for entry.
void checkLevelTables(const AdaptiveRefinement& refinement, const std::string& what) {
  INFO(what);
  for (int m = 1; m < refinement.levelCount(); ++m) {
    CAPTURE(m);
    checkEqualTables(buildTopology(refinement.level(m).mesh), refinement.level(m).topology);
  }
}

void checkAgainstUniform(const PolyMesh& mesh, const std::string& name, int maxLevel,
                         std::initializer_list<Scheme> schemes = {Scheme::CatmullClark, Scheme::C2PS, Scheme::RTS, Scheme::BPS}) {
  const double size = modelSize(mesh);
  for (Scheme scheme : schemes)
    for (bool uniformFirst : {false, true}) {
      if (uniformFirst && scheme != Scheme::C2PS) continue;
      for (int level = 0; level <= maxLevel; ++level) {
        const RefineOptions options{scheme, level, uniformFirst};
        const std::string what = name + " " + schemeName(scheme) + (uniformFirst ? "-u" : "") + " level " + std::to_string(level);
        const PatchSet uniform = extractPatches(Refinement(mesh, options));
        PatchSet adaptive;
        std::optional<AdaptiveRefinement> refinement;
        REQUIRE_NOTHROW(refinement.emplace(mesh, options));
        REQUIRE_NOTHROW(adaptive = extractPatches(*refinement));
        comparePatchSets(uniform, adaptive, size, what);
        if (level == maxLevel) checkLevelTables(*refinement, what);
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

TEST_CASE("adaptive: holes and interpolateboundary 0: the same patches as uniform refinement, every scheme") {
  PolyMesh mushroom = shapes::mushroom(12);
  mushroom.tags.holes = {Index(mushroom.faceCount() - 1), Index(mushroom.faceCount() - 7), 3};  // stem faces, and a fan face
  checkAgainstUniform(mushroom, "mushroom with holes", 4);
  PolyMesh cube = shapes::cube();
  cube.tags.holes = {2};
  checkAgainstUniform(cube, "cube with a hole", 4);
  PolyMesh grid = shapes::grid(5, 4, [](double x, double y) { return x * y; });
  grid.tags.boundary = BoundaryInterpolation::None;
  checkAgainstUniform(grid, "grid, interpolateboundary 0", 4);
}

TEST_CASE("adaptive: RTS and BPS beyond level 5 outside caps and globes are the uniform surface with fewer columns") {
  for (const char* name : {"default.obj"})
    for (Scheme scheme : {Scheme::RTS, Scheme::BPS})
      for (int level : {6, 7}) {
        const PolyMesh mesh = loadObj(std::string(POLARVIEW_ASSET_DIR) + "/" + name);
        const RefineOptions options{scheme, level, false};
        compareTail(extractPatches(Refinement(mesh, options)), extractPatches(AdaptiveRefinement(mesh, options)),
                    modelSize(mesh), std::string(name) + " " + schemeName(scheme) + " level " + std::to_string(level));
      }
}

TEST_CASE("adaptive: the same patches as uniform refinement on the shipped models, every scheme, levels 0-5") {
  for (const char* name : {"default.obj", "globe.obj"}) {
    const std::string path = std::string(POLARVIEW_ASSET_DIR) + "/" + name;
    checkAgainstUniform(loadObj(path), name, 5);
  }
}

TEST_CASE("adaptive: live edits: new points on the kept hierarchy, patches refreshed, equal a fresh refinement") {
  const PolyMesh mushroom = loadObj(std::string(POLARVIEW_ASSET_DIR) + "/default.obj");
  for (const PolyMesh& mesh : {mushroom, shapes::globe(8, 5), shapes::cube()})
    for (Scheme scheme : {Scheme::CatmullClark, Scheme::C2PS, Scheme::RTS, Scheme::BPS})
      for (int level : {3, 6}) {
        const RefineOptions options{scheme, level, false};
        AdaptiveRefinement kept(mesh, options);
        PatchSources sources;
        PatchSet patches = extractPatches(kept, &sources);
        PolyMesh edited = mesh;
        for (Index v : {Index(0), Index(5), edited.vertexCount() - 1}) edited.points[size_t(v)] += Point(0.03, -0.02, 0.05);
        kept.updatePositions(edited.points);
        refreshPatches(kept, sources, patches);
        const PatchSet fresh = extractPatches(AdaptiveRefinement(edited, options));
        INFO(schemeName(scheme) << " level " << level << ", " << mesh.vertexCount() << " vertices");
        REQUIRE(fresh.patches.size() == patches.patches.size());
        double worst = 0.0;
        for (size_t k = 0; k < fresh.patches.size(); ++k)
          for (int i = 0; i < 16; ++i)
            worst = std::max(worst, glm::length(withAbsolutePositions(fresh.patches[k]).cp[i] -
                                                withAbsolutePositions(patches.patches[k]).cp[i]));
        CHECK(worst <= 1e-12 * modelSize(mesh));
      }
}

namespace {

// Two patch sets of the same refinement path: identical, patch for patch (bits, not round-off:
// the same arithmetic made both), with the same sources.
void requireIdentical(const PatchSet& expected, const PatchSources& expectedSources, const PatchSet& got,
                      const PatchSources& gotSources, const std::string& what) {
  INFO(what);
  REQUIRE(expected.patches.size() == got.patches.size());
  CHECK(expected.kindCounts == got.kindCounts);
  size_t differ = 0;
  for (size_t k = 0; k < expected.patches.size(); ++k) {
    const Patch& a = expected.patches[k];
    const Patch& b = got.patches[k];
    bool same = a.kind == b.kind && a.level == b.level && a.ring == b.ring && a.pole == b.pole && a.face == b.face &&
                a.edgeLevelDelta == b.edgeLevelDelta;
    for (int i = 0; i < 16; ++i) same = same && a.cp[i] == b.cp[i];
    same = same && a.origin == b.origin;
    same = same && expectedSources.stencil[k] == gotSources.stencil[k] &&
           expectedSources.sidesMissing[k] == gotSources.sidesMissing[k];
    differ += !same;
  }
  CHECK(differ == 0);
}

}  // namespace

TEST_CASE("adaptive: a refinement extended level by level, and a level cache stepping up and down, equal fresh ones") {
  const PolyMesh mushroom = loadObj(std::string(POLARVIEW_ASSET_DIR) + "/default.obj");
  const std::vector<std::pair<std::string, PolyMesh>> meshes = {
      {"default.obj", mushroom}, {"globe", shapes::globe(8, 5)}, {"cube", shapes::cube()}, {"cap", shapes::polarCap(6, 3)}};
  for (const auto& [name, mesh] : meshes)
    for (Scheme scheme : {Scheme::CatmullClark, Scheme::C2PS, Scheme::RTS, Scheme::BPS}) {
      const int deepest = 7;  // past RTS/BPS's tail start (level 5) on the default model
      std::vector<PatchSet> fresh(deepest + 1);
      std::vector<PatchSources> freshSources(deepest + 1);
      for (int level = 0; level <= deepest; ++level)
        fresh[size_t(level)] = extractPatches(AdaptiveRefinement(mesh, RefineOptions{scheme, level, false}),
                                              &freshSources[size_t(level)]);
      // Up one level at a time from 1, the cache visiting each level as it goes.
      AdaptiveRefinement stepped(mesh, RefineOptions{scheme, 1, false});
      LevelPatchCache cache;
      PatchSources sources;
      for (int level = 1; level <= deepest; ++level) {
        if (level > 1) stepped.extend(1);
        CHECK(stepped.levelCount() == level + 1);
        const PatchSet set = cache.patchSet(stepped, level, &sources);
        requireIdentical(fresh[size_t(level)], freshSources[size_t(level)], set, sources,
                         name + " " + schemeName(scheme) + " up to level " + std::to_string(level));
      }
      CHECK(stepped.totalFaces() == AdaptiveRefinement(mesh, RefineOptions{scheme, deepest, false}).totalFaces());
      // Down and up again on the deepest refinement, in an order that skips levels.
      for (int level : {3, 0, 6, 2, 7, 5}) {
        const PatchSet set = cache.patchSet(stepped, level, &sources);
        requireIdentical(fresh[size_t(level)], freshSources[size_t(level)], set, sources,
                         name + " " + schemeName(scheme) + " back to level " + std::to_string(level));
      }
      // The two sets share their regular patches of the shallower level, first.
      const PatchSet four = cache.patchSet(stepped, 4), six = cache.patchSet(stepped, 6);
      const size_t shared = cache.sharedPrefix(4, 6);
      REQUIRE(shared <= std::min(four.patches.size(), six.patches.size()));
      for (size_t k = 0; k < shared; ++k) REQUIRE((four.patches[k].cp == six.patches[k].cp && four.patches[k].origin == six.patches[k].origin));
      // Truncated to 3 and extended to 6 in one step: the fresh level 6 again.
      stepped.truncate(3);
      CHECK(stepped.levelCount() == 4);
      stepped.extend(3);
      LevelPatchCache again;
      requireIdentical(fresh[6], freshSources[6], again.patchSet(stepped, 6, &sources), sources,
                       name + " " + schemeName(scheme) + " truncated to 3, extended to 6");
    }
}

TEST_CASE("adaptive: an extension over the face budget is refused and leaves the refinement as it was") {
  const PolyMesh mesh = loadObj(std::string(POLARVIEW_ASSET_DIR) + "/default.obj");
  AdaptiveRefinement refinement(mesh, RefineOptions{Scheme::C2PS, 3, false});
  const size_t faces = refinement.totalFaces();
  CHECK_THROWS_WITH(refinement.extend(6, faces + 1000), doctest::Contains("is the deepest that fits"));
  CHECK(refinement.levelCount() == 4);
  CHECK(refinement.totalFaces() == faces);
  const PatchSet before = extractPatches(AdaptiveRefinement(mesh, RefineOptions{Scheme::C2PS, 3, false}));
  CHECK(extractPatches(refinement).patches.size() == before.patches.size());
}

namespace {

// A cube with sharp features (OpenSubdiv `t` tags): the four edges around its top face infinitely
// sharp, one vertical edge semi-sharp (1.5, gone after two levels), one bottom corner sharp.
PolyMesh creasedCube() {
  PolyMesh mesh = shapes::cube();
  const MeshTopology topo = buildTopology(mesh);
  // The top face: the face whose vertices all have the largest z.
  Index top = 0;
  double best = -1e300;
  for (Index f = 0; f < mesh.faceCount(); ++f) {
    double z = 0.0;
    for (int c = 0; c < mesh.faceSize(f); ++c) z += mesh.points[size_t(mesh.face(f)[c])].z;
    if (z > best) best = z, top = f;
  }
  auto crease = [](Index a, Index b, double s) { return CreaseEdge{std::min(a, b), std::max(a, b), s}; };
  for (int c = 0; c < 4; ++c) mesh.tags.creases.push_back(crease(mesh.face(top)[c], mesh.face(top)[(c + 1) % 4], 10.0));
  // A vertical edge from a top corner.
  const Index corner = mesh.face(top)[0];
  for (Index k = topo.vertexEdgeStart[corner]; k < topo.vertexEdgeStart[corner + 1]; ++k) {
    const Index other = topo.otherEnd(topo.vertexEdges[k], corner);
    if (std::abs(mesh.points[size_t(other)].z - mesh.points[size_t(corner)].z) > 1e-9) {
      mesh.tags.creases.push_back(crease(corner, other, 1.5));
      break;
    }
  }
  std::sort(mesh.tags.creases.begin(), mesh.tags.creases.end(),
            [](const CreaseEdge& a, const CreaseEdge& b) { return std::tie(a.v0, a.v1) < std::tie(b.v0, b.v1); });
  Index lowest = 0;
  for (Index v = 0; v < mesh.vertexCount(); ++v)
    if (mesh.points[size_t(v)].z < mesh.points[size_t(lowest)].z) lowest = v;
  mesh.tags.corners.push_back(CornerVertex{lowest, 10.0});
  return mesh;
}

}  // namespace

TEST_CASE("adaptive: creases and corners (Catmull-Clark): the same patches as the uniform refinement, and not the smooth ones") {
  const PolyMesh creased = creasedCube();
  REQUIRE(creased.tags.hasSharpFeatures());
  PolyMesh smooth = creased;
  smooth.tags = SubdivTags{};
  for (int level = 0; level <= 4; ++level) {
    const RefineOptions options{Scheme::CatmullClark, level, false};
    const std::string what = "creased cube level " + std::to_string(level);
    const PatchSet uniform = extractPatches(Refinement(creased, options));
    PatchSet adaptive;
    REQUIRE_NOTHROW(adaptive = extractPatches(AdaptiveRefinement(creased, options)));
    comparePatchSets(uniform, adaptive, modelSize(creased), what);
    if (level >= 2) {
      // Faces at sharp features are not the smooth cube's: along the infinitely sharp edges they are
      // boundary patches cut by the crease (the smooth closed cube has none), at the semi-sharp edge
      // and the bends of the creases they are refined to the last level and closed by end caps.
      const PatchSet plain = extractPatches(AdaptiveRefinement(smooth, options));
      CHECK(plain.count(PatchKind::Boundary) == 0);
      CHECK(adaptive.count(PatchKind::Boundary) > 0);
    }
  }
}

namespace {

struct KRange {
  double lo = INFINITY, hi = -INFINITY;
  size_t patches = 0;
};

// K over ring m of pole 0: 5 x 5 samples of each of its PolarRing patches.
KRange ringK(const PatchSet& set, int m) {
  KRange range;
  for (const Patch& patch : set.patches) {
    if (patch.kind != PatchKind::PolarRing || patch.pole != 0 || patch.ring != m) continue;
    ++range.patches;
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; j <= 4; ++j) {
        const double K = evaluatePatch(patch, i / 4.0, j / 4.0).gaussian;
        range.lo = std::min(range.lo, K), range.hi = std::max(range.hi, K);
      }
  }
  return range;
}

}  // namespace

TEST_CASE("adaptive: deep rings keep their curvature (each part refined in a frame of its own)") {
  // Points ~1 apart from the origin and 1e-8 apart from each other (RTS's ring 20, C2PS's ring 12)
  // lose the second differences K is made of to the rounding of absolute coordinates; relative to
  // their frames they keep them. Reference: the same rings refined from the pole's own links,
  // relative to the pole (ring_curvature.h).
  const PolyMesh mesh = loadObj(std::string(POLARVIEW_ASSET_DIR) + "/default.obj");
  struct Case {
    Scheme scheme;
    int levels;
    std::vector<int> rings;
  };
  for (const Case& c : {Case{Scheme::RTS, 20, {8, 14, 17, 20}}, Case{Scheme::C2PS, 11, {6, 9, 11}}}) {
    const AdaptiveRefinement refinement(mesh, RefineOptions{c.scheme, c.levels, false});
    const RefinedLevel& base = refinement.level(0);
    REQUIRE_FALSE(base.poles.empty());
    const PoleDifferential pole = analyzePole(base.poleTaylor[0]);
    const std::vector<RingCurvature> exact =
        ringCurvatures(base.poleGrids[0], c.scheme, false, c.levels, NAN, NAN, pole.normal);
    const PatchSet set = extractPatches(refinement);
    for (const int m : c.rings) {
      const KRange got = ringK(set, m);
      const RingCurvature& want = exact[size_t(m - 1)];
      REQUIRE(want.m == m);
      REQUIRE(got.patches > 0);
      MESSAGE(std::string(schemeName(c.scheme)) << " ring " << m << ": K in [" << got.lo << ", " << got.hi << "] over " << got.patches
                                   << " patches; exact [" << want.minK << ", " << want.maxK << "]");
      // Same surface, other samples: the ranges agree to a tenth of the exact spread plus 1e-4 of K.
      const double tolerance = 0.1 * (want.maxK - want.minK) + 1e-4 * std::abs(want.maxK);
      CHECK(std::abs(got.lo - want.minK) <= tolerance);
      CHECK(std::abs(got.hi - want.maxK) <= tolerance);
    }
  }
}

TEST_CASE("adaptive: creases away from the poles in C2PS, RTS and BPS meshes: Catmull-Clark's rules there, as uniform") {
  // The mushroom's stem, creased infinitely sharp along its lowest edges; its cap's pole is untouched.
  PolyMesh mushroom = shapes::mushroom(12);
  double low = INFINITY, high = -INFINITY;
  for (const Point& p : mushroom.points) low = std::min(low, p.z), high = std::max(high, p.z);
  const MeshTopology topo = buildTopology(mushroom);
  for (Index e = 0; e < topo.edgeCount; ++e) {
    const Index a = topo.edgeVerts[2 * e], b = topo.edgeVerts[2 * e + 1];
    if (!topo.edgeOnBoundary(e) && std::max(mushroom.points[size_t(a)].z, mushroom.points[size_t(b)].z) < low + 0.3 * (high - low))
      mushroom.tags.creases.push_back({std::min(a, b), std::max(a, b), kInfiniteSharpness});
  }
  std::sort(mushroom.tags.creases.begin(), mushroom.tags.creases.end(),
            [](const CreaseEdge& x, const CreaseEdge& y) { return std::tie(x.v0, x.v1) < std::tie(y.v0, y.v1); });
  REQUIRE_FALSE(mushroom.tags.creases.empty());
  checkAgainstUniform(mushroom, "mushroom, creased stem", 4);
  // Semi-sharp creases under Chaikin's rule (a half edge decays with its neighbours' mean).
  PolyMesh chaikin = mushroom;
  for (size_t k = 0; k < chaikin.tags.creases.size(); ++k) chaikin.tags.creases[k].sharpness = 0.5 + 0.7 * double(k % 4);
  chaikin.tags.creaseMethod = CreaseMethod::Chaikin;
  checkAgainstUniform(chaikin, "mushroom, Chaikin semi-sharp stem", 4);
  // C2PS applies them (its stem is Catmull-Clark's) and still refines the pole.
  PolyMesh smooth = mushroom;
  smooth.tags = SubdivTags{};
  for (const Scheme scheme : {Scheme::C2PS, Scheme::RTS}) {
    const RefineOptions options{scheme, 3, false};
    const AdaptiveRefinement creased(mushroom, options), plain(smooth, options);
    CHECK(creased.level(0).poles.size() == 1);
    const PatchSet a = extractPatches(creased), b = extractPatches(plain);
    CHECK(a.count(PatchKind::PoleCap) == b.count(PatchKind::PoleCap));
    CHECK(a.count(PatchKind::Boundary) > b.count(PatchKind::Boundary));
  }
}

TEST_CASE("adaptive: the same patches as uniform refinement on OpenSubdiv's regression shapes (where kept), every scheme") {
  // Read with their tags (support/osd_shapes.h). The sparse steps meet creases, holes,
  // non-manifold splits, boundaries and n-gons here.
  const std::filesystem::path dir = testing::osdShapeDirectory(POLARVIEW_OSD_SHAPES);
  const std::vector<std::filesystem::path> files = testing::osdShapeFiles(dir);
  if (files.empty()) {
    MESSAGE("OpenSubdiv's regression shapes not found at ", dir.string(), ": skipped");
    return;
  }
  for (const std::filesystem::path& file : files) {
    const PolyMesh untagged = parseObjText(testing::osdShapeText(file, false), file.filename().string());
    const PolyMesh mesh = parseObjText(testing::osdShapeText(file, true), file.filename().string());
    // Levels as deep as keep the uniform side small (it grows as 4^L).
    const int levels = mesh.faceCount() > 2000 ? 3 : mesh.faceCount() > 200 ? 4 : 5;
    checkAgainstUniform(mesh, file.filename().string(), levels);
    // Without their tags other faces are refined: catmark_car's first step then refines faces
    // whose selected corners are not consecutive (two face points, sparse steps).
    if (!mesh.tags.creases.empty() || !mesh.tags.corners.empty())
      checkAgainstUniform(untagged, file.filename().string() + " untagged", levels, {Scheme::CatmullClark});
  }
}

TEST_CASE("adaptive: the face estimate stops at its budget, however large the poles (valence 100,000)") {
  // A level over the budget is refused before it is made: the estimate of a C2PS cap of valence
  // 100,000 (level 1: 400,000 faces) under a budget of 300,000 faces holds level 0 only, and says
  // "more than the budget" (budget + 1) from level 1 on; under 2,000,000 it measures levels 1-2.
  const PolyMesh cap = shapes::polarCap(100000, 2);
  const std::vector<size_t> small = estimateAdaptiveFaceCounts(cap, {Scheme::C2PS, 12, false}, 300000);
  REQUIRE(small.size() == 13);
  CHECK(small[0] == size_t(cap.faceCount()));
  for (int m = 1; m <= 12; ++m) CHECK(small[size_t(m)] == 300001);
  const std::vector<size_t> larger = estimateAdaptiveFaceCounts(cap, {Scheme::C2PS, 12, false}, 2000000);
  CHECK(larger[1] > size_t(cap.faceCount()));
  CHECK(larger[1] <= 2000000);
  CHECK(larger[12] == 2000001);
  // Within the budget the estimate is the refinement's own count.
  const PolyMesh small64 = shapes::polarCap(64, 3);
  const std::vector<size_t> counted = estimateAdaptiveFaceCounts(small64, {Scheme::C2PS, 4, false}, 1 << 24);
  CHECK(counted[4] == AdaptiveRefinement(small64, {Scheme::C2PS, 4, false}).totalFaces());
}

TEST_CASE("adaptive: the refinement and its patches are the same bit for bit on 1, 2 and 3 threads") {
  // Large enough that the extraction and the refiner's passes split (parallel_for.h thresholds):
  // C2PS on the default model, and Catmull-Clark on a globe whose two valence-512 poles give more
  // end caps than the extraction makes on a second thread (kCapsOnSecondThread) and levels large
  // enough for the sparse step's two tasks (kTwoTaskCorners).
  for (const auto& [mesh, scheme] : {std::pair{loadObj(std::string(POLARVIEW_ASSET_DIR) + "/default.obj"), Scheme::C2PS},
                                     std::pair{shapes::globe(512, 8), Scheme::CatmullClark}}) {
  CAPTURE(schemeName(scheme));
  auto run = [&](unsigned threads) {
    setThreadLimit(threads);
    AdaptiveRefinement refinement(mesh, {scheme, 7, false}, "default.obj");
    PatchSources sources;
    PatchSet set = extractPatches(refinement, &sources);
    setThreadLimit(0);
    return std::make_tuple(std::move(set), std::move(sources), refinement.level(refinement.levelCount() - 1).mesh.points);
  };
  const auto [one, oneSources, onePoints] = run(1);
  REQUIRE(one.patches.size() > 3 * 1024);
  if (scheme == Scheme::CatmullClark) REQUIRE(one.kindCounts[size_t(PatchKind::EndCap)] >= 1024);
  for (unsigned threads : {2u, 3u}) {
    CAPTURE(threads);
    const auto [many, manySources, manyPoints] = run(threads);
    CHECK(manyPoints == onePoints);
    CHECK(many.kindCounts == one.kindCounts);
    CHECK(manySources.stencil == oneSources.stencil);
    CHECK(manySources.sidesMissing == oneSources.sidesMissing);
    REQUIRE(many.patches.size() == one.patches.size());
    size_t differing = 0;
    for (size_t k = 0; k < one.patches.size(); ++k) {
      const Patch &a = one.patches[k], &b = many.patches[k];
      differing += !(a.cp == b.cp && a.origin == b.origin && a.kind == b.kind && a.level == b.level && a.ring == b.ring &&
                     a.pole == b.pole && a.face == b.face && a.sector == b.sector && a.link == b.link &&
                     a.ringTurn == b.ringTurn && a.edgeLevelDelta == b.edgeLevelDelta && a.capExtra == b.capExtra &&
                     a.sectorCount == b.sectorCount);
    }
    CHECK(differing == 0);
  }
  }
}

namespace {

// Every table, flag and point of two refinements of the same mesh, level for level: equal.
void requireSameLevels(const AdaptiveRefinement& a, const AdaptiveRefinement& b, const std::string& what) {
  INFO(what);
  REQUIRE(a.levelCount() == b.levelCount());
  CHECK(a.totalFaces() == b.totalFaces());
  for (int m = 0; m < a.levelCount(); ++m) {
    CAPTURE(m);
    const RefinedLevel &x = a.level(m), &y = b.level(m);
    CHECK(x.mesh.faceStart == y.mesh.faceStart);
    CHECK(x.mesh.faceVerts == y.mesh.faceVerts);
    CHECK(x.mesh.points == y.mesh.points);
    CHECK(x.faceParent == y.faceParent);
    CHECK(x.faceHole == y.faceHole);
    CHECK(x.sharpness.edge == y.sharpness.edge);
    CHECK(x.sharpness.vertex == y.sharpness.vertex);
    CHECK(x.frameOrigins == y.frameOrigins);
    CHECK(x.vertexFrame == y.vertexFrame);
    checkEqualTables(x.topology, y.topology);
    CHECK(a.neededFaces(m) == b.neededFaces(m));
    CHECK(a.exactVertices(m) == b.exactVertices(m));
    CHECK(a.radiallyRefinedFaces(m) == b.radiallyRefinedFaces(m));
  }
}

}  // namespace

TEST_CASE("adaptive: levels past a fixed point are copies, bit for bit what refining them again makes") {
  // Around isolated extraordinary vertices the sparse step soon makes a level equal to its parent
  // (docs/performance.md, "Fixed points"); from there the refinement copies levels and the
  // extraction reuses stencils. Against the same refinement with every level refined anew.
  std::vector<std::pair<std::string, PolyMesh>> meshes = {{"cube", shapes::cube()},
                                                          {"creased cube", creasedCube()},
                                                          {"torus", shapes::torus(6, 5)},
                                                          {"default.obj", loadObj(std::string(POLARVIEW_ASSET_DIR) + "/default.obj")}};
  const std::filesystem::path dir = testing::osdShapeDirectory(POLARVIEW_OSD_SHAPES);
  for (const std::filesystem::path& file : testing::osdShapeFiles(dir))
    meshes.emplace_back(file.filename().string(), parseObjText(testing::osdShapeText(file, true), file.filename().string()));
  const int levels = 8;
  int repeating = 0, cubeRepeats = 0;
  const size_t generated = 4;  // C2PS too on these (poles: no fixed point, every level anew)
  int refinements = 0;
  for (size_t i = 0; i < meshes.size(); ++i)
    for (Scheme scheme : {Scheme::CatmullClark, Scheme::C2PS}) {
      if (scheme == Scheme::C2PS && i >= generated) continue;
      const auto& [name, mesh] = meshes[i];
      ++refinements;
      const std::string what = name + " " + schemeName(scheme);
      RefineOptions copying{scheme, levels, false}, anew = copying;
      anew.copyFixedPointLevels = false;
      AdaptiveRefinement a(mesh, copying), b(mesh, anew);
      requireSameLevels(a, b, what);
      bool repeats = false;
      for (int m = 1; m < a.levelCount(); ++m) {
        repeats = repeats || a.repeatsParentLevel(m);
        CHECK(!b.repeatsParentLevel(m));
      }
      repeating += repeats;
      if (name == "cube" && scheme == Scheme::CatmullClark) cubeRepeats = repeats;
      // Patches, one-off with and without sources, and through a level cache stepping up.
      PatchSources sa, sb;
      const PatchSet pa = extractPatches(a, &sa), pb = extractPatches(b, &sb);
      requireIdentical(pb, sb, pa, sa, what + " patches");
      const PatchSet bare = extractPatches(a);
      REQUIRE(bare.patches.size() == pb.patches.size());
      for (size_t k = 0; k < bare.patches.size(); ++k) REQUIRE((bare.patches[k].cp == pb.patches[k].cp && bare.patches[k].level == pb.patches[k].level));
      LevelPatchCache cache;
      PatchSources cached;
      for (int level : {5, levels}) (void)cache.patchSet(a, level, &cached);
      requireIdentical(pb, sb, cache.patchSet(a, levels, &cached), cached, what + " cached");
      // Extended level by level, then moved points (an edit): the same again.
      AdaptiveRefinement c(mesh, RefineOptions{scheme, 2, false});
      for (int m = 3; m <= levels; ++m) c.extend(1);
      std::vector<Point> moved = mesh.points;
      moved[0] += Point(0.125, -0.25, 0.5);
      c.updatePositions(moved);
      b.updatePositions(moved);
      requireSameLevels(c, b, what + " extended and moved");
    }
  CHECK(cubeRepeats == 1);  // the cube's valence-3 corners reach a fixed point: the copies were made
  MESSAGE(repeating, " of ", refinements, " refinements reached a fixed point by level ", levels);
}
