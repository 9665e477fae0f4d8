// Catmull-Clark: B-spline reproduction, affine invariance, planarity, counts, limit masks.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "core/mesh/constants.h"
#include "core/mesh/shapes.h"
#include "core/mesh/topology.h"
#include "core/subdiv/catmull_clark.h"
#include "core/subdiv/refiner.h"
#include "support/reference_catmull_clark.h"

using namespace polarview;

namespace {

// (n+1) x (n+1) control points over an open n x n quad grid, random heights and jitter.
struct ControlGrid {
  int side = 0;             // points per side
  std::vector<Index> id;    // id[j * side + i]: vertex at grid position (i, j)
  PolyMesh mesh;
  Index at(int i, int j) const { return id[size_t(j) * side + i]; }
};

ControlGrid randomGrid(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2), height(-1, 1);
  ControlGrid g;
  g.side = n + 1;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      g.id.push_back(g.mesh.vertexCount());
      g.mesh.points.emplace_back(i + jitter(rng), j + jitter(rng), height(rng));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) g.mesh.addFace({g.at(i, j), g.at(i + 1, j), g.at(i + 1, j + 1), g.at(i, j + 1)});
  return g;
}

Index findEdge(const MeshTopology& t, Index a, Index b) {
  for (Index i = t.vertexEdgeStart[a]; i < t.vertexEdgeStart[a + 1]; ++i)
    if (t.otherEnd(t.vertexEdges[i], a) == b) return t.vertexEdges[i];
  FAIL("no edge between ", a, " and ", b);
  return -1;
}

Index findFace(const MeshTopology& t, Index a, Index c) {
  for (Index i = t.vertexFaceStart[a]; i < t.vertexFaceStart[a + 1]; ++i)
    for (Index k = t.vertexFaceStart[c]; k < t.vertexFaceStart[c + 1]; ++k)
      if (t.vertexFaces[i] == t.vertexFaces[k]) return t.vertexFaces[i];
  FAIL("no face with vertices ", a, " and ", c);
  return -1;
}

// One CC step of a grid, keeping track of where each grid position went (2i, 2j doubling).
ControlGrid refineGrid(const ControlGrid& g) {
  const MeshTopology t = buildTopology(g.mesh);
  ControlGrid child;
  child.mesh = reference::refineCatmullClark(g.mesh, t);
  child.side = 2 * g.side - 1;
  child.id.assign(size_t(child.side) * child.side, -1);
  auto set = [&](int i, int j, Index v) { child.id[size_t(j) * child.side + i] = v; };
  for (int j = 0; j < g.side; ++j)
    for (int i = 0; i < g.side; ++i) {
      set(2 * i, 2 * j, ccVertexPoint(t, g.at(i, j)));
      if (i + 1 < g.side) set(2 * i + 1, 2 * j, ccEdgePoint(t, findEdge(t, g.at(i, j), g.at(i + 1, j))));
      if (j + 1 < g.side) set(2 * i, 2 * j + 1, ccEdgePoint(t, findEdge(t, g.at(i, j), g.at(i, j + 1))));
      if (i + 1 < g.side && j + 1 < g.side) set(2 * i + 1, 2 * j + 1, ccFacePoint(t, findFace(t, g.at(i, j), g.at(i + 1, j + 1))));
    }
  return child;
}

// Uniform cubic B-spline basis on [0,1].
void bsplineBasis(double t, double b[4]) {
  const double s = 1 - t;
  b[0] = s * s * s / 6;
  b[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
  b[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;
  b[3] = t * t * t / 6;
}

// The bicubic uniform B-spline of the control grid at (u, v) (grid units; cell floor(u) uses
// control points floor(u)-1 .. floor(u)+2).
Point evaluateBSpline(const ControlGrid& g, double u, double v) {
  const int i = std::min(int(std::floor(u)), g.side - 3), j = std::min(int(std::floor(v)), g.side - 3);
  double bu[4], bv[4];
  bsplineBasis(u - i, bu);
  bsplineBasis(v - j, bv);
  Point p(0.0);
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a) p += bu[a] * bv[b] * g.mesh.points[g.at(i - 1 + a, j - 1 + b)];
  return p;
}

// A small open mesh with a triangle, a quad, a pentagon and a hexagon, plus an unused vertex.
PolyMesh mixedOpenMesh() {
  PolyMesh m;
  const double xy[][2] = {{0, 0}, {1, 0}, {2, 0}, {3, 0.2}, {0, 1}, {1, 1.1}, {2, 1}, {3, 1}, {1.5, 2}, {2.6, 1.9}, {0.4, 1.8}, {9, 9}};
  for (auto& p : xy) m.points.emplace_back(p[0], p[1], 0.1 * p[0] * p[1]);
  m.addFace({0, 1, 5, 4});          // quad
  m.addFace({1, 2, 6, 5});          // quad
  m.addFace({2, 3, 7, 6});          // quad
  m.addFace({4, 5, 8, 10});         // quad
  m.addFace({5, 6, 9, 8});          // quad
  m.addFace({6, 7, 9});             // triangle
  return m;
}

// A closed mesh with triangles, quads and pentagons: a pentagonal prism capped by 5-triangle fans
// on top and a pentagon at the bottom.
PolyMesh closedMixedMesh() {
  PolyMesh m;
  for (int ring = 0; ring < 2; ++ring)
    for (int j = 0; j < 5; ++j) m.points.emplace_back(std::cos(2 * kPi * j / 5), std::sin(2 * kPi * j / 5), ring);
  m.points.emplace_back(0, 0, 1.7);  // top apex, vertex 10
  for (int j = 0; j < 5; ++j) m.addFace({Index(j), Index((j + 1) % 5), Index(5 + (j + 1) % 5), Index(5 + j)});
  for (int j = 0; j < 5; ++j) m.addFace({Index(5 + j), Index(5 + (j + 1) % 5), 10});
  m.addFace({4, 3, 2, 1, 0});
  return m;
}

using polarview::shapes::cube;  // the unit cube, eight valence-3 vertices

// Two hexagons stacked on a 3 x 3 point grid: the middle vertex is interior with valence 2.
PolyMesh stackedHexagons() {
  PolyMesh m;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) m.points.emplace_back(i + 0.1 * j * j, j + 0.2 * i * i, 0.3 * i * j + (i == 1 && j == 1 ? 0.5 : 0));
  m.addFace({0, 1, 2, 5, 4, 3});
  m.addFace({3, 4, 5, 8, 7, 6});
  return m;
}

std::vector<PolyMesh> sampleMeshes() { return {cube(), mixedOpenMesh(), closedMixedMesh(), stackedHexagons(), randomGrid(4, 3).mesh}; }

// L steps of Catmull-Clark.
PolyMesh refineLevels(PolyMesh m, int levels) {
  for (int l = 0; l < levels; ++l) m = reference::refineCatmullClark(m, buildTopology(m));
  return m;
}

}  // namespace

TEST_CASE("catmull-clark: regular grid reproduces the bicubic B-spline") {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const int n = 7;
    ControlGrid level0 = randomGrid(n, seed);
    ControlGrid refined = level0;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> param(1.0, n - 1.0);  // cells untouched by boundary rules
    for (int level = 1; level <= 3; ++level) {
      refined = refineGrid(refined);
      const double scale = double(1 << level);
      double maxError = 0;
      for (int sample = 0; sample < 200; ++sample) {
        const double u = param(rng), v = param(rng);
        const Point expected = evaluateBSpline(level0, u, v), got = evaluateBSpline(refined, scale * u, scale * v);
        maxError = std::max(maxError, glm::length(expected - got));
      }
      CAPTURE(level);
      CHECK(maxError < 1e-13);
    }
  }
}

TEST_CASE("catmull-clark: limit points of a regular grid lie on the B-spline") {
  const ControlGrid g = randomGrid(6, 9);
  const ControlGrid refined = refineGrid(g);
  const std::vector<Point> limit = catmullClarkLimitPoints(buildTopology(refined.mesh), refined.mesh);
  for (int j = 2; j <= 2 * 6 - 2; ++j)
    for (int i = 2; i <= 2 * 6 - 2; ++i) {
      const Point onSurface = evaluateBSpline(g, i / 2.0, j / 2.0);
      CHECK(glm::length(limit[refined.at(i, j)] - onSurface) < 1e-13);
    }
}

TEST_CASE("catmull-clark: limit points do not move under further refinement") {
  for (const PolyMesh& base : sampleMeshes()) {
    const PolyMesh level1 = refineLevels(base, 1);
    const MeshTopology t1 = buildTopology(level1);
    const PolyMesh level2 = reference::refineCatmullClark(level1, t1);
    const std::vector<Point> limit1 = catmullClarkLimitPoints(t1, level1);
    const std::vector<Point> limit2 = catmullClarkLimitPoints(buildTopology(level2), level2);
    for (Index v = 0; v < level1.vertexCount(); ++v) CHECK(glm::length(limit1[v] - limit2[ccVertexPoint(t1, v)]) < 1e-13);
  }
  // Limit masks need quads around each vertex.
  CHECK_THROWS_AS(catmullClarkLimitPoints(buildTopology(closedMixedMesh()), closedMixedMesh()), std::invalid_argument);
}

TEST_CASE("catmull-clark: weights sum to one, so affine maps commute with refinement") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coef(-2, 2);
  for (const PolyMesh& base : sampleMeshes()) {
    glm::dmat3 linear;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) linear[c][r] = coef(rng);
    const Point shift(coef(rng) * 100, coef(rng) * 100, coef(rng) * 100);
    PolyMesh moved = base;
    for (Point& p : moved.points) p = linear * p + shift;
    const PolyMesh a = refineLevels(base, 2), b = refineLevels(moved, 2);
    REQUIRE(a.vertexCount() == b.vertexCount());
    double maxError = 0;
    for (Index v = 0; v < a.vertexCount(); ++v) maxError = std::max(maxError, glm::length(linear * a.points[v] + shift - b.points[v]));
    CHECK(maxError < 1e-11);
  }
}

TEST_CASE("catmull-clark: a plane stays planar") {
  const Point normal = glm::normalize(Point(0.3, -0.5, 0.8));
  const double offset = 0.7;
  for (const PolyMesh& base : {mixedOpenMesh(), randomGrid(5, 4).mesh}) {
    PolyMesh planar = base;
    for (Point& p : planar.points) p -= (glm::dot(p, normal) - offset) * normal;  // project onto the plane
    const PolyMesh refined = refineLevels(planar, 3);
    double maxDistance = 0;
    for (const Point& p : refined.points) maxDistance = std::max(maxDistance, std::abs(glm::dot(p, normal) - offset));
    CHECK(maxDistance < 1e-13);
  }
}

TEST_CASE("catmull-clark: counts are F' = corners, V' = F + E + V, E' = 2E + corners") {
  for (const PolyMesh& base : sampleMeshes()) {
    PolyMesh m = base;
    for (int level = 0; level < 3; ++level) {
      const MeshTopology t = buildTopology(m);
      const Index corners = Index(m.faceVerts.size());
      std::vector<Index> faceParent;
      PolyMesh child = reference::refineCatmullClarkTopology(m, t, &faceParent);
      computeCatmullClarkPoints(t, m, m.points.data(), child.points.data());
      CHECK(child.faceCount() == corners);
      CHECK(child.vertexCount() == t.faceCount + t.edgeCount + t.vertexCount);
      const MeshTopology ct = buildTopology(child);  // child is manifold and consistently oriented
      CHECK(ct.edgeCount == 2 * t.edgeCount + corners);
      CHECK(ct.vertexCount - ct.edgeCount + ct.faceCount == t.vertexCount - t.edgeCount + t.faceCount);
      // Child face c is (vertex point, outgoing edge point, face point, incoming edge point) of corner c.
      for (Index c = 0; c < corners; ++c) {
        const Index f = t.cornerFace[c];
        CHECK(faceParent[c] == f);
        CHECK(child.face(c)[0] == ccVertexPoint(t, m.faceVerts[c]));
        CHECK(child.face(c)[1] == ccEdgePoint(t, t.cornerEdge[c]));
        CHECK(child.face(c)[2] == ccFacePoint(t, f));
      }
      m = std::move(child);
    }
  }
}

TEST_CASE("catmull-clark: face points are centroids, boundary edges midpoints, unused vertices stay") {
  const PolyMesh m = mixedOpenMesh();
  const MeshTopology t = buildTopology(m);
  const PolyMesh child = reference::refineCatmullClark(m, t);
  for (Index f = 0; f < m.faceCount(); ++f) {
    Point centroid(0.0);
    for (Index i = 0; i < m.faceSize(f); ++i) centroid += m.points[m.face(f)[i]] / double(m.faceSize(f));
    CHECK(glm::length(child.points[ccFacePoint(t, f)] - centroid) < 1e-15);
  }
  for (Index e = 0; e < t.edgeCount; ++e)
    if (t.edgeOnBoundary(e))
      CHECK(glm::length(child.points[ccEdgePoint(t, e)] - 0.5 * (m.points[t.edgeVerts[2 * e]] + m.points[t.edgeVerts[2 * e + 1]])) < 1e-15);
  const Index unused = m.vertexCount() - 1;
  REQUIRE_FALSE(t.vertexUsed[unused]);
  CHECK(child.points[ccVertexPoint(t, unused)] == m.points[unused]);
}

// [SECTION] creases and corners (OpenSubdiv's CREASE_UNIFORM rules; osd_oracle_test compares them)

namespace {

// The edge between a and b of `mesh` as a crease tag.
CreaseEdge creaseTag(Index a, Index b, double sharpness) { return {std::min(a, b), std::max(a, b), sharpness}; }

// Level-1 points of `mesh` refined by Catmull-Clark with its tags.
std::vector<Point> refinedOnce(const PolyMesh& mesh) {
  return Refinement(mesh, {Scheme::CatmullClark, 1, false}).finest().mesh.points;
}

}  // namespace

TEST_CASE("catmull-clark: an infinitely sharp crease refines as a cubic B-spline curve, whatever lies off it") {
  // Row j = 3 of a 6 x 6 grid, boundary to boundary: its inner vertices take the crease rule, its
  // ends (three sharp edges) the corner rule, so the curve depends on its own points only.
  ControlGrid g = randomGrid(6, 5);
  for (int i = 0; i < 6; ++i) g.mesh.tags.creases.push_back(creaseTag(g.at(i, 3), g.at(i + 1, 3), kInfiniteSharpness));
  PolyMesh moved = g.mesh;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> shift(-0.3, 0.3);
  for (int j = 0; j <= 6; ++j)
    for (int i = 0; i <= 6; ++i)
      if (j != 3) moved.points[g.at(i, j)] += Point(shift(rng), shift(rng), shift(rng));
  constexpr int kLevels = 3;
  const Refinement a(g.mesh, {Scheme::CatmullClark, kLevels, false}), b(moved, {Scheme::CatmullClark, kLevels, false});
  const std::vector<Point>& pa = a.finest().mesh.points;
  const std::vector<Point>& pb = b.finest().mesh.points;
  const long unchanged = std::count_if(pa.begin(), pa.end(), [&](const Point& p) { return pb[size_t(&p - pa.data())] == p; });
  CHECK(unchanged == 6 * (1 << kLevels) + 1);  // exactly the points of the crease curve
  // The finest level still carries the crease, infinitely sharp, on all its 6 * 2^L edges.
  CHECK(a.finest().mesh.tags.creases.size() == size_t(6 * (1 << kLevels)));
}

TEST_CASE("catmull-clark: semi-sharp tags lose 1 a level until the crease is smooth") {
  PolyMesh m = shapes::cube();
  m.tags.creases = {creaseTag(m.face(0)[0], m.face(0)[1], 2.5)};
  m.tags.corners = {{m.face(0)[2], 1.5}};
  const Refinement r(m, {Scheme::CatmullClark, 3, false});
  CHECK_FALSE(r.level(0).sharpness.empty());
  const SubdivTags& level1 = r.level(1).mesh.tags;
  REQUIRE(level1.creases.size() == 2);  // the edge's two halves
  for (const CreaseEdge& c : level1.creases) CHECK(c.sharpness == 1.5);
  CHECK(level1.corners == std::vector<CornerVertex>{{ccVertexPoint(r.level(0).topology, m.face(0)[2]), 0.5}});
  const SubdivTags& level2 = r.level(2).mesh.tags;
  CHECK(level2.creases.size() == 4);
  for (const CreaseEdge& c : level2.creases) CHECK(c.sharpness == 0.5);
  CHECK(level2.corners.empty());
  CHECK(r.level(3).mesh.tags.creases.empty());
  CHECK(r.level(3).sharpness.empty());  // smooth from here: the fast rules apply
}

TEST_CASE("catmull-clark: sharpness s in (0, 1) blends s of the sharp rule with 1 - s of the smooth one") {
  const PolyMesh smoothMesh = shapes::torus(6, 5);
  const MeshTopology t = buildTopology(smoothMesh);
  const std::vector<Point> smooth = refinedOnce(smoothMesh);
  constexpr double s = 0.375;  // exact in float, as OpenSubdiv stores it
  const Index e = 7, v = 11;
  const Index a = t.edgeVerts[2 * e], b = t.edgeVerts[2 * e + 1];
  REQUIRE(v != a);
  REQUIRE(v != b);

  PolyMesh creased = smoothMesh;
  creased.tags.creases = {creaseTag(a, b, s)};
  const std::vector<Point> withCrease = refinedOnce(creased);
  const Point midpoint = 0.5 * (smoothMesh.points[a] + smoothMesh.points[b]);
  CHECK(glm::length(withCrease[ccEdgePoint(t, e)] - (s * midpoint + (1 - s) * smooth[ccEdgePoint(t, e)])) < 1e-14);
  // Its ends are darts (one sharp edge): smooth rule.
  CHECK(withCrease[ccVertexPoint(t, a)] == smooth[ccVertexPoint(t, a)]);

  // A corner of sharpness s: s of the vertex itself (corner rule), 1 - s of the smooth point.
  PolyMesh cornered = smoothMesh;
  cornered.tags.corners = {{v, s}};
  const std::vector<Point> withCorner = refinedOnce(cornered);
  CHECK(glm::length(withCorner[ccVertexPoint(t, v)] - (s * smoothMesh.points[v] + (1 - s) * smooth[ccVertexPoint(t, v)])) < 1e-14);
  for (Index w = 0; w < t.vertexCount; ++w)
    if (w != v) CHECK(withCorner[ccVertexPoint(t, w)] == smooth[ccVertexPoint(t, w)]);
}
