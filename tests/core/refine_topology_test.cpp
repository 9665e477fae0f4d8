// Derived child connectivity (refine_topology.h) equals the connectivity rebuilt from scratch:
// refineCatmullClarkTopology (+ the diagonal splits C2PS makes) followed by buildTopology, table by
// table, over closed, open, mixed n-gon and polar meshes, levels 1-3, with and without splits.
#include <doctest/doctest.h>

#include <random>
#include <string>

#include "core/mesh/shapes.h"
#include "core/mesh/topology.h"
#include "core/subdiv/catmull_clark.h"
#include "core/subdiv/polar_config.h"
#include "core/subdiv/refine_topology.h"
#include "core/subdiv/refiner.h"
#include "core/spline/patch_extraction.h"
#include <stdexcept>
#include "support/reference_catmull_clark.h"

using namespace polarview;

namespace {

// Which parent corners to split: none, those at refinable poles (as C2PS does), or those at
// random vertices (any child quad may be split, so this stresses every ring shape).
enum class Splits { None, Poles, RandomVertices };

std::vector<uint8_t> chooseSplits(const PolyMesh& mesh, const MeshTopology& topo, Splits splits, unsigned seed) {
  std::vector<uint8_t> split(mesh.faceVerts.size(), 0);
  std::vector<uint8_t> vertexSplits(topo.vertexCount, 0);
  if (splits == Splits::Poles) {
    for (const PolarConfig& config : findPolarConfigs(mesh, topo))
      if (config.refinable) vertexSplits[config.pole] = 1;
  } else if (splits == Splits::RandomVertices) {
    std::mt19937 rng(seed);
    for (Index v = 0; v < topo.vertexCount; ++v) vertexSplits[v] = rng() % 3 == 0;
  }
  for (size_t c = 0; c < split.size(); ++c) split[c] = vertexSplits[mesh.faceVerts[c]];
  return split;
}

// The reference child: Catmull-Clark quads, marked quads split into (V, E_a, F), (V, F, E_b).
PolyMesh referenceChild(const PolyMesh& parent, const MeshTopology& topo, const std::vector<uint8_t>& split,
                        std::vector<Index>& faceParent) {
  std::vector<Index> quadParent;
  PolyMesh quads = reference::refineCatmullClarkTopology(parent, topo, &quadParent);
  PolyMesh child;
  child.points.resize(quads.points.size());
  faceParent.clear();
  for (Index f = 0; f < quads.faceCount(); ++f) {
    const Index* v = quads.face(f);
    if (split[f]) {
      child.addFace({v[0], v[1], v[2]});
      child.addFace({v[0], v[2], v[3]});
      faceParent.push_back(quadParent[f]);
    } else {
      child.addFace(v, 4);
    }
    faceParent.push_back(quadParent[f]);
  }
  return child;
}

void requireSameTopology(const MeshTopology& derived, const MeshTopology& rebuilt) {
  REQUIRE(derived.vertexCount == rebuilt.vertexCount);
  REQUIRE(derived.edgeCount == rebuilt.edgeCount);
  REQUIRE(derived.faceCount == rebuilt.faceCount);
  CHECK(derived.cornerEdge == rebuilt.cornerEdge);
  CHECK(derived.cornerFace == rebuilt.cornerFace);
  CHECK(derived.edgeVerts == rebuilt.edgeVerts);
  CHECK(derived.edgeFaces == rebuilt.edgeFaces);
  CHECK(derived.vertexFaceStart == rebuilt.vertexFaceStart);
  CHECK(derived.vertexFaces == rebuilt.vertexFaces);
  CHECK(derived.vertexEdgeStart == rebuilt.vertexEdgeStart);
  CHECK(derived.vertexEdges == rebuilt.vertexEdges);
  CHECK(derived.vertexCorners == rebuilt.vertexCorners);
  CHECK(derived.vertexOnBoundary == rebuilt.vertexOnBoundary);
  CHECK(derived.vertexUsed == rebuilt.vertexUsed);
}

// Refines `base` three times both ways (the derived one on `threads` threads) and compares every
// level's mesh, parents, tables and corner links.
void checkDerivedEqualsRebuilt(const std::string& name, const PolyMesh& base, Splits splits, unsigned threads) {
  PolyMesh mesh = base;
  MeshTopology topo = buildTopology(mesh);
  std::vector<Index> links = cornerLinks(mesh, topo);
  RefinedConnectivity out;
  for (int level = 1; level <= 3; ++level) {
    CAPTURE(name);
    CAPTURE(level);
    CAPTURE(int(splits));
    CAPTURE(threads);
    const std::vector<uint8_t> split = chooseSplits(mesh, topo, splits, unsigned(level * 7919 + mesh.faceCount()));
    std::vector<Index> faceParent;
    PolyMesh reference = referenceChild(mesh, topo, split, faceParent);
    ConnectivityOptions options;
    options.threads = threads;
    options.childLinks = level < 3;  // the finest level needs none
    refineCatmullClarkConnectivity(mesh, topo, links, splits == Splits::None ? nullptr : &split, out, options);

    REQUIRE(out.mesh.points.size() == reference.points.size());
    CHECK(out.mesh.faceStart == reference.faceStart);
    CHECK(out.mesh.faceVerts == reference.faceVerts);
    CHECK(out.faceParent == faceParent);
    const MeshTopology rebuilt = buildTopology(reference);
    requireSameTopology(out.topology, rebuilt);
    if (options.childLinks)
      CHECK(out.links == cornerLinks(reference, rebuilt));
    else
      CHECK(out.links.empty());

    // Lean steps (a finest level): without the rings, or with the faces only (OpenSubdiv's minimal
    // last level, no edges and so no links). Each has the full step's faces, parents, counts and
    // vertex flags, no rings (faces only: no edges either); completed, every table of the full
    // step, its points and links as they were.
    for (bool edges : {true, false}) {
      CAPTURE(edges);
      ConnectivityOptions lean = options;
      lean.vertexRings = false;
      lean.edges = edges;
      lean.childLinks = edges && options.childLinks;
      RefinedConnectivity child;
      refineCatmullClarkConnectivity(mesh, topo, links, splits == Splits::None ? nullptr : &split, child, lean);
      CHECK(child.mesh.faceStart == reference.faceStart);
      CHECK(child.mesh.faceVerts == reference.faceVerts);
      CHECK(child.faceParent == faceParent);
      CHECK(child.topology.vertexCount == rebuilt.vertexCount);
      CHECK(child.topology.edgeCount == rebuilt.edgeCount);
      CHECK(child.topology.faceCount == rebuilt.faceCount);
      CHECK(child.topology.vertexOnBoundary == rebuilt.vertexOnBoundary);
      CHECK(child.topology.vertexUsed == rebuilt.vertexUsed);
      CHECK(child.topology.vertexFaces.empty());
      CHECK(child.topology.vertexEdgeStart.empty());
      CHECK(child.topology.cornerEdge == (edges ? rebuilt.cornerEdge : std::vector<Index>{}));
      CHECK(child.topology.edgeFaces == (edges ? rebuilt.edgeFaces : std::vector<Index>{}));
      CHECK(child.links == (lean.childLinks ? out.links : std::vector<Index>{}));
      for (size_t v = 0; v < child.mesh.points.size(); ++v) child.mesh.points[v] = Point(double(v), 1.0, -2.0);
      const std::vector<Point> marked = child.mesh.points;
      const std::vector<Index> leanLinks = child.links;
      completeChildTopology(mesh, topo, links, splits == Splits::None ? nullptr : &split, child, lean);
      requireSameTopology(child.topology, rebuilt);
      CHECK(child.mesh.faceVerts == reference.faceVerts);
      CHECK(child.faceParent == faceParent);
      CHECK(child.mesh.points == marked);
      CHECK(child.links == leanLinks);
    }
    // Faces only cannot give the links or rings, which need the edges.
    ConnectivityOptions noEdges = options;
    noEdges.edges = false;
    RefinedConnectivity refused;
    CHECK_THROWS_AS(refineCatmullClarkConnectivity(mesh, topo, links, splits == Splits::None ? nullptr : &split, refused, noEdges),
                    std::logic_error);

    mesh = out.mesh;
    topo = out.topology;
    links = out.links;
  }
}

// Opposite half-edges join the same two vertices in opposite directions, on the edge's two faces;
// the corner after the twin sits at the corner's own vertex.
void checkLinksAreOppositeHalfEdges(const PolyMesh& mesh, const MeshTopology& topo, const std::vector<Index>& links) {
  auto next = [&](Index c) { Index f = topo.cornerFace[c]; return c + 1 == mesh.faceStart[f + 1] ? mesh.faceStart[f] : c + 1; };
  REQUIRE(links.size() == 2 * mesh.faceVerts.size());
  for (Index c = 0; c < Index(mesh.faceVerts.size()); ++c) {
    const Index t = links[2 * c], e = topo.cornerEdge[c];
    if (t < 0) {
      CHECK(topo.edgeOnBoundary(e));
      CHECK(links[2 * c + 1] == -1);
      continue;
    }
    CHECK(links[2 * t] == c);
    CHECK(topo.cornerEdge[t] == e);
    CHECK(mesh.faceVerts[t] == mesh.faceVerts[next(c)]);
    CHECK(mesh.faceVerts[next(t)] == mesh.faceVerts[c]);
    CHECK(links[2 * c + 1] == next(t));
  }
}

// A closed n-gonal prism: two n-gon caps and n quads.
PolyMesh prism(int n) {
  PolyMesh m;
  for (int j = 0; j < n; ++j) m.points.emplace_back(std::cos(6.283185307179586 * j / n), std::sin(6.283185307179586 * j / n), 0.0);
  for (int j = 0; j < n; ++j) m.points.emplace_back(m.points[j].x, m.points[j].y, 1.0);
  std::vector<Index> bottom, top;
  for (int j = 0; j < n; ++j) {
    bottom.push_back(Index(n - 1 - j));
    top.push_back(Index(n + j));
    m.addFace({Index(j), Index((j + 1) % n), Index(n + (j + 1) % n), Index(n + j)});
  }
  m.addFace(bottom.data(), bottom.size());
  m.addFace(top.data(), top.size());
  return m;
}

// An open disc of mixed faces: a hexagon in the middle, a ring of alternating triangles and
// pentagon-like quads+triangles, plus a vertex no face uses.
PolyMesh mixedDisc() {
  PolyMesh m;
  const int n = 6;
  for (int j = 0; j < n; ++j) m.points.emplace_back(std::cos(6.283185307179586 * j / n), std::sin(6.283185307179586 * j / n), 0.0);
  for (int j = 0; j < 2 * n; ++j)
    m.points.emplace_back(2 * std::cos(3.141592653589793 * j / n), 2 * std::sin(3.141592653589793 * j / n), 0.1 * j);
  m.points.emplace_back(9.0, 9.0, 9.0);  // unused
  std::vector<Index> hexagon;
  for (int j = 0; j < n; ++j) hexagon.push_back(Index(j));
  m.addFace(hexagon.data(), hexagon.size());
  auto outer = [&](int k) { return Index(n + (k % (2 * n))); };
  for (int j = 0; j < n; ++j) {
    const Index a = Index(j), b = Index((j + 1) % n);
    if (j % 2 == 0) {
      m.addFace({a, outer(2 * j), outer(2 * j + 1), outer(2 * j + 2), b});  // pentagon
    } else {
      m.addFace({a, outer(2 * j), outer(2 * j + 1)});
      m.addFace({a, outer(2 * j + 1), outer(2 * j + 2), b});
    }
  }
  return m;
}

// A regular grid whose quads are randomly cut into triangles (either diagonal).
PolyMesh randomlyTriangulatedGrid(int nu, int nv, unsigned seed) {
  PolyMesh grid = shapes::grid(nu, nv);
  PolyMesh m;
  m.points = grid.points;
  std::mt19937 rng(seed);
  for (Index f = 0; f < grid.faceCount(); ++f) {
    const Index* q = grid.face(f);
    switch (rng() % 3) {
      case 0: m.addFace(q, 4); break;
      case 1: m.addFace({q[0], q[1], q[2]}); m.addFace({q[0], q[2], q[3]}); break;
      default: m.addFace({q[0], q[1], q[3]}); m.addFace({q[1], q[2], q[3]}); break;
    }
  }
  return m;
}

std::vector<std::pair<std::string, PolyMesh>> testMeshes() {
  return {{"cube", shapes::cube()},
          {"mushroom", shapes::mushroom(12)},
          {"mushroom-8", shapes::mushroom(8)},
          {"globe", shapes::globe(7, 4)},
          {"cap", shapes::polarCap(5, 3)},
          {"torus", shapes::torus(6, 5)},
          {"open grid", shapes::grid(4, 3)},
          {"prism", prism(5)},
          {"mixed disc", mixedDisc()},
          {"triangulated grid", randomlyTriangulatedGrid(5, 4, 11)}};
}

// A cube with a crease and a corner (their sharpness decays through the child's rings).
PolyMesh creasedCube() {
  PolyMesh mesh = shapes::cube();
  mesh.tags.creases.push_back({mesh.faceVerts[0], mesh.faceVerts[1], 2.0});
  mesh.tags.corners.push_back({mesh.faceVerts[2], 3.0});
  return mesh;
}

}  // namespace

// 1 thread, and 2, 3, 7 threads whose parts meet at arbitrary faces and vertices.
constexpr unsigned kThreadCounts[] = {1, 2, 3, 7};

TEST_CASE("derived Catmull-Clark connectivity equals buildTopology's tables at levels 1-3, on any thread count") {
  for (unsigned threads : kThreadCounts)
    for (const auto& [name, mesh] : testMeshes()) checkDerivedEqualsRebuilt(name, mesh, Splits::None, threads);
}

TEST_CASE("derived connectivity with C2PS's pole splits equals the rebuilt one, on any thread count") {
  for (unsigned threads : kThreadCounts)
    for (const auto& [name, mesh] : testMeshes()) checkDerivedEqualsRebuilt(name, mesh, Splits::Poles, threads);
}

TEST_CASE("derived connectivity with splits at random vertices (boundary ones too) equals the rebuilt one") {
  for (unsigned threads : kThreadCounts)
    for (const auto& [name, mesh] : testMeshes()) checkDerivedEqualsRebuilt(name, mesh, Splits::RandomVertices, threads);
}

TEST_CASE("corner links name the opposite half-edge of each interior edge and its successor, -1 on the boundary") {
  for (const auto& [name, mesh] : testMeshes()) {
    const std::string& meshName = name;  // C++17 lambdas (CAPTURE) cannot capture a structured binding
    CAPTURE(meshName);
    const MeshTopology topo = buildTopology(mesh);
    checkLinksAreOppositeHalfEdges(mesh, topo, cornerLinks(mesh, topo));
  }
}

TEST_CASE("Catmull-Clark points are bit-identical on 1, 2, 3 and 7 threads") {
  for (const auto& [name, base] : testMeshes()) {
    const std::string& meshName = name;  // C++17 lambdas (CAPTURE) cannot capture a structured binding
    CAPTURE(meshName);
    PolyMesh mesh = base;
    for (int level = 1; level <= 3; ++level) {
      const MeshTopology topo = buildTopology(mesh);
      std::vector<Point> serial(ccChildVertexCount(topo));
      computeCatmullClarkPoints(topo, mesh, mesh.points.data(), serial.data(), 1);
      for (unsigned threads : {2u, 3u, 7u}) {
        std::vector<Point> parallel(serial.size(), Point(-1.0));
        computeCatmullClarkPoints(topo, mesh, mesh.points.data(), parallel.data(), threads);
        for (size_t v = 0; v < serial.size(); ++v) REQUIRE(parallel[v] == serial[v]);
      }
      PolyMesh child = reference::refineCatmullClarkTopology(mesh, topo, nullptr);
      child.points = serial;
      mesh = std::move(child);
    }
  }
}

TEST_CASE("a refinement with the finest level's faces only: same faces, points and tags; tables made on demand equal the full ones") {
  const std::vector<std::pair<std::string, PolyMesh>> meshes = {
      {"mushroom", shapes::mushroom(12)}, {"cap", shapes::polarCap(5, 3)}, {"open grid", shapes::grid(4, 3)}, {"creased cube", creasedCube()}};
  // One level: completed from the base mesh's links; more: from links made on completion (the
  // level below a faces-only one is made without them).
  for (const auto& [name, mesh] : meshes)
    for (Scheme scheme : {Scheme::CatmullClark, Scheme::C2PS, Scheme::RTS})
      for (int levels : {1, 3}) {
        CAPTURE(name);
        CAPTURE(int(scheme));
        CAPTURE(levels);
        RefineOptions options{scheme, levels};
        const Refinement full(mesh, options);
        options.fullFinestTopology = false;
        Refinement lazy(mesh, options);
        const RefinedLevel &a = full.finest(), &b = lazy.finest();
        CHECK(b.mesh.faceVerts == a.mesh.faceVerts);
        CHECK(b.mesh.points == a.mesh.points);
        CHECK(b.faceParent == a.faceParent);
        CHECK(b.topology.edgeCount == a.topology.edgeCount);
        // RTS refines the cap radially, creases decay through the rings: both keep every table.
        if (!lazy.radialOnly() && mesh.tags.creases.empty()) {
          CHECK_FALSE(lazy.finestTopologyComplete());
          CHECK(b.topology.edgeVerts.empty());
          CHECK(b.topology.vertexFaces.empty());
          CHECK_THROWS_AS(extractPatches(lazy), std::logic_error);
        }
        lazy.completeFinestTopology();
        CHECK(lazy.finestTopologyComplete());
        requireSameTopology(b.topology, a.topology);
        const PatchSet fromFull = extractPatches(full), fromLazy = extractPatches(lazy);
        REQUIRE(fromLazy.patches.size() == fromFull.patches.size());
        for (size_t k = 0; k < fromFull.patches.size(); ++k) CHECK(fromLazy.patches[k].cp == fromFull.patches[k].cp);
      }
}
