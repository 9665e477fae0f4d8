// Feature-adaptive extraction: patch counts by kind, and seams checked geometrically: every sample
// on every patch side must lie on another patch's side (watertight) unless it is on the mesh
// boundary, where it must lie on Catmull-Clark's EDGE_ONLY limit curve (the cubic B-spline of the
// boundary polygon). Matching by closest point makes the check independent of levels and
// parametrisations (neighbours may come from different levels).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/mesh/constants.h"
#include "core/mesh/shapes.h"
#include "core/mesh/topology.h"
#include "core/spline/patch.h"
#include "core/spline/patch_extraction.h"
#include "core/spline/pole_taylor.h"
#include "core/subdiv/refiner.h"

using namespace polarview;

namespace {

// Point of side s at t: s = 0: v = 0, u = t; 1: u = 1, v = t; 2: v = 1, u = 1-t; 3: u = 0, v = 1-t.
void sideParameter(int s, double t, double& u, double& v) {
  switch (s) {
    case 0: u = t, v = 0.0; break;
    case 1: u = 1.0, v = t; break;
    case 2: u = 1.0 - t, v = 1.0; break;
    default: u = 0.0, v = 1.0 - t; break;
  }
}

bool sideIsPole(const Patch& patch, int s) { return patch.kind == PatchKind::PoleCap && s == 3; }

struct Box {
  Point lo{1e300}, hi{-1e300};
  void add(const Point& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  bool contains(const Point& p, double margin) const {
    return p.x >= lo.x - margin && p.y >= lo.y - margin && p.z >= lo.z - margin && p.x <= hi.x + margin &&
           p.y <= hi.y + margin && p.z <= hi.z + margin;
  }
};

struct SideMatch {
  double distance = 1e300;
  int patch = -1;
  double u = 0, v = 0;
};

// Closest point to x on side s of a patch: the best of a few samples, then Newton steps on
// |C(t) - x|^2 (C the side curve, derivatives from evaluatePatch).
SideMatch closestOnSide(const Patch& patch, int s, const Point& x) {
  static constexpr double kDu[4] = {1, 0, -1, 0}, kDv[4] = {0, 1, 0, -1};
  auto at = [&](double t, Point* d1, Point* d2) {
    double u, v;
    sideParameter(s, t, u, v);
    const SurfacePoint sp = evaluatePatch(patch, u, v);
    if (d1) *d1 = kDu[s] * sp.du + kDv[s] * sp.dv;
    if (d2) *d2 = kDu[s] * kDu[s] * sp.duu + 2 * kDu[s] * kDv[s] * sp.duv + kDv[s] * kDv[s] * sp.dvv;
    return sp.position;
  };
  const int samples = 8;
  double t = 0.0, best = 1e300;
  for (int k = 0; k <= samples; ++k) {
    const double d = glm::length(at(double(k) / samples, nullptr, nullptr) - x);
    if (d < best) best = d, t = double(k) / samples;
  }
  for (int it = 0; it < 8; ++it) {
    Point d1, d2;
    const Point c = at(t, &d1, &d2);
    const double g = glm::dot(d1, c - x), h = glm::dot(d1, d1) + glm::dot(d2, c - x);
    if (!(h > 0.0)) break;
    t = std::clamp(t - g / h, 0.0, 1.0);
  }
  SideMatch match;
  match.distance = glm::length(at(t, nullptr, nullptr) - x);
  sideParameter(s, t, match.u, match.v);
  return match;
}

struct SeamReport {
  double maxGap = 0.0;                  // largest distance of a matched sample to its neighbour
  double maxAngleSmooth = 0.0;          // normal angle (rad) across seams without end caps / pole caps
  double maxAngleEndCap = 0.0;          // across seams touching an end cap
  double maxAngleCap = 0.0;             // across seams touching a pole cap
  std::vector<Point> unmatched;         // samples with no neighbour (mesh boundary)
  size_t samples = 0;
};

double meshSize(const PatchSet& set) {
  Box box;
  for (const Patch& p : set.patches) box.add(evaluatePatch(p, 0.5, 0.5).position);
  return glm::length(box.hi - box.lo);
}

SeamReport checkSeams(const PatchSet& set, double tolerance) {
  const std::vector<Patch>& patches = set.patches;
  std::vector<Box> boxes(patches.size());
  for (size_t i = 0; i < patches.size(); ++i) {
    if (patches[i].kind != PatchKind::PoleCap) {
      for (const Point& c : patches[i].cp) boxes[i].add(c);  // convex hull property
      continue;
    }
    for (int a = 0; a <= 8; ++a)
      for (int b = 0; b <= 8; ++b) boxes[i].add(evaluatePatch(patches[i], a / 8.0, b / 8.0).position);
    const Point pad = 0.25 * (boxes[i].hi - boxes[i].lo);
    boxes[i].lo -= pad, boxes[i].hi += pad;
  }
  SeamReport report;
  const double margin = 1e-6 * meshSize(set);
  for (size_t i = 0; i < patches.size(); ++i) {
    for (int s = 0; s < 4; ++s) {
      if (sideIsPole(patches[i], s)) continue;
      for (double t : {0.13, 0.5, 0.81}) {
        double u, v;
        sideParameter(s, t, u, v);
        const SurfacePoint here = evaluatePatch(patches[i], u, v);
        SideMatch best;
        for (size_t j = 0; j < patches.size(); ++j) {
          if (j == i || !boxes[j].contains(here.position, margin)) continue;
          for (int s2 = 0; s2 < 4; ++s2) {
            if (sideIsPole(patches[j], s2)) continue;
            SideMatch m = closestOnSide(patches[j], s2, here.position);
            if (m.distance < best.distance) best = m, best.patch = int(j);
          }
        }
        ++report.samples;
        if (best.distance > tolerance) {
          report.unmatched.push_back(here.position);
          continue;
        }
        report.maxGap = std::max(report.maxGap, best.distance);
        const Patch& other = patches[best.patch];
        const Point otherNormal = evaluatePatch(other, best.u, best.v).normal;
        const double angle = std::atan2(glm::length(glm::cross(here.normal, otherNormal)), glm::dot(here.normal, otherNormal));
        auto involves = [&](PatchKind kind) { return patches[i].kind == kind || other.kind == kind; };
        double& slot = involves(PatchKind::PoleCap) ? report.maxAngleCap
                       : involves(PatchKind::EndCap) ? report.maxAngleEndCap
                                                     : report.maxAngleSmooth;
        slot = std::max(slot, angle);
      }
    }
  }
  return report;
}

PatchSet extract(const PolyMesh& mesh, Scheme scheme, int levels) {
  RefineOptions options;
  options.scheme = scheme;
  options.levels = levels;
  Refinement refinement(mesh, options);
  return extractPatches(refinement);
}

std::string describe(const char* name, const PatchSet& set, const SeamReport& r) {
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "%s: %zu patches (regular %zu, boundary %zu, ring %zu, pole cap %zu, end cap %zu); %zu seam samples, "
                "max gap %.2e, normal angle: smooth %.2e rad, end caps %.2e rad, pole caps %.2e rad",
                name, set.patches.size(), set.count(PatchKind::Regular), set.count(PatchKind::Boundary),
                set.count(PatchKind::PolarRing), set.count(PatchKind::PoleCap), set.count(PatchKind::EndCap), r.samples,
                r.maxGap, r.maxAngleSmooth, r.maxAngleEndCap, r.maxAngleCap);
  return buf;
}

// The boundary loops of a mesh as point sequences (walked along boundary edges).
std::vector<std::vector<Point>> boundaryLoops(const PolyMesh& mesh) {
  const MeshTopology topo = buildTopology(mesh);
  std::vector<Index> next(mesh.vertexCount(), -1);
  for (Index f = 0; f < mesh.faceCount(); ++f)
    for (Index c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; ++c)
      if (topo.edgeOnBoundary(topo.cornerEdge[c])) {
        const Index a = mesh.faceVerts[c];
        const Index b = mesh.faceVerts[c + 1 < mesh.faceStart[f + 1] ? c + 1 : mesh.faceStart[f]];
        next[a] = b;
      }
  std::vector<uint8_t> seen(mesh.vertexCount(), 0);
  std::vector<std::vector<Point>> loops;
  for (Index v = 0; v < mesh.vertexCount(); ++v) {
    if (next[v] < 0 || seen[v]) continue;
    loops.emplace_back();
    for (Index w = v; !seen[w]; w = next[w]) {
      seen[w] = 1;
      loops.back().push_back(mesh.points[w]);
    }
  }
  return loops;
}

// Distance from x to the closed uniform cubic B-spline curves of the loops.
double distanceToBoundaryCurves(const std::vector<std::vector<Point>>& loops, const Point& x) {
  double best = 1e300;
  for (const auto& loop : loops) {
    const int n = int(loop.size());
    for (int k = 0; k < n; ++k) {
      const Point& d0 = loop[(k + n - 1) % n];
      const Point& d1 = loop[k];
      const Point& d2 = loop[(k + 1) % n];
      const Point& d3 = loop[(k + 2) % n];
      auto curve = [&](double t) {
        const double s = 1 - t;
        return (s * s * s * d0 + (3 * t * t * t - 6 * t * t + 4) * d1 + (-3 * t * t * t + 3 * t * t + 3 * t + 1) * d2 +
                t * t * t * d3) / 6.0;
      };
      double lo = 0, hi = 1;
      for (int it = 0; it < 100; ++it) {
        const double a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
        if (glm::length(curve(a) - x) < glm::length(curve(b) - x)) hi = b;
        else lo = a;
      }
      for (double t : {0.0, 0.5 * (lo + hi), 1.0}) best = std::min(best, glm::length(curve(t) - x));
    }
  }
  return best;
}

std::string formatNumber(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2e", x);
  return buf;
}

PolyMesh octahedron() {
  PolyMesh mesh;
  mesh.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  mesh.addFace({0, 2, 4});
  mesh.addFace({2, 1, 4});
  mesh.addFace({1, 3, 4});
  mesh.addFace({3, 0, 4});
  mesh.addFace({2, 0, 5});
  mesh.addFace({1, 2, 5});
  mesh.addFace({3, 1, 5});
  mesh.addFace({0, 3, 5});
  return mesh;
}

}  // namespace

TEST_CASE("extraction: a regular torus is all Regular patches at level 0, none at level 1, seamless") {
  for (int levels : {0, 1, 2}) {
    const PolyMesh torus = shapes::torus(8, 6);
    const PatchSet set = extract(torus, Scheme::CatmullClark, levels);
    CHECK(set.count(PatchKind::Regular) == size_t(torus.faceCount()));
    CHECK(set.patches.size() == size_t(torus.faceCount()));
    for (const Patch& p : set.patches) CHECK(p.level == 0);
    const SeamReport r = checkSeams(set, 1e-9 * meshSize(set));
    CHECK(r.unmatched.empty());
    CHECK(r.maxAngleSmooth < 1e-9);
    if (levels == 1) MESSAGE(describe("torus 8x6, CC L=1", set, r));
  }
}

TEST_CASE("extraction: a closed cube gets end caps exactly at its eight extraordinary vertices, watertight") {
  for (int levels : {1, 2, 3}) {
    RefineOptions options;
    options.scheme = Scheme::CatmullClark;
    options.levels = levels;
    const Refinement refinement(shapes::cube(), options);
    const PatchSet set = extractPatches(refinement);
    const RefinedLevel& finest = refinement.finest();
    for (const Patch& p : set.patches) {
      if (p.kind != PatchKind::EndCap) continue;
      int extraordinary = 0;
      for (int c = 0; c < 4; ++c) extraordinary += finest.topology.valence(finest.mesh.face(p.face)[c]) != 4;
      CHECK(extraordinary == 1);
    }
    CHECK(set.count(PatchKind::EndCap) == 24);  // 3 faces around each of 8 valence-3 vertices
    CHECK(set.count(PatchKind::Boundary) == 0);
    CHECK(set.count(PatchKind::PoleCap) == 0);
    // Regular patches: 6 faces -> 24 quads at level 1, each non-corner one regular from level 1 on.
    CHECK(set.count(PatchKind::Regular) + set.count(PatchKind::EndCap) > 0);
    for (const Patch& p : set.patches)
      if (p.kind == PatchKind::EndCap) CHECK(p.level == levels);
    const double size = meshSize(set);
    const SeamReport r = checkSeams(set, 1e-9 * size);
    CHECK(r.unmatched.empty());
    CHECK(r.maxGap < 1e-9 * size);
    CHECK(r.maxAngleSmooth < 1e-9);
    CHECK(r.maxAngleEndCap < 0.35);  // bounded (G0 end caps); measured below
    MESSAGE(describe(("cube, CC L=" + std::to_string(levels)).c_str(), set, r));
  }
}

TEST_CASE("extraction: an open grid's Boundary patches follow Catmull-Clark's limit boundary curve") {
  const PolyMesh grid = shapes::grid(6, 5, [](double x, double y) { return 0.3 * std::sin(3 * x) * std::cos(2 * y) + x * y; });
  const auto loops = boundaryLoops(grid);
  REQUIRE(loops.size() == 1);
  for (int levels : {0, 2}) {
    const PatchSet set = extract(grid, Scheme::CatmullClark, levels);
    CHECK(set.count(PatchKind::Boundary) > 0);
    CHECK(set.count(PatchKind::EndCap) == (levels == 0 ? 4 : 4));  // the four valence-2 corners
    const double size = meshSize(set);
    const SeamReport r = checkSeams(set, 1e-9 * size);
    CHECK(!r.unmatched.empty());
    double worst = 0.0;
    for (const Point& x : r.unmatched) worst = std::max(worst, distanceToBoundaryCurves(loops, x));
    CHECK(worst < 1e-9 * size);
    CHECK(r.maxAngleSmooth < 1e-9);
    const std::string report = describe(("open grid 6x5, CC L=" + std::to_string(levels)).c_str(), set, r) +
                               "; boundary samples off the CC limit curve by at most " + formatNumber(worst);
    MESSAGE(report);
  }
}

TEST_CASE("extraction: c2ps globe has 2 n_m ring patches per pole at each level m and caps of n_L sectors") {
  const int n = 6, links = 9;
  const PolyMesh globe = shapes::globe(n, links);
  for (int levels : {1, 2, 3}) {
    RefineOptions options;
    options.scheme = Scheme::C2PS;
    options.levels = levels;
    const Refinement refinement(globe, options);
    const PatchSet set = extractPatches(refinement);
    REQUIRE(refinement.finest().poles.size() == 2);
    // Per pole: ring m for m = 1..L has 2 n 2^m patches; ring 0 is the level-0 ring of each pole.
    for (int pole = 0; pole < 2; ++pole)
      for (int m = 1; m <= levels; ++m) {
        size_t ring = 0;
        for (const Patch& p : set.patches)
          if (p.kind == PatchKind::PolarRing && p.ring == m && p.pole == pole) ++ring;
        CHECK(ring == size_t(2 * (n << m)));
      }
    CHECK(set.count(PatchKind::PoleCap) == size_t(2 * (n << levels)));
    CHECK(set.count(PatchKind::EndCap) == 0);
    const double size = meshSize(set);
    const SeamReport r = checkSeams(set, 1e-9 * size);
    CHECK(r.unmatched.empty());
    CHECK(r.maxGap < 1e-9 * size);
    CHECK(r.maxAngleSmooth < 1e-8);
    CHECK(r.maxAngleCap < 1e-9);  // C1 caps (the C0 cap of before jumped by 0.185 rad at L = 1)
    MESSAGE(describe(("globe n=6, C2PS L=" + std::to_string(levels)).c_str(), set, r));
  }
}

TEST_CASE("extraction: the pole cap's boundary is ring L's inner boundary") {
  for (Scheme scheme : {Scheme::C2PS, Scheme::RTS, Scheme::BPS}) {
    const PolyMesh cap = shapes::polarCap(7, 6, 1.0, 1.5);
    RefineOptions options;
    options.scheme = scheme;
    options.levels = 2;
    const Refinement refinement(cap, options);
    const PatchSet set = extractPatches(refinement);
    const RefinedLevel& finest = refinement.finest();
    REQUIRE(finest.poles.size() == 1);
    const PolarConfig& config = finest.poles[0];
    const int nL = config.valence;
    // For every cap sector j: its u = 1 edge against the ring patch on face (q2j, q3j, q3j+1, q2j+1).
    double worst = 0.0;
    int checked = 0;
    for (const Patch& capPatch : set.patches) {
      if (capPatch.kind != PatchKind::PoleCap) continue;
      const int j = capPatch.sector;
      const Index a = config.links[size_t(nL) + j], b = config.links[size_t(nL) + (j + 1) % nL];
      for (const Patch& ring : set.patches) {
        if (ring.face < 0 || ring.level != refinement.levelCount() - 1 || ring.kind == PatchKind::PoleCap) continue;
        const Index* loop = finest.mesh.face(ring.face);
        int ca = -1, cb = -1;
        for (int c = 0; c < finest.mesh.faceSize(ring.face); ++c) {
          if (loop[c] == a) ca = c;
          if (loop[c] == b) cb = c;
        }
        if (ca < 0 || cb < 0) continue;
        const double corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (double t : {0.0, 0.25, 0.6, 1.0}) {
          const double u = (1 - t) * corner[ca][0] + t * corner[cb][0], v = (1 - t) * corner[ca][1] + t * corner[cb][1];
          worst = std::max(worst, glm::length(evaluatePatch(capPatch, 1.0, t).position - evaluatePatch(ring, u, v).position));
        }
        ++checked;
      }
    }
    CHECK(checked == nL);
    CHECK(worst < 1e-12);
    const SeamReport r = checkSeams(set, 1e-9 * meshSize(set));
    MESSAGE(describe((std::string("polar cap n=7, ") + schemeName(scheme) + " L=2").c_str(), set, r));
    // Every unmatched sample lies on the open boundary ring (the mesh's last link).
    const auto loops = boundaryLoops(cap);
    for (const Point& x : r.unmatched) CHECK(distanceToBoundaryCurves(loops, x) < 1e-9);
  }
}

TEST_CASE("extraction: the pole cap meets ring L with the same normal along the seam (C2: continuity_test) and keeps the pole's K, H") {
  struct Shape {
    const char* name;
    PolyMesh mesh;
  };
  const Shape shapesToCheck[] = {{"globe n=6", shapes::globe(6, 9)}, {"mushroom n=12", shapes::mushroom(12)}};
  for (const Shape& shape : shapesToCheck)
    for (int levels = 1; levels <= 4; ++levels) {
      RefineOptions options;
      options.scheme = Scheme::C2PS;
      options.levels = levels;
      const Refinement refinement(shape.mesh, options);
      const PatchSet set = extractPatches(refinement);
      const RefinedLevel& finest = refinement.finest();
      const int L = refinement.levelCount() - 1;
      // Ring-L patches by their face, to find the one on each cap sector's boundary edge.
      std::vector<int> patchOfFace(finest.mesh.faceCount(), -1);
      for (size_t k = 0; k < set.patches.size(); ++k)
        if (set.patches[k].level == L && set.patches[k].face >= 0) patchOfFace[set.patches[k].face] = int(k);
      double worstAngle = 0.0, worstGap = 0.0;
      int sectors = 0;
      for (const Patch& cap : set.patches) {
        if (cap.kind != PatchKind::PoleCap) continue;
        const PolarConfig& config = finest.poles[cap.pole];
        const int n = config.valence, j = cap.sector;
        const Index a = config.links[size_t(n) + j], b = config.links[size_t(n) + (j + 1) % n];
        Index edge = -1;
        for (Index k = finest.topology.vertexEdgeStart[a]; k < finest.topology.vertexEdgeStart[a + 1]; ++k)
          if (finest.topology.otherEnd(finest.topology.vertexEdges[k], a) == b) edge = finest.topology.vertexEdges[k];
        REQUIRE(edge >= 0);
        // Of the two faces on the 2-link edge (q2j, q2j+1) the ring patch is the one outside the hole.
        const Patch* ring = nullptr;
        for (int side = 0; side < 2; ++side) {
          const Index f = finest.topology.edgeFaces[2 * edge + side];
          if (f >= 0 && patchOfFace[f] >= 0) ring = &set.patches[patchOfFace[f]];
        }
        REQUIRE(ring != nullptr);
        const Index* loop = finest.mesh.face(ring->face);
        int ca = -1, cb = -1;
        for (int c = 0; c < 4; ++c) {
          if (loop[c] == a) ca = c;
          if (loop[c] == b) cb = c;
        }
        REQUIRE((ca >= 0 && cb >= 0));
        const double corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int k = 0; k <= 8; ++k) {
          const double t = k / 8.0;
          const double u = (1 - t) * corner[ca][0] + t * corner[cb][0], v = (1 - t) * corner[ca][1] + t * corner[cb][1];
          const SurfacePoint inside = evaluatePatch(cap, 1.0, t), outside = evaluatePatch(*ring, u, v);
          worstGap = std::max(worstGap, glm::length(inside.position - outside.position));
          worstAngle = std::max(worstAngle, std::atan2(glm::length(glm::cross(inside.normal, outside.normal)),
                                                       glm::dot(inside.normal, outside.normal)));
        }
        // At the pole: exactly the Taylor expansion's differential geometry.
        const PoleDifferential pole = analyzePole(finest.poleTaylor[cap.pole]);
        for (double v : {0.0, 0.5, 1.0}) {
          const SurfacePoint sp = evaluatePatch(cap, 0.0, v);
          CHECK(glm::length(sp.position - pole.limit) < 1e-14);
          CHECK(glm::length(sp.normal - pole.normal) < 1e-12);
          CHECK(sp.gaussian == doctest::Approx(pole.gaussian).epsilon(1e-12));
          CHECK(sp.mean == doctest::Approx(pole.mean).epsilon(1e-12));
        }
        ++sectors;
      }
      CHECK(size_t(sectors) == set.count(PatchKind::PoleCap));
      CHECK(sectors > 0);
      CHECK(worstGap < 1e-12);
      CHECK(worstAngle < 1e-9);
      MESSAGE(std::string(shape.name) << ", C2PS L=" << levels << ": " << sectors << " cap sectors, seam gap " << worstGap
                         << ", normal jump " << worstAngle << " rad");
    }
}

// Tessellation vertices of the T-junction sides (edgeLevelDelta != 0) with the segment counts the
// TCS chooses (transitionEdgeSegments), split into coarse (+d) and fine (-d) sides.
struct TransitionVertices {
  std::vector<Point> coarse, fine;
  int coarseSides = 0, fineSides = 0;
  int fineSidesExpected = 0;  // sum of 2^d over the coarse sides
};

TransitionVertices transitionVertices(const PatchSet& set, int densityExponent) {
  TransitionVertices out;
  for (const Patch& patch : set.patches)
    for (int s = 0; s < 4; ++s) {
      const int d = patch.edgeLevelDelta[s];
      if (d == 0) continue;
      const int segments = transitionEdgeSegments(patch.level, d, densityExponent);
      std::vector<Point>& into = d > 0 ? out.coarse : out.fine;
      ++(d > 0 ? out.coarseSides : out.fineSides);
      if (d > 0) out.fineSidesExpected += 1 << d;
      for (int i = 0; i <= segments; ++i) {
        double u, v;
        sideParameter(s, double(i) / segments, u, v);
        into.push_back(evaluatePatch(patch, u, v).position);
      }
    }
  return out;
}

// How many of `points` have no point of `targets` within `tolerance` (targets sorted by x).
size_t unmatchedPoints(const std::vector<Point>& points, std::vector<Point> targets, double tolerance) {
  std::sort(targets.begin(), targets.end(), [](const Point& a, const Point& b) { return a.x < b.x; });
  size_t unmatched = 0;
  for (const Point& p : points) {
    auto it = std::lower_bound(targets.begin(), targets.end(), p.x - tolerance,
                               [](const Point& a, double x) { return a.x < x; });
    bool found = false;
    for (; it != targets.end() && it->x <= p.x + tolerance && !found; ++it) found = glm::length(*it - p) <= tolerance;
    unmatched += !found;
  }
  return unmatched;
}

TEST_CASE("extraction: at every T-junction the fine sides' tessellation vertices are exactly the coarse side's") {
  struct Case {
    const char* name;
    PolyMesh mesh;
    Scheme scheme;
    int levels;
  };
  const Case cases[] = {{"mushroom C2PS", shapes::mushroom(12), Scheme::C2PS, 4},
                        {"mushroom CC", shapes::mushroom(12), Scheme::CatmullClark, 3},
                        {"mushroom RTS", shapes::mushroom(12), Scheme::RTS, 2},
                        {"globe C2PS", shapes::globe(6, 9), Scheme::C2PS, 3},
                        {"cube CC", shapes::cube(), Scheme::CatmullClark, 4},
                        {"octahedron CC", octahedron(), Scheme::CatmullClark, 3}};
  for (const Case& c : cases) {
    const std::string name = c.name;
    CAPTURE(name);
    const PatchSet set = extract(c.mesh, c.scheme, c.levels);
    const double tolerance = 1e-10 * meshSize(set);
    // Every patch's sides: a fine side's jump is at most the level, and caps have none.
    for (const Patch& patch : set.patches)
      for (int s = 0; s < 4; ++s) {
        CHECK(-patch.edgeLevelDelta[s] <= int(patch.level));
        if (patch.kind == PatchKind::PoleCap) CHECK(patch.edgeLevelDelta[s] == 0);
      }
    for (int k : {-3, 0, 2, 4, 7, 11}) {
      CAPTURE(k);
      const TransitionVertices t = transitionVertices(set, k);
      CHECK(t.coarseSides > 0);
      CHECK(t.fineSides == t.fineSidesExpected);  // each coarse side faces 2^d fine ones
      CHECK(unmatchedPoints(t.fine, t.coarse, tolerance) == 0);
      CHECK(unmatchedPoints(t.coarse, t.fine, tolerance) == 0);
      if (k == 4)
        MESSAGE(std::string(c.name) << " L=" << c.levels << ": " << t.coarseSides << " coarse and " << t.fineSides
                                    << " fine T-junction sides, " << t.fine.size() << " fine vertices all on the coarse sides' "
                                    << t.coarse.size());
    }
  }
}

TEST_CASE("extraction: RTS/BPS radial levels (caps, globes) have no T-junctions") {
  for (Scheme scheme : {Scheme::RTS, Scheme::BPS}) {
    RefineOptions options;
    options.scheme = scheme;
    options.levels = 3;
    const Refinement refinement(shapes::globe(6, 9), options);
    REQUIRE(refinement.radialOnly());
    const PatchSet set = extractPatches(refinement);
    int maxLevel = 0;
    for (const Patch& patch : set.patches) {
      maxLevel = std::max(maxLevel, int(patch.level));
      for (int s = 0; s < 4; ++s) CHECK(patch.edgeLevelDelta[s] == 0);
    }
    CHECK(maxLevel == 3);  // patches of several levels, meeting along whole edges
  }
}

TEST_CASE("extraction: a mushroom (pole, rings, CC stem with extraordinary vertices) is watertight") {
  for (Scheme scheme : {Scheme::C2PS, Scheme::RTS, Scheme::CatmullClark}) {
    const PatchSet set = extract(shapes::mushroom(12), scheme, 2);
    CHECK(set.count(PatchKind::EndCap) > 0);
    if (scheme != Scheme::CatmullClark) CHECK(set.count(PatchKind::PoleCap) == 48);
    const double size = meshSize(set);
    const SeamReport r = checkSeams(set, 1e-9 * size);
    CHECK(r.unmatched.empty());
    CHECK(r.maxAngleSmooth < 1e-8);
    MESSAGE(describe((std::string("mushroom, ") + schemeName(scheme) + " L=2").c_str(), set, r));
  }
}

TEST_CASE("extraction: triangles at level 0 become watertight split end caps") {
  const PatchSet set = extract(octahedron(), Scheme::CatmullClark, 0);
  CHECK(set.count(PatchKind::EndCap) == 8 * 3);
  const SeamReport r = checkSeams(set, 1e-9 * meshSize(set));
  CHECK(r.unmatched.empty());
}

TEST_CASE("end caps: the limit point and normal at an extraordinary vertex do not change with the level") {
  // Catmull-Clark limit points and the tangent mask's plane are exact, so end caps built at level 1
  // and at level 4 must agree at the extraordinary vertices (a jittered cube: eight valence-3 EVs,
  // and a mushroom's stem: four more).
  PolyMesh cube = shapes::cube();
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  for (Point& p : cube.points) p += Point(jitter(rng), jitter(rng), jitter(rng));
  struct EvSample {
    Point position, normal;
  };
  auto evSamples = [&](int levels) {
    RefineOptions options;
    options.scheme = Scheme::CatmullClark;
    options.levels = levels;
    const Refinement refinement(cube, options);
    const PatchSet set = extractPatches(refinement);
    const RefinedLevel& finest = refinement.finest();
    std::vector<EvSample> samples;
    const double corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const Patch& p : set.patches) {
      if (p.kind != PatchKind::EndCap) continue;
      const Index* loop = finest.mesh.face(p.face);
      for (int c = 0; c < 4; ++c)
        if (finest.topology.valence(loop[c]) != 4) {
          const SurfacePoint sp = evaluatePatch(p, corner[c][0], corner[c][1]);
          samples.push_back({sp.position, sp.normal});
        }
    }
    return samples;
  };
  const std::vector<EvSample> coarse = evSamples(1), fine = evSamples(4);
  REQUIRE(coarse.size() == 24);
  REQUIRE(fine.size() == 24);
  double worstPosition = 0.0, worstAngle = 0.0;
  for (const EvSample& a : coarse) {
    const EvSample* match = &fine[0];
    for (const EvSample& b : fine)
      if (glm::length(b.position - a.position) < glm::length(match->position - a.position)) match = &b;
    worstPosition = std::max(worstPosition, glm::length(match->position - a.position));
    worstAngle = std::max(worstAngle, std::atan2(glm::length(glm::cross(a.normal, match->normal)), glm::dot(a.normal, match->normal)));
  }
  CHECK(worstPosition < 1e-12);
  CHECK(worstAngle < 1e-10);
  // Every end cap at one EV has the same normal there (the normal is continuous at the EV).
  for (const EvSample& a : coarse)
    for (const EvSample& b : coarse)
      if (glm::length(a.position - b.position) < 1e-12) CHECK(glm::length(a.normal - b.normal) < 1e-12);
  MESSAGE("EV limit point drift level 1 -> 4: " << worstPosition << ", normal drift " << worstAngle << " rad");
}

TEST_CASE("end caps around a valence-300 vertex: tangents are the Catmull-Clark mask's, the caps meet watertight") {
  // A jittered 300-gon refined once: its centre is an extraordinary vertex of valence 300 with 300
  // quads around it, all end caps. The caps read each vertex's limit data once (linear in the
  // valence); here the tangents along every spoke are checked against the mask summed directly.
  const int n = 300;
  PolyMesh polygon;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  std::vector<Index> loop;
  for (int j = 0; j < n; ++j) {
    const double a = 2.0 * 3.14159265358979323846 * j / n;
    polygon.points.push_back({std::cos(a) + jitter(rng), std::sin(a) + jitter(rng), jitter(rng)});
    loop.push_back(Index(j));
  }
  polygon.addFace(loop.data(), loop.size());
  RefineOptions options;
  options.scheme = Scheme::CatmullClark;
  options.levels = 1;
  const Refinement refinement(polygon, options);
  const PatchSet set = extractPatches(refinement);
  const PolyMesh& mesh = refinement.finest().mesh;
  const MeshTopology& topo = refinement.finest().topology;
  // The mask, directly: t_i = scale sum_j A cos(step (j - i)) e_j + (cos(step (j - i)) + cos(step (j + 1 - i))) f_j.
  auto directTangent = [&](Index v, Index towards) {
    const Index k = topo.valence(v), first = topo.vertexEdgeStart[v], faceFirst = topo.vertexFaceStart[v];
    const double kd = double(k), step = 2.0 * 3.14159265358979323846 / kd;
    const double A = 1.0 + std::cos(step) + std::cos(step / 2.0) * std::sqrt(2.0 * (9.0 + std::cos(step)));
    const double scale = 1.0 / (kd * (0.5 * A + 1.0 + std::cos(step)));
    Index i = -1;
    for (Index j = 0; j < k; ++j)
      if (topo.otherEnd(topo.vertexEdges[first + j], v) == towards) i = j;
    REQUIRE(i >= 0);
    Point t(0.0);
    for (Index j = 0; j < k; ++j) {
      const Index face = topo.vertexFaces[faceFirst + j], corner = topo.vertexCorners[faceFirst + j];
      const Index start = mesh.faceStart[face];
      const Point& f = mesh.points[mesh.faceVerts[start + (corner - start + 2) % 4]];  // quad: opposite
      const Point& e = mesh.points[topo.otherEnd(topo.vertexEdges[first + j], v)];
      const double a = step * double(j - i), b = step * double(j + 1 - i);
      t += (A * std::cos(a)) * e + (std::cos(a) + std::cos(b)) * f;
    }
    return scale * t;
  };
  int checked = 0;
  double worst = 0.0;
  const double corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const Patch& p : set.patches) {
    REQUIRE(p.kind == PatchKind::EndCap);
    const Index* face = mesh.face(p.face);
    for (int c = 0; c < 4; ++c) {
      if (topo.valence(face[c]) != Index(n)) continue;
      // Along the face's edge from this corner to the next: +du, +dv, -du, -dv at corners 0..3.
      const SurfacePoint sp = evaluatePatch(p, corner[c][0], corner[c][1]);
      const Point along = c == 0 ? sp.du : c == 1 ? sp.dv : c == 2 ? -sp.du : -sp.dv;
      const Point expected = directTangent(face[c], face[(c + 1) % 4]);
      worst = std::max(worst, glm::length(along - expected) / std::max(glm::length(expected), 1e-300));
      ++checked;
    }
  }
  CHECK(checked == n);
  CHECK(worst < 1e-9);
  // Neighbouring caps share their spoke curves: sample every cap's sides, each sample must lie on
  // another cap's side too (watertight up to round-off).
  std::vector<Point> samples;
  for (const Patch& p : set.patches)
    for (double t : {0.25, 0.5, 0.75})
      for (const auto& uv : {std::pair{t, 0.0}, std::pair{1.0, t}, std::pair{t, 1.0}, std::pair{0.0, t}})
        samples.push_back(evaluatePatch(p, uv.first, uv.second).position);
  std::sort(samples.begin(), samples.end(), [](const Point& a, const Point& b) { return a.x < b.x; });
  int unmatched = 0;
  for (size_t s = 0; s < samples.size(); ++s) {
    bool found = false;
    for (size_t o = s; o-- > 0 && samples[s].x - samples[o].x < 1e-9;) found = found || glm::length(samples[o] - samples[s]) < 1e-11;
    for (size_t o = s + 1; o < samples.size() && samples[o].x - samples[s].x < 1e-9; ++o)
      found = found || glm::length(samples[o] - samples[s]) < 1e-11;
    unmatched += !found;
  }
  // The outer sides (on the polygon's boundary) have no neighbour: 3 samples on each of 2n of them.
  CHECK(unmatched == 3 * 2 * n);
  MESSAGE("valence " << n << ": " << checked << " spoke tangents, worst relative difference to the direct mask " << worst);
}

TEST_CASE("extraction: hole faces give no patches, at any level; the rest of the surface is unchanged") {
  // A torus (every face regular): holes change no point, so the holed set is the plain set less the
  // patches over the holes and their children, patch for patch.
  PolyMesh torus = shapes::torus(8, 6);
  const PatchSet plain = extract(torus, Scheme::CatmullClark, 2);
  torus.tags.holes = {0, 9, 20};
  const PatchSet holed = extract(torus, Scheme::CatmullClark, 2);
  REQUIRE(plain.patches.size() == size_t(torus.faceCount()));
  CHECK(holed.patches.size() == plain.patches.size() - 3);
  size_t k = 0;
  for (const Patch& patch : plain.patches) {
    if (patch.face == 0 || patch.face == 9 || patch.face == 20) continue;
    REQUIRE(k < holed.patches.size());
    CHECK(holed.patches[k].face == patch.face);
    CHECK(holed.patches[k].cp == patch.cp);
    ++k;
  }
  // A cube: end caps around holes' corners are refined like the others, none over the holes.
  PolyMesh cube = shapes::cube();
  const size_t cubePatches = extract(cube, Scheme::CatmullClark, 3).patches.size();
  cube.tags.holes = {4};
  CHECK(extract(cube, Scheme::CatmullClark, 3).patches.size() == cubePatches * 5 / 6);
}

TEST_CASE("extraction: interpolateboundary 0 keeps the faces away from the boundary, with the same patches") {
  PolyMesh grid = shapes::grid(6, 6, [](double x, double y) { return 0.3 * x * x - 0.2 * x * y; });
  const PatchSet edgeOnly = extract(grid, Scheme::CatmullClark, 0);
  grid.tags.boundary = BoundaryInterpolation::None;
  const PatchSet none = extract(grid, Scheme::CatmullClark, 2);
  // Faces touching a boundary vertex are holes: the inner 4 x 4 remain, regular at level 0.
  CHECK(none.patches.size() == 16);
  CHECK(none.count(PatchKind::Regular) == 16);
  size_t matched = 0;
  for (const Patch& patch : none.patches)
    for (const Patch& same : edgeOnly.patches) matched += same.face == patch.face && same.cp == patch.cp;
  CHECK(matched == 16);
}

namespace {

// Points of every patch on a (k+1) x (k+1) grid of its parameter square.
std::vector<Point> surfaceSamples(const PatchSet& set, int k) {
  std::vector<Point> points;
  for (const Patch& patch : set.patches)
    for (int i = 0; i <= k; ++i)
      for (int j = 0; j <= k; ++j) points.push_back(evaluatePatch(patch, double(i) / k, double(j) / k).position);
  return points;
}

// The largest distance from a point of `from` to the nearest of `to`. [O(|from| |to|)]
double farthestFrom(const std::vector<Point>& from, const std::vector<Point>& to) {
  double worst = 0.0;
  for (const Point& p : from) {
    double best = INFINITY;
    for (const Point& q : to) best = std::min(best, glm::length(p - q));
    worst = std::max(worst, best);
  }
  return worst;
}

}  // namespace

TEST_CASE("extraction: faces at infinitely sharp creases are boundary patches cut by the crease, exact at every level") {
  // A torus with one closed crease loop around its tube (vertices 0-5: valence 4, the sharp
  // edges opposite), and a cube with every edge infinitely sharp (corners where three meet).
  PolyMesh torus = shapes::torus(8, 6);
  {
    const MeshTopology topo = buildTopology(torus);
    for (Index e = 0; e < topo.edgeCount; ++e) {
      const Index a = topo.edgeVerts[2 * e], b = topo.edgeVerts[2 * e + 1];
      if (a < 6 && b < 6) torus.tags.creases.push_back({std::min(a, b), std::max(a, b), kInfiniteSharpness});
    }
    std::sort(torus.tags.creases.begin(), torus.tags.creases.end(),
              [](const CreaseEdge& x, const CreaseEdge& y) { return x.v0 != y.v0 ? x.v0 < y.v0 : x.v1 < y.v1; });
    REQUIRE(torus.tags.creases.size() == 6);
  }
  PolyMesh cube = shapes::cube();
  {
    const MeshTopology topo = buildTopology(cube);
    for (Index e = 0; e < topo.edgeCount; ++e)
      cube.tags.creases.push_back({std::min(topo.edgeVerts[2 * e], topo.edgeVerts[2 * e + 1]),
                                   std::max(topo.edgeVerts[2 * e], topo.edgeVerts[2 * e + 1]), kInfiniteSharpness});
    std::sort(cube.tags.creases.begin(), cube.tags.creases.end(),
              [](const CreaseEdge& x, const CreaseEdge& y) { return x.v0 != y.v0 ? x.v0 < y.v0 : x.v1 < y.v1; });
  }
  for (const auto& [name, mesh, boundaryPatches] :
       {std::tuple<std::string, PolyMesh, size_t>{"creased torus", torus, 12}, {"cube, every edge sharp", cube, 6}}) {
    CAPTURE(name);
    const PatchSet coarse = extract(mesh, Scheme::CatmullClark, 0);
    CHECK(coarse.patches.size() == size_t(mesh.faceCount()));  // every face a patch at level 0
    CHECK(coarse.count(PatchKind::Boundary) == boundaryPatches);
    CHECK(coarse.count(PatchKind::EndCap) == 0);
    // Two levels of the crease rules, then the same extraction of that mesh (with its tags): the
    // same surface, the level-2 patches' points on the level-0 patches to round-off.
    const Refinement refined(mesh, {Scheme::CatmullClark, 2, false});
    const PatchSet fine = extractPatches(Refinement(refined.finest().mesh, {Scheme::CatmullClark, 0, false}));
    CHECK(fine.patches.size() == 16 * coarse.patches.size());
    const double distance = farthestFrom(surfaceSamples(fine, 2), surfaceSamples(coarse, 8));
    MESSAGE(name, ": level-2 patches' points are within ", distance, " of the level-0 patches");
    CHECK(distance <= 1e-12);
  }
  // The cube's sharp limit is the cube itself: every point on a face plane.
  Point lo(INFINITY), hi(-INFINITY);
  for (const Point& p : cube.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  double offPlane = 0.0;
  for (const Point& p : surfaceSamples(extract(cube, Scheme::CatmullClark, 0), 6)) {
    double nearest = INFINITY;
    for (int axis = 0; axis < 3; ++axis) nearest = std::min({nearest, std::abs(p[axis] - lo[axis]), std::abs(p[axis] - hi[axis])});
    offPlane = std::max(offPlane, nearest);
  }
  CHECK(offPlane <= 1e-14);
}

// Patch::link, sector and ringTurn (patch.h): turned, a ring patch's u runs outwards (its corner at
// u = 1 is further from the pole's limit point than at u = 0), and along its row the sectors follow
// one another in v (sector s's last control column is sector s + 1's first but one).
TEST_CASE("extraction: ring patches know their place: link, sector along v, and the turn that points u outwards") {
  for (Scheme scheme : {Scheme::C2PS, Scheme::RTS}) {
    CAPTURE(static_cast<int>(scheme));
    RefineOptions options;
    options.scheme = scheme;
    options.levels = 3;
    const Refinement refinement(shapes::globe(6, 9), options);
    const PatchSet set = extractPatches(refinement);
    std::map<std::tuple<int, int, int>, std::map<int, const Patch*>> rows;  // (pole, ring, link) -> sector -> patch
    Point pole[2];
    for (const Patch& p : set.patches)
      if (p.kind == PatchKind::PoleCap) pole[p.pole] = p.origin + p.cp[0];
    size_t rings = 0;
    for (const Patch& p : set.patches) {
      if (p.kind != PatchKind::PolarRing) continue;
      ++rings;
      REQUIRE(p.link >= 1);
      REQUIRE(p.sector >= 0);
      CHECK(rows[{p.pole, p.ring, p.link}].emplace(p.sector, &p).second);  // one patch a sector
    }
    CHECK(rings > 0);
    for (const auto& [key, row] : rows) {
      const int sectors = int(row.size());
      CHECK(row.rbegin()->first == sectors - 1);
      for (const auto& [s, p] : row) {
        const Patch turned = turnedPatch(*p, p->ringTurn);
        const Point& centre = pole[std::get<0>(key)];
        CHECK(glm::length(turned.cp[6] - centre) > glm::length(turned.cp[5] - centre));
        const Patch& next = *row.at((s + 1) % sectors);
        const Patch nextTurned = turnedPatch(next, next.ringTurn);
        for (int i = 0; i < 4; ++i) CHECK(glm::length(turned.cp[size_t(4 + i)] - nextTurned.cp[size_t(i)]) < 1e-12);
      }
    }
  }
}
