// BezierView export: every written patch is read back from the text and compared with the patch it
// came from. B-spline patches must be the same polynomial (1e-12 of the bounding box, control points
// bit for bit after the 17-digit round trip) with du x dv outwards; pole caps must stay within
// the stated bound (1e-6 of the bounding box, measured densely) and be watertight among themselves.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/mesh/input_error.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/shapes.h"
#include "core/spline/bezierview_export.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/refiner.h"

using namespace polarview;

namespace {

// The bound the export documents for caps, relative to the bounding-box diagonal.
constexpr double kCapBound = 1e-6;

struct Case {
  std::string name;
  PolyMesh mesh;
  Scheme scheme;
  int level;
};

// A written file read back, with the source patch of every Bezier patch (caps: one per piece).
struct RoundTrip {
  PatchSet set;
  BezierViewStats stats;
  std::string text;
  std::vector<BezierViewGroup> groups;
  std::vector<const BezierPatch*> written;  // in file order
  std::vector<size_t> source;               // index into set.patches, parallel to `written`
  std::vector<int> piece, pieces;           // cap piece k of n (0 of 1 for B-spline patches)
};

RoundTrip roundTrip(const Case& c) {
  RoundTrip rt;
  rt.set = extractPatches(Refinement(c.mesh, {c.scheme, c.level, false}, c.name));
  std::ostringstream out;
  rt.stats = writeBezierView(out, rt.set);
  rt.text = out.str();
  std::istringstream in(rt.text);
  rt.groups = readBezierView(in, c.name);
  for (const BezierViewGroup& g : rt.groups)
    for (const BezierPatch& p : g.patches) rt.written.push_back(&p);

  // The writer's order: groups by (kind, level), extraction order inside; caps in fitPoleCap pieces.
  std::map<std::pair<int, int>, std::vector<size_t>> order;
  for (size_t k = 0; k < rt.set.patches.size(); ++k)
    order[{int(rt.set.patches[k].kind), int(rt.set.patches[k].level)}].push_back(k);
  const double diagonal = patchBoxDiagonal(rt.set);
  for (const auto& [key, members] : order)
    for (size_t k : members) {
      const int n = rt.set.patches[k].kind == PatchKind::PoleCap
                        ? int(fitPoleCap(rt.set.patches[k], BezierViewOptions{}, diagonal).size())
                        : 1;
      for (int p = 0; p < n; ++p) {
        rt.source.push_back(k);
        rt.piece.push_back(p);
        rt.pieces.push_back(n);
      }
    }
  return rt;
}

std::vector<Case> bsplineCases() {
  std::vector<Case> cases;
  cases.push_back({"torus", shapes::torus(8, 6), Scheme::CatmullClark, 0});
  cases.push_back({"grid", shapes::grid(4, 3, [](double x, double y) { return 0.3 * x * x - 0.2 * x * y; }),
                   Scheme::CatmullClark, 2});
  cases.push_back({"cube", shapes::cube(), Scheme::CatmullClark, 2});
  cases.push_back({"mushroom", shapes::mushroom(12), Scheme::C2PS, 2});
  cases.push_back({"globe", shapes::globe(8, 5), Scheme::RTS, 1});
  return cases;
}

std::vector<Case> capCases() {
  std::vector<Case> cases;
  for (int n : {5, 6, 8, 12})
    for (Scheme s : {Scheme::C2PS, Scheme::RTS, Scheme::BPS})
      for (int level = 0; level <= 2; ++level)
        cases.push_back({"cap n=" + std::to_string(n), shapes::polarCap(n, 4), s, level});
  for (Scheme s : {Scheme::C2PS, Scheme::RTS, Scheme::BPS}) {
    cases.push_back({"globe n=5", shapes::globe(5, 4), s, 2});
    cases.push_back({"mushroom", shapes::mushroom(12), s, 2});
    cases.push_back({"assets/default.obj", loadObj(std::string(POLARVIEW_ASSET_DIR) + "/default.obj"), s, 2});
    cases.push_back({"assets/globe.obj", loadObj(std::string(POLARVIEW_ASSET_DIR) + "/globe.obj"), s, 2});
  }
  return cases;
}

// Parameter of piece p of n at local t (as the writer samples).
double pieceParameter(int p, int n, double t) { return (1.0 - t) * (double(p) / n) + t * (double(p + 1) / n); }

}  // namespace

TEST_CASE("bezierview: B-spline patches are written as the same bicubic polynomial, outwards") {
  for (const Case& c : bsplineCases()) {
    CAPTURE(c.name);
    const RoundTrip rt = roundTrip(c);
    REQUIRE(rt.written.size() == rt.source.size());
    REQUIRE(rt.written.size() == rt.stats.total());
    CHECK(rt.groups.size() == rt.stats.groups);
    const double diagonal = patchBoxDiagonal(rt.set);
    REQUIRE(diagonal > 0.0);
    double worst = 0.0;
    int compared = 0;
    for (size_t w = 0; w < rt.written.size(); ++w) {
      const Patch& patch = rt.set.patches[rt.source[w]];
      if (patch.kind == PatchKind::PoleCap) continue;
      const BezierPatch& bezier = *rt.written[w];
      REQUIRE(bezier.degU == 3);
      REQUIRE(bezier.degV == 3);
      // 17 significant digits: the text holds the converted points exactly.
      const BezierPatch expected = bicubicBezier(patch);
      for (size_t k = 0; k < 16; ++k) REQUIRE(bezier.cp[k] == expected.cp[k]);
      for (double u : {0.0, 0.1, 0.37, 0.5, 0.81, 1.0})
        for (double v : {0.0, 0.23, 0.5, 0.66, 1.0}) {
          const SurfacePoint sp = evaluatePatch(patch, u, v);
          worst = std::max(worst, glm::length(bezier.evaluate(u, v) - sp.position) / diagonal);
          ++compared;
        }
      // Rows along u, columns along v: the finite-difference normal d/du x d/dv of the written patch
      // is evaluatePatch's (BezierView's normal is d/drow x d/dcolumn).
      const double h = 1e-4;
      const Point nu = bezier.evaluate(0.5 + h, 0.5) - bezier.evaluate(0.5 - h, 0.5);
      const Point nv = bezier.evaluate(0.5, 0.5 + h) - bezier.evaluate(0.5, 0.5 - h);
      const Point normal = evaluatePatch(patch, 0.5, 0.5).normal;
      if (glm::length(normal) > 0.0) CHECK(glm::dot(glm::normalize(glm::cross(nu, nv)), normal) > 0.999);
    }
    MESSAGE(c.name << ": " << compared << " samples, largest deviation " << worst << " of the bounding box");
    CHECK(compared > 0);
    CHECK(worst < 1e-12);
  }
}

TEST_CASE("bezierview: every written patch of a globe faces away from its centre, caps included") {
  for (Scheme s : {Scheme::C2PS, Scheme::RTS, Scheme::BPS, Scheme::CatmullClark}) {
    CAPTURE(schemeName(s));
    const RoundTrip rt = roundTrip({"globe", shapes::globe(8, 5), s, 2});
    for (size_t w = 0; w < rt.written.size(); ++w) {
      const BezierPatch& b = *rt.written[w];
      const double h = 1e-4, u = 0.5, v = 0.5;
      const Point position = b.evaluate(u, v);
      const Point normal = glm::cross(b.evaluate(u + h, v) - b.evaluate(u - h, v), b.evaluate(u, v + h) - b.evaluate(u, v - h));
      CHECK(glm::dot(normal, position) > 0.0);  // the globe is centred at the origin
    }
  }
}

TEST_CASE("bezierview: pole caps stay within 1e-6 of the bounding box and meet watertight") {
  double overall = 0.0;
  std::string overallCase;
  for (const Case& c : capCases()) {
    const std::string name = c.name + " " + schemeName(c.scheme) + " level " + std::to_string(c.level);
    CAPTURE(name);
    const RoundTrip rt = roundTrip(c);
    REQUIRE(rt.written.size() == rt.source.size());
    REQUIRE(rt.stats.capSectors == rt.set.count(PatchKind::PoleCap));
    REQUIRE(rt.stats.capSectors > 0);
    const double diagonal = patchBoxDiagonal(rt.set);
    double worst = 0.0;
    size_t capPatches = 0;
    for (size_t w = 0; w < rt.written.size(); ++w) {
      const Patch& cap = rt.set.patches[rt.source[w]];
      if (cap.kind != PatchKind::PoleCap) continue;
      ++capPatches;
      const BezierPatch& b = *rt.written[w];
      REQUIRE(b.degU == 5);  // the cap is a quintic in u (patch.h)
      // Row u = 0 is the pole; the edge shared with the next piece of the sector is the same curve.
      for (int j = 0; j <= b.degV; ++j) CHECK(b.cp[size_t(j)] == cap.origin + cap.cp[0]);
      if (rt.piece[w] + 1 < rt.pieces[w]) {
        const BezierPatch& next = *rt.written[w + 1];
        for (int i = 0; i <= b.degU; ++i)
          CHECK(b.cp[size_t(i) * (b.degV + 1) + b.degV] == next.cp[size_t(i) * (next.degV + 1)]);
      }
      // Dense deviation from evaluatePatch.
      const int su = 33, sv = 65;
      for (int a = 0; a < su; ++a)
        for (int k = 0; k < sv; ++k) {
          const double u = double(a) / (su - 1), t = double(k) / (sv - 1);
          const Point exact = evaluatePatch(cap, u, pieceParameter(rt.piece[w], rt.pieces[w], t)).position;
          worst = std::max(worst, glm::length(b.evaluate(u, t) - exact) / diagonal);
        }
    }
    CHECK(capPatches == rt.stats.written[size_t(PatchKind::PoleCap)]);
    CHECK(worst < kCapBound);
    // The writer's own (coarser) measurement is no larger than the dense one.
    CHECK(rt.stats.capRelativeDeviation() <= worst * (1.0 + 1e-9) + 1e-300);
    if (worst > overall) overall = worst, overallCase = name;
    char line[200];
    std::snprintf(line, sizeof line, "%-40s cap sectors %4zu, pieces %4zu (split <= %2d), dense max deviation %.3g",
                  name.c_str(), rt.stats.capSectors, capPatches, rt.stats.maxCapSplit, worst);
    MESSAGE(line);
  }
  MESSAGE("largest cap deviation: " << overall << " of the bounding box (" << overallCase << ")");
}

TEST_CASE("bezierview: the reader takes kinds 4 and 5 with groups and refuses the rest") {
  std::istringstream ok("Group 3 flat\n4\n1\n0 0 0\n0 1 0\n1 0 0\n1 1 0\n5\n1 2\n0 0 0 0 1 0 0 2 0\n1 0 0 1 1 0 1 2 1\n");
  const std::vector<BezierViewGroup> groups = readBezierView(ok, "ok.bv");
  REQUIRE(groups.size() == 1);
  CHECK(groups[0].name == "flat");
  CHECK(groups[0].id == 3);
  REQUIRE(groups[0].patches.size() == 2);
  CHECK(groups[0].patches[1].degV == 2);
  CHECK(glm::length(groups[0].patches[1].evaluate(1.0, 1.0) - Point(1, 2, 1)) == 0.0);
  std::istringstream triangle("3\n1\n0 0 0 1 0 0 0 1 0\n");
  CHECK_THROWS_AS(readBezierView(triangle, "tri.bv"), InputError);
  std::istringstream truncated("5\n3 3\n0 0 0\n");
  CHECK_THROWS_AS(readBezierView(truncated, "short.bv"), InputError);
}

TEST_CASE("bezierview: a non-finite control point is refused before anything is written") {
  PatchSet set = extractPatches(Refinement(shapes::torus(6, 5), {Scheme::CatmullClark, 0, false}, "torus"));
  set.patches[3].cp[7].y = std::nan("");
  std::ostringstream out;
  CHECK_THROWS_AS(writeBezierView(out, set, {}, "torus"), InputError);
  CHECK(out.str().empty());
}
