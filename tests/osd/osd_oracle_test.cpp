// Catmull-Clark against OpenSubdiv 3.5 as the oracle: same options as OpenSubdiv's own tools
// (VTX_BOUNDARY_EDGE_ONLY, CREASE_UNIFORM, TRI_SUB_CATMARK), refined uniformly level by level
// with Far::PrimvarRefinerReal<double>; positions must agree to round-off at every level.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <random>
#include <string>

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <glm/geometric.hpp>

#include "app/osd_descriptor.h"

#include "core/mesh/constants.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/shapes.h"
#include "core/mesh/topology.h"
#include "core/subdiv/catmull_clark.h"
#include "core/subdiv/refiner.h"
#include "support/reference_catmull_clark.h"
#include "support/osd_shapes.h"

using namespace polarview;
namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

namespace {

constexpr int kLevels = 4;

// The vertex type PrimvarRefiner interpolates (its Clear / AddWithWeight interface).
struct OsdPoint {
  Point p{0.0};
  void Clear(void* = nullptr) { p = Point(0.0); }
  void AddWithWeight(const OsdPoint& src, double weight) { p += weight * src.p; }
};

// [SECTION] Test meshes, each generated here

using polarview::shapes::cube;  // the unit cube, eight valence-3 vertices

// An nu x nv grid of cells, open or wrapped into a torus, whose cells are randomly made into quads,
// triangle pairs, 4-triangle fans around a centre vertex, hexagons (two cells merged) or a pentagon
// plus a triangle (a cell merged with half of its neighbour). `mixed` false keeps all quads.
PolyMesh cellGrid(int nu, int nv, bool torus, bool mixed, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  PolyMesh m;
  const int cu = torus ? nu : nu + 1, cv = torus ? nv : nv + 1;
  auto place = [&](double i, double j) {
    if (!torus) return Point(i + jitter(rng), j + jitter(rng), 0.5 * std::sin(i) * std::cos(0.7 * j) + jitter(rng));
    const double u = 2 * kPi * i / nu, v = 2 * kPi * j / nv, r = 1 + jitter(rng);
    return Point((3 + r * std::cos(v)) * std::cos(u), (3 + r * std::cos(v)) * std::sin(u), r * std::sin(v));
  };
  for (int j = 0; j < cv; ++j)
    for (int i = 0; i < cu; ++i) m.points.push_back(place(i, j));
  auto id = [&](int i, int j) { return Index((j % cv) * cu + (i % cu)); };

  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const Index a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      const int kind = mixed ? int(rng() % 5) : 0;
      const bool roomForTwo = i + 1 < nu;  // merged cells never wrap around
      if (kind == 1) {
        m.addFace({a, b, c});
        m.addFace({a, c, d});
      } else if (kind == 2) {
        const Index centre = m.vertexCount();
        m.points.push_back(place(i + 0.5, j + 0.5));
        m.addFace({a, b, centre});
        m.addFace({b, c, centre});
        m.addFace({c, d, centre});
        m.addFace({d, a, centre});
      } else if (kind == 3 && roomForTwo) {
        m.addFace({a, b, id(i + 2, j), id(i + 2, j + 1), c, d});  // hexagon over two cells
        ++i;
      } else if (kind == 4 && roomForTwo) {
        const Index e = id(i + 2, j), g = id(i + 2, j + 1);
        m.addFace({a, b, g, c, d});  // pentagon: this cell and half of the next
        m.addFace({b, e, g});
        ++i;
      } else {
        m.addFace({a, b, c, d});
      }
    }
  }
  return m;
}

// A valence-n triangle fan around a pole, ringed by `rings` rings of quads; open at the outer ring
// or closed by a second pole (a globe).
PolyMesh poleMesh(int n, int rings, bool closed) {
  PolyMesh m;
  m.points.emplace_back(0, 0, 1);
  for (int r = 1; r <= rings; ++r)
    for (int j = 0; j < n; ++j) {
      const double t = (closed ? kPi : 0.5 * kPi) * r / (rings + 1), a = 2 * kPi * j / n;
      m.points.emplace_back(std::sin(t) * std::cos(a), std::sin(t) * std::sin(a), std::cos(t) + 0.05 * std::cos(3 * a));
    }
  auto q = [&](int r, int j) { return Index(1 + (r - 1) * n + (j % n)); };
  for (int j = 0; j < n; ++j) m.addFace({0, q(1, j), q(1, j + 1)});
  for (int r = 1; r < rings; ++r)
    for (int j = 0; j < n; ++j) m.addFace({q(r, j), q(r + 1, j), q(r + 1, j + 1), q(r, j + 1)});
  if (closed) {
    const Index south = m.vertexCount();
    m.points.emplace_back(0, 0, -1);
    for (int j = 0; j < n; ++j) m.addFace({south, q(rings, j + 1), q(rings, j)});
  }
  return m;
}

// [SECTION] OpenSubdiv side

// OpenSubdiv's refiner of `m`, with m.tags' creases and corners (sharpness as float, as Far takes
// it), boundary rule and creasing method.
std::unique_ptr<Far::TopologyRefiner> osdRefiner(const PolyMesh& m, int levels) {
  const OsdMeshDescriptor described(m);
  std::unique_ptr<Far::TopologyRefiner> refiner(described.create());
  REQUIRE(refiner);
  Far::TopologyRefiner::UniformOptions uniform(levels);
  uniform.fullTopologyInLastLevel = true;  // PrimvarRefiner::Limit needs the finest level's vertex rings
  refiner->RefineUniform(uniform);
  return refiner;
}

// Maps our child vertices and faces to OpenSubdiv's at the next level, given the maps at this
// level. Face and vertex points map through their parents; edge points through the parent edge's
// end vertices (the two libraries number edges differently).
void mapChildLevel(const MeshTopology& topo, const PolyMesh& child, const Far::TopologyLevel& osdParent,
                   const Far::TopologyLevel& osdChild, const std::vector<int>& vertexMap, const std::vector<int>& faceMap,
                   std::vector<int>& childVertexMap, std::vector<int>& childFaceMap) {
  childVertexMap.assign(child.vertexCount(), -1);
  for (Index f = 0; f < topo.faceCount; ++f) childVertexMap[ccFacePoint(topo, f)] = osdParent.GetFaceChildVertex(faceMap[f]);
  for (Index e = 0; e < topo.edgeCount; ++e) {
    const int a = vertexMap[topo.edgeVerts[2 * e]], b = vertexMap[topo.edgeVerts[2 * e + 1]];
    const int osdEdge = osdParent.FindEdge(a, b);
    REQUIRE(osdEdge >= 0);
    const auto ends = osdParent.GetEdgeVertices(osdEdge);
    REQUIRE(std::min(ends[0], ends[1]) == std::min(a, b));
    REQUIRE(std::max(ends[0], ends[1]) == std::max(a, b));
    childVertexMap[ccEdgePoint(topo, e)] = osdParent.GetEdgeChildVertex(osdEdge);
  }
  for (Index v = 0; v < topo.vertexCount; ++v) childVertexMap[ccVertexPoint(topo, v)] = osdParent.GetVertexChildVertex(vertexMap[v]);

  // Child face c (of parent corner c) is the OSD child face of the same parent containing its vertex point.
  childFaceMap.assign(child.faceCount(), -1);
  for (Index c = 0; c < child.faceCount(); ++c) {
    const int vertexPoint = childVertexMap[child.face(c)[0]];
    for (int osdFace : osdParent.GetFaceChildFaces(faceMap[topo.cornerFace[c]])) {
      const auto verts = osdChild.GetFaceVertices(osdFace);
      if (std::find(verts.begin(), verts.end(), vertexPoint) != verts.end()) childFaceMap[c] = osdFace;
    }
    REQUIRE(childFaceMap[c] >= 0);
    // Same quad, same orientation: OSD's loop is ours mapped, up to rotation.
    const auto verts = osdChild.GetFaceVertices(childFaceMap[c]);
    REQUIRE(verts.size() == 4);
    const int shift = int(std::find(verts.begin(), verts.end(), vertexPoint) - verts.begin());
    for (int k = 0; k < 4; ++k) CHECK(verts[(shift + k) % 4] == childVertexMap[child.face(c)[k]]);
  }
}

double boundingDiagonal(const std::vector<Point>& points) {
  Point lo(points[0]), hi(points[0]);
  for (const Point& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return glm::length(hi - lo);
}

// Refines `base` kLevels times with both libraries and compares counts and positions per level,
// then the limit positions of the finest level.
void compareWithOpenSubdiv(const std::string& name, const PolyMesh& base) {
  CAPTURE(name);
  const std::unique_ptr<Far::TopologyRefiner> refiner = osdRefiner(base, kLevels);
  const Far::PrimvarRefinerReal<double> primvar(*refiner);
  const double scale = boundingDiagonal(base.points);
  const double tolerance = 1e-12 * scale;

  std::vector<OsdPoint> osdPoints(base.vertexCount());
  for (Index v = 0; v < base.vertexCount(); ++v) osdPoints[v].p = base.points[v];
  std::vector<int> vertexMap(base.vertexCount()), faceMap(base.faceCount());
  for (size_t i = 0; i < vertexMap.size(); ++i) vertexMap[i] = int(i);
  for (size_t i = 0; i < faceMap.size(); ++i) faceMap[i] = int(i);

  PolyMesh ours = base;
  MeshTopology topo = buildTopology(ours);
  for (int level = 1; level <= kLevels; ++level) {
    CAPTURE(level);
    const Far::TopologyLevel& osdParent = refiner->GetLevel(level - 1);
    const Far::TopologyLevel& osdChild = refiner->GetLevel(level);
    REQUIRE(osdParent.GetNumEdges() == topo.edgeCount);

    PolyMesh child = reference::refineCatmullClark(ours, topo);
    REQUIRE(child.faceCount() == osdChild.GetNumFaces());
    REQUIRE(child.vertexCount() == osdChild.GetNumVertices());
    std::vector<OsdPoint> osdChildPoints(osdChild.GetNumVertices());
    OsdPoint* dst = osdChildPoints.data();  // PrimvarRefiner takes the destination by reference
    primvar.Interpolate(level, osdPoints.data(), dst);

    std::vector<int> childVertexMap, childFaceMap;
    mapChildLevel(topo, child, osdParent, osdChild, vertexMap, faceMap, childVertexMap, childFaceMap);
    double maxDifference = 0;
    for (Index v = 0; v < child.vertexCount(); ++v)
      maxDifference = std::max(maxDifference, glm::length(child.points[v] - osdChildPoints[childVertexMap[v]].p));
    MESSAGE(name, " level ", level, ": ", child.faceCount(), " faces, max |ours - OpenSubdiv| = ", maxDifference,
            " (scale ", scale, ")");
    CHECK(maxDifference <= tolerance);

    ours = std::move(child);
    topo = buildTopology(ours);
    osdPoints = std::move(osdChildPoints);
    vertexMap = std::move(childVertexMap);
    faceMap = std::move(childFaceMap);
  }

  // Limit positions of the finest level (all quads) against OSD's limit masks. OSD gives an
  // interior valence-2 vertex its own position (Sdc's corner mask), not the limit its vertex
  // points converge to; ours is that limit (catmull_clark_test: it stays put under refinement),
  // so those vertices are skipped here.
  std::vector<OsdPoint> osdLimit(osdPoints.size());
  OsdPoint* limitDst = osdLimit.data();
  primvar.Limit(osdPoints.data(), limitDst);
  const std::vector<Point> limit = catmullClarkLimitPoints(topo, ours);
  double maxLimitDifference = 0;
  int skipped = 0;
  for (Index v = 0; v < ours.vertexCount(); ++v) {
    if (!topo.vertexOnBoundary[v] && topo.valence(v) == 2) {
      ++skipped;
      continue;
    }
    maxLimitDifference = std::max(maxLimitDifference, glm::length(limit[v] - osdLimit[vertexMap[v]].p));
  }
  MESSAGE(name, " limit points at level ", kLevels, ": max |ours - OpenSubdiv| = ", maxLimitDifference, " (",
          skipped, " interior valence-2 vertices skipped)");
  CHECK(maxLimitDifference <= tolerance);
}

// Per face of `level`: whether it is a hole on both sides (faceMap: ours -> OpenSubdiv's); returns
// how many are.
size_t compareHoles(const RefinedLevel& level, const Far::TopologyLevel& osdLevel, const std::vector<int>& faceMap) {
  size_t holes = 0, differ = 0;
  for (Index f = 0; f < level.mesh.faceCount(); ++f) {
    holes += level.isHole(f);
    differ += level.isHole(f) != osdLevel.IsFaceHole(faceMap[size_t(f)]);
  }
  CHECK(differ == 0);
  return holes;
}

// Refines `base` (with crease and corner tags) kLevels times with polarview's uniform Refinement
// and with OpenSubdiv, and compares positions and hole faces per level; also that each level's tags
// are the base's less 1 a level, by refining the level-1 mesh with its own tags once more.
void compareSharpWithOpenSubdiv(const std::string& name, const PolyMesh& base, bool sharp = true) {
  CAPTURE(name);
  const std::unique_ptr<Far::TopologyRefiner> refiner = osdRefiner(base, kLevels);
  const Far::PrimvarRefinerReal<double> primvar(*refiner);
  const double tolerance = 1e-12 * boundingDiagonal(base.points);
  const Refinement ours(base, {Scheme::CatmullClark, kLevels, false});
  REQUIRE(ours.levelCount() == kLevels + 1);
  CHECK(ours.level(0).sharpness.empty() == !sharp);

  std::vector<OsdPoint> osdPoints(base.vertexCount());
  for (Index v = 0; v < base.vertexCount(); ++v) osdPoints[v].p = base.points[v];
  std::vector<int> vertexMap(base.vertexCount()), faceMap(base.faceCount());
  for (size_t i = 0; i < vertexMap.size(); ++i) vertexMap[i] = int(i);
  for (size_t i = 0; i < faceMap.size(); ++i) faceMap[i] = int(i);
  const size_t baseHoleCount = compareHoles(ours.level(0), refiner->GetLevel(0), faceMap);
  CHECK((baseHoleCount > 0) == refiner->HasHoles());
  for (int level = 1; level <= kLevels; ++level) {
    CAPTURE(level);
    const RefinedLevel& parent = ours.level(level - 1);
    const PolyMesh& child = ours.level(level).mesh;
    const Far::TopologyLevel& osdChild = refiner->GetLevel(level);
    REQUIRE(child.vertexCount() == osdChild.GetNumVertices());
    std::vector<OsdPoint> osdChildPoints(osdChild.GetNumVertices());
    OsdPoint* dst = osdChildPoints.data();
    primvar.Interpolate(level, osdPoints.data(), dst);
    std::vector<int> childVertexMap, childFaceMap;
    mapChildLevel(parent.topology, child, refiner->GetLevel(level - 1), osdChild, vertexMap, faceMap, childVertexMap, childFaceMap);
    double maxDifference = 0;
    for (Index v = 0; v < child.vertexCount(); ++v)
      maxDifference = std::max(maxDifference, glm::length(child.points[v] - osdChildPoints[childVertexMap[v]].p));
    const size_t holes = compareHoles(ours.level(level), osdChild, childFaceMap);
    MESSAGE(name, " level ", level, ": max |ours - OpenSubdiv| = ", maxDifference, ", ", holes, " hole faces");
    CHECK(maxDifference <= tolerance);
    osdPoints = std::move(osdChildPoints);
    vertexMap = std::move(childVertexMap);
    faceMap = std::move(childFaceMap);
  }

  // The level-1 mesh with its tags (sharpness less 1) refined kLevels - 1 times is the same surface.
  const Refinement again(ours.level(1).mesh, {Scheme::CatmullClark, kLevels - 1, false});
  double maxDifference = 0;
  for (Index v = 0; v < ours.finest().mesh.vertexCount(); ++v)
    maxDifference = std::max(maxDifference, glm::length(again.finest().mesh.points[v] - ours.finest().mesh.points[v]));
  CHECK(maxDifference <= tolerance);
}

// Tags `mesh`: each edge crease with probability 1/3, sharpness from a list of fractional (under
// and over 1), integral and infinite values, and every seventh vertex a corner.
void tagRandomly(PolyMesh& mesh, uint32_t seed) {
  const float kSharpness[] = {0.25f, 0.5f, 0.9f, 1.0f, 1.3f, 2.0f, 2.6f, 10.0f};
  std::mt19937 rng(seed);
  const MeshTopology topo = buildTopology(mesh);
  for (Index e = 0; e < topo.edgeCount; ++e)
    if (rng() % 3 == 0)
      mesh.tags.creases.push_back({std::min(topo.edgeVerts[2 * e], topo.edgeVerts[2 * e + 1]),
                                   std::max(topo.edgeVerts[2 * e], topo.edgeVerts[2 * e + 1]), kSharpness[rng() % 8]});
  for (Index v = 1; v < mesh.vertexCount(); v += 7) mesh.tags.corners.push_back({v, kSharpness[rng() % 8]});
}

}  // namespace

TEST_CASE("opensubdiv oracle: semi-sharp and infinitely sharp creases and corners on a cube refine identically") {
  // Around the top face: sharpness 0.3 (decays at once), 1 (a full step), 1.5, 2.7; one vertical
  // edge infinitely sharp; a semi-sharp corner; the top face's vertices see 2 or 3 sharp edges.
  PolyMesh m = cube();
  const MeshTopology topo = buildTopology(m);
  const float sharpness[] = {0.3f, 1.0f, 1.5f, 2.7f, 10.0f};
  for (Index e = 0; e < 5; ++e)
    m.tags.creases.push_back({std::min(topo.edgeVerts[2 * e], topo.edgeVerts[2 * e + 1]),
                              std::max(topo.edgeVerts[2 * e], topo.edgeVerts[2 * e + 1]), sharpness[e]});
  m.tags.corners.push_back({6, 2.5});
  compareSharpWithOpenSubdiv("cube with creases", m);
}

TEST_CASE("opensubdiv oracle: random creases and corners on open and closed mixed meshes refine identically") {
  for (uint32_t seed : {11u, 12u, 13u, 18u}) {  // 18: the fractional weight sums three edges (order matters)
    PolyMesh torus = cellGrid(9, 6, true, true, seed);
    tagRandomly(torus, seed);
    compareSharpWithOpenSubdiv("closed mixed torus, random creases, seed " + std::to_string(seed), torus);
    PolyMesh open = cellGrid(7, 5, false, true, seed);
    tagRandomly(open, seed + 100);
    compareSharpWithOpenSubdiv("open mixed grid, random creases, seed " + std::to_string(seed), open);
  }
}

TEST_CASE("opensubdiv oracle: Chaikin creasing (creasemethod chaikin) refines identically") {
  // Chains of semi-sharp edges of differing sharpness, so each half's sharpness depends on its
  // neighbours at that end; one value above 1 whose halves may still decay (OpenSubdiv then blends
  // with a weight over 1).
  PolyMesh torus = cellGrid(9, 6, true, false, 31);
  const MeshTopology topo = buildTopology(torus);
  const float kSharpness[] = {0.5f, 1.25f, 2.0f, 3.5f, 1.0f, 0.75f};
  for (Index e = 0; e < topo.edgeCount; e += 2)
    torus.tags.creases.push_back({std::min(topo.edgeVerts[2 * e], topo.edgeVerts[2 * e + 1]),
                                  std::max(topo.edgeVerts[2 * e], topo.edgeVerts[2 * e + 1]), kSharpness[(e / 2) % 6]});
  torus.tags.creaseMethod = CreaseMethod::Chaikin;
  compareSharpWithOpenSubdiv("torus, Chaikin creases", torus);
  for (uint32_t seed : {41u, 42u, 71u}) {  // 42, 71: Chaikin sums three or more edges at a vertex
    PolyMesh open = cellGrid(7, 5, false, true, seed);
    tagRandomly(open, seed);
    open.tags.creaseMethod = CreaseMethod::Chaikin;
    compareSharpWithOpenSubdiv("open mixed grid, Chaikin, random creases, seed " + std::to_string(seed), open);
  }
}

TEST_CASE("opensubdiv oracle: interpolateboundary 1 (edge and corner) sharpens corners of one face") {
  PolyMesh grid = cellGrid(6, 4, false, false, 7);
  grid.tags.boundary = BoundaryInterpolation::EdgeAndCorner;
  compareSharpWithOpenSubdiv("open grid, edge-and-corner boundary", grid);
  PolyMesh tagged = cellGrid(7, 5, false, true, 21);
  tagRandomly(tagged, 21);
  tagged.tags.boundary = BoundaryInterpolation::EdgeAndCorner;
  compareSharpWithOpenSubdiv("open mixed grid, edge-and-corner boundary, random creases", tagged);
}

TEST_CASE("opensubdiv oracle: holes, and interpolateboundary 0 (boundary faces become holes), tag the same faces") {
  PolyMesh grid = cellGrid(6, 5, false, true, 5);
  grid.tags.holes = {3, 11, 12};
  compareSharpWithOpenSubdiv("open mixed grid, three holes", grid, false);
  PolyMesh none = cellGrid(7, 6, false, true, 8);
  none.tags.boundary = BoundaryInterpolation::None;
  compareSharpWithOpenSubdiv("open mixed grid, interpolateboundary 0", none, false);
  // A boundary edge tagged infinitely sharp keeps the faces at its ends (where no other boundary
  // edge is smooth) out of the holes; semi-sharp tags do not.
  PolyMesh tagged = cellGrid(7, 5, false, true, 13);
  tagRandomly(tagged, 13);
  tagged.tags.boundary = BoundaryInterpolation::None;
  tagged.tags.holes = {2, 9};
  compareSharpWithOpenSubdiv("open mixed grid, interpolateboundary 0, holes, random creases", tagged);
}

TEST_CASE("opensubdiv oracle: smoothtriangles smooth (TRI_SUB_SMOOTH) weighs triangles' face points as OpenSubdiv") {
  PolyMesh mixed = cellGrid(6, 5, false, true, 3);
  mixed.tags.triangles = TriangleSubdivision::Smooth;
  compareSharpWithOpenSubdiv("open mixed grid, smooth triangles", mixed);
  PolyMesh tagged = cellGrid(6, 6, true, true, 17);
  tagRandomly(tagged, 17);
  tagged.tags.triangles = TriangleSubdivision::Smooth;
  compareSharpWithOpenSubdiv("closed mixed grid, smooth triangles, random creases", tagged);
}

TEST_CASE("opensubdiv oracle: a closed cube refines identically") { compareWithOpenSubdiv("cube", cube()); }

TEST_CASE("opensubdiv oracle: a closed mesh of triangles, quads, pentagons and hexagons refines identically") {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const std::string name = "closed mixed torus seed " + std::to_string(seed);
    compareWithOpenSubdiv(name, cellGrid(9, 6, true, true, seed));
  }
}

TEST_CASE("opensubdiv oracle: an open quad grid with boundaries and corners refines identically") {
  compareWithOpenSubdiv("open grid 6x4", cellGrid(6, 4, false, false, 7));
}

TEST_CASE("opensubdiv oracle: an open mesh with triangles and n-gons refines identically") {
  for (uint32_t seed : {4u, 5u}) {
    const std::string name = "open mixed grid seed " + std::to_string(seed);
    compareWithOpenSubdiv(name, cellGrid(7, 5, false, true, seed));
  }
}

TEST_CASE("opensubdiv oracle: a valence-16 triangle-fan pole refines identically") {
  compareWithOpenSubdiv("open cap, valence-16 pole", poleMesh(16, 3, false));
  compareWithOpenSubdiv("globe, two valence-16 poles", poleMesh(16, 4, true));
}

// [SECTION] non-manifold meshes (manifold_split.h)

namespace {

// Refines a non-manifold `base` 1..kLevels times with both libraries: the same faces, and the merged
// points (Refinement::outputMesh) as OpenSubdiv's as point sets (the split numbers its own way),
// to round-off. Returns OpenSubdiv's vertex count less ours at the finest level (the two halves of
// an edge whose ends are one vertex are two vertices there, one here).
int compareSplitWithOpenSubdiv(const std::string& name, const PolyMesh& base) {
  CAPTURE(name);
  const std::unique_ptr<Far::TopologyRefiner> refiner = osdRefiner(base, kLevels);
  const Far::PrimvarRefinerReal<double> primvar(*refiner);
  const double scale = boundingDiagonal(base.points);
  std::vector<OsdPoint> osdPoints(base.vertexCount());
  for (Index v = 0; v < base.vertexCount(); ++v) osdPoints[v].p = base.points[v];
  int missing = 0;
  for (int level = 1; level <= kLevels; ++level) {
    CAPTURE(level);
    std::vector<OsdPoint> child(refiner->GetLevel(level).GetNumVertices());
    OsdPoint* dst = child.data();
    primvar.Interpolate(level, osdPoints.data(), dst);
    osdPoints = std::move(child);
    const Refinement ours(base, {Scheme::CatmullClark, level, false});
    REQUIRE(ours.splitInput());
    const PolyMesh merged = ours.outputMesh();
    CHECK(merged.faceCount() == refiner->GetLevel(level).GetNumFaces());
    std::vector<Point> theirs;
    for (const OsdPoint& p : osdPoints) theirs.push_back(p.p);
    const double distance = pointSetDistance(merged.points, theirs, 1e-9 * scale);
    MESSAGE(name, " level ", level, ": ", merged.vertexCount(), " vertices (OpenSubdiv ", theirs.size(),
            "), point sets ", distance, " apart");
    CHECK(distance <= 1e-12 * scale);
    missing = int(theirs.size()) - merged.vertexCount();
  }
  return missing;
}

}  // namespace

TEST_CASE("opensubdiv oracle: non-manifold meshes (fins, bow ties, repeated vertices, flipped faces) refine alike") {
  // Three quads of a grid's strip raised as fins on one edge, the grid jittered.
  PolyMesh fins = cellGrid(5, 4, false, false, 31);
  {
    const Index a = 8, b = 9;  // an interior edge of the grid
    const Index top = fins.vertexCount();
    fins.points.emplace_back(fins.points[a] + Point(0.1, 0.2, 1.0));
    fins.points.emplace_back(fins.points[b] + Point(-0.1, 0.1, 0.9));
    fins.points.emplace_back(fins.points[a] + Point(0.2, -0.3, -0.8));
    fins.points.emplace_back(fins.points[b] + Point(0.0, -0.2, -1.1));
    fins.addFace({a, b, top + 1, top});
    fins.addFace({b, a, top + 2, top + 3});
  }
  CHECK(compareSplitWithOpenSubdiv("grid with two fins on an interior edge", fins) == 0);
  {  // creases on every third face side, a corner on every fifth vertex (tagRandomly needs a manifold mesh)
    std::mt19937 rng(5);
    const float kSharpness[] = {0.5f, 1.0f, 2.6f, 10.0f};
    for (size_t c = 0; c < fins.faceVerts.size(); c += 3) {
      const Index f = Index(std::upper_bound(fins.faceStart.begin(), fins.faceStart.end(), Index(c)) - fins.faceStart.begin()) - 1;
      const Index a = fins.faceVerts[c], b = fins.faceVerts[Index(c) + 1 < fins.faceStart[f + 1] ? c + 1 : size_t(fins.faceStart[f])];
      fins.tags.creases.push_back({std::min(a, b), std::max(a, b), kSharpness[rng() % 4]});
    }
    std::sort(fins.tags.creases.begin(), fins.tags.creases.end(),
              [](const CreaseEdge& x, const CreaseEdge& y) { return x.v0 != y.v0 ? x.v0 < y.v0 : x.v1 < y.v1; });
    fins.tags.creases.erase(std::unique(fins.tags.creases.begin(), fins.tags.creases.end(),
                                        [](const CreaseEdge& x, const CreaseEdge& y) { return x.v0 == y.v0 && x.v1 == y.v1; }),
                            fins.tags.creases.end());
    for (Index v = 2; v < fins.vertexCount(); v += 5) fins.tags.corners.push_back({v, kSharpness[rng() % 4]});
  }
  CHECK(compareSplitWithOpenSubdiv("grid with fins, creases and corners", fins) == 0);

  // Three sheets on one line (an interior non-manifold crease through vertex 1), with a crease tag
  // on a sheet's edge at that vertex: three sharp edges there, Far's corner rule at every copy while
  // the tag lasts (infinitely sharp, semi-sharp 2 and 2.5).
  for (const double sharpness : {10.0, 2.0, 2.5}) {
    PolyMesh book;
    for (const Point& p : {Point(0, -1, 0), Point(0.1, 0.2, 0.3), Point(0, 1, 0), Point(1, -1, 0), Point(1, 0, 0), Point(1, 1, 0),
                           Point(-1, -1, 0), Point(-1, 0, 0), Point(-1, 1, 0), Point(0, -1, 1), Point(0, 0, 1), Point(0, 1, 1)})
      book.points.push_back(p);
    for (const auto& f : std::vector<std::vector<Index>>{{0, 1, 4, 3}, {1, 2, 5, 4}, {1, 0, 6, 7}, {2, 1, 7, 8}, {0, 1, 10, 9}, {1, 2, 11, 10}})
      book.addFace(f.data(), f.size());
    book.tags.creases.push_back({1, 4, sharpness});  // vertex 1: the line's middle
    CHECK(compareSplitWithOpenSubdiv("three sheets on a line, a tag at its vertex, sharpness " + std::to_string(sharpness), book) == 0);
  }

  // Two closed cones sharing their tip (a bow tie of closed fans).
  PolyMesh cones;
  for (const Point& p : {Point(0, 0, 0), Point(1, 0, 1), Point(0, 1, 1.2), Point(-1, -1, 1), Point(1, 0.1, -1), Point(0, 1, -1.1),
                         Point(-1, -1, -0.9)})
    cones.points.push_back(p);
  for (const auto& f : std::vector<std::vector<Index>>{{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}, {0, 5, 4}, {0, 6, 5}, {0, 4, 6}, {4, 5, 6}})
    cones.addFace(f.data(), f.size());
  CHECK(compareSplitWithOpenSubdiv("two cones touching at their tips", cones) == 0);

  // OpenSubdiv's quad pole: quads (a, b, p, p) around p, a degenerate edge each.
  PolyMesh quadPole;
  const int n = 7;
  quadPole.points.emplace_back(0, 0, 0.3);
  for (int r = 1; r <= 2; ++r)
    for (int j = 0; j < n; ++j) quadPole.points.emplace_back(r * std::cos(2 * kPi * j / n), r * std::sin(2 * kPi * j / n), 0.1 * r * (j % 3));
  auto q = [&](int r, int j) { return Index(1 + (r - 1) * n + (j % n)); };
  for (int j = 0; j < n; ++j) quadPole.addFace({q(1, j), q(1, j + 1), 0, 0});
  for (int j = 0; j < n; ++j) quadPole.addFace({q(2, j), q(2, j + 1), q(1, j + 1), q(1, j)});
  // OpenSubdiv keeps each degenerate edge, and the two halves of each at every level, apart (all at
  // p); the merged output keeps one vertex per position there: fewer vertices, the same points.
  CHECK(compareSplitWithOpenSubdiv("quads with a degenerate edge around a vertex", quadPole) > 0);

  // A face turned against its neighbours, and a face repeating a vertex across it.
  PolyMesh flipped = cellGrid(4, 4, false, true, 9);
  std::reverse(flipped.faceVerts.begin() + flipped.faceStart[5], flipped.faceVerts.begin() + flipped.faceStart[6]);
  CHECK(compareSplitWithOpenSubdiv("mixed grid with a flipped face", flipped) == 0);
  PolyMesh repeat = cellGrid(3, 3, false, false, 4);
  const Index extra = repeat.vertexCount();
  repeat.points.emplace_back(1.5, 1.5, 1.0);
  repeat.addFace({4, 5, 4, extra});  // runs 4-5 and back: an edge repeated in one face
  CHECK(compareSplitWithOpenSubdiv("grid with a face repeating a vertex", repeat) >= 0);
}

// [SECTION] OpenSubdiv's own regression shapes

TEST_CASE("opensubdiv oracle: OpenSubdiv's regression shapes, with their tags, refine alike (where the shapes are kept)") {
  // Read with their tags (support/osd_shapes.h).
  const std::filesystem::path dir = testing::osdShapeDirectory(POLARVIEW_OSD_SHAPES);
  const std::vector<std::filesystem::path> files = testing::osdShapeFiles(dir);
  if (files.empty()) {
    MESSAGE("OpenSubdiv's regression shapes not found at ", dir.string(), ": skipped");
    return;
  }
  constexpr int kShapeLevels = 3;
  size_t compared = 0, split = 0;
  double worst = 0.0;
  for (const std::filesystem::path& file : files) {
    CAPTURE(file.string());
    const PolyMesh mesh = parseObjText(testing::osdShapeText(file, true), file.filename().string());
    const std::unique_ptr<Far::TopologyRefiner> refiner = osdRefiner(mesh, kShapeLevels);
    const Far::PrimvarRefinerReal<double> primvar(*refiner);
    std::vector<OsdPoint> points(mesh.vertexCount());
    for (Index v = 0; v < mesh.vertexCount(); ++v) points[v].p = mesh.points[v];
    for (int level = 1; level <= kShapeLevels; ++level) {
      std::vector<OsdPoint> child(refiner->GetLevel(level).GetNumVertices());
      OsdPoint* dst = child.data();
      primvar.Interpolate(level, points.data(), dst);
      points = std::move(child);
    }
    const Refinement ours(mesh, {Scheme::CatmullClark, kShapeLevels, false});
    const PolyMesh merged = ours.outputMesh();
    CHECK(merged.faceCount() == refiner->GetLevel(kShapeLevels).GetNumFaces());
    std::vector<Point> theirs;
    for (const OsdPoint& p : points) theirs.push_back(p.p);
    const double scale = boundingDiagonal(mesh.points);
    const double distance = pointSetDistance(merged.points, theirs, 1e-9 * scale) / scale;
    CHECK(distance <= 1e-12);
    worst = std::max(worst, distance);
    ++compared;
    split += ours.splitInput();
  }
  MESSAGE(compared, " shapes (", split, " non-manifold) at level ", kShapeLevels,
          ": largest distance to OpenSubdiv's points ", worst, " of the shape's size");
  CHECK(compared == files.size());
}
