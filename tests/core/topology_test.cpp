// Topology tables: counts, incidence consistency, rotational order, boundaries, manifold errors.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <random>

#include "core/mesh/constants.h"
#include "core/mesh/shapes.h"
#include "core/mesh/input_error.h"
#include "core/mesh/topology.h"

using namespace polarview;

namespace {

// nu x nv quads over a periodic or open parameter grid; `wrapU`/`wrapV` glue opposite sides.
PolyMesh quadGrid(int nu, int nv, bool wrapU, bool wrapV) {
  PolyMesh m;
  const int cu = wrapU ? nu : nu + 1, cv = wrapV ? nv : nv + 1;
  for (int j = 0; j < cv; ++j)
    for (int i = 0; i < cu; ++i) {
      const double u = 2 * kPi * i / nu, v = 2 * kPi * j / nv;
      m.points.push_back(wrapU && wrapV ? Point((2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v))
                                        : Point(i, j, 0));
    }
  auto id = [&](int i, int j) { return Index((j % cv) * cu + (i % cu)); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) m.addFace({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return m;
}

using polarview::shapes::cube;  // the unit cube, eight valence-3 vertices

// UV sphere: n-valent triangle fans at both poles, `rings` latitude rings of n vertices.
PolyMesh uvSphere(int n, int rings) {
  PolyMesh m;
  m.points.emplace_back(0, 0, 1);
  for (int r = 1; r <= rings; ++r)
    for (int j = 0; j < n; ++j) {
      const double t = kPi * r / (rings + 1), a = 2 * kPi * j / n;
      m.points.emplace_back(std::sin(t) * std::cos(a), std::sin(t) * std::sin(a), std::cos(t));
    }
  m.points.emplace_back(0, 0, -1);
  const Index south = m.vertexCount() - 1;
  auto q = [&](int r, int j) { return Index(1 + (r - 1) * n + (j % n)); };
  for (int j = 0; j < n; ++j) m.addFace({0, q(1, j), q(1, j + 1)});
  for (int r = 1; r < rings; ++r)
    for (int j = 0; j < n; ++j) m.addFace({q(r, j), q(r + 1, j), q(r + 1, j + 1), q(r, j + 1)});
  for (int j = 0; j < n; ++j) m.addFace({south, q(rings, j + 1), q(rings, j)});
  return m;
}

// Every invariant topology.h promises, checked table against table.
void checkTablesConsistent(const PolyMesh& m, const MeshTopology& t) {
  REQUIRE(t.vertexCount == m.vertexCount());
  REQUIRE(t.faceCount == m.faceCount());
  // Corners: edge from this corner's vertex to the next one; the face is one of the edge's faces.
  for (Index f = 0; f < m.faceCount(); ++f)
    for (Index i = 0; i < m.faceSize(f); ++i) {
      const Index c = m.faceStart[f] + i, e = t.cornerEdge[c];
      const Index a = m.face(f)[i], b = m.face(f)[(i + 1) % m.faceSize(f)];
      REQUIRE(t.cornerFace[c] == f);
      REQUIRE(((t.edgeVerts[2 * e] == a && t.edgeVerts[2 * e + 1] == b) || (t.edgeVerts[2 * e] == b && t.edgeVerts[2 * e + 1] == a)));
      REQUIRE((t.edgeFaces[2 * e] == f || t.edgeFaces[2 * e + 1] == f));
    }
  // Valences: sum of vertex valences is twice the edge count; faces per vertex sum to corners.
  long valenceSum = 0;
  for (Index v = 0; v < t.vertexCount; ++v) valenceSum += t.valence(v);
  CHECK(valenceSum == 2L * t.edgeCount);
  CHECK(t.vertexFaceStart.back() == Index(m.faceVerts.size()));
  // Rings: face i lies between edges i and i+1 (edge i leaves v along face i's loop).
  for (Index v = 0; v < t.vertexCount; ++v) {
    const Index nf = t.faceValence(v), ne = t.valence(v);
    REQUIRE(t.vertexUsed[v] == (nf > 0));
    if (nf == 0) continue;
    REQUIRE(ne == nf + (t.vertexOnBoundary[v] ? 1 : 0));
    const Index* faces = t.vertexFaces.data() + t.vertexFaceStart[v];
    const Index* corners = t.vertexCorners.data() + t.vertexFaceStart[v];
    const Index* edges = t.vertexEdges.data() + t.vertexEdgeStart[v];
    for (Index i = 0; i < nf; ++i) {
      REQUIRE(m.faceVerts[corners[i]] == v);
      REQUIRE(t.cornerFace[corners[i]] == faces[i]);
      REQUIRE(t.cornerEdge[corners[i]] == edges[i]);  // outgoing edge of face i
      const Index next = edges[(i + 1) % ne];
      // The next edge is face i's incoming edge at v, so consecutive faces share it.
      REQUIRE((t.edgeFaces[2 * next] == faces[i] || t.edgeFaces[2 * next + 1] == faces[i]));
      if (i + 1 < nf) REQUIRE((t.edgeFaces[2 * next] == faces[i + 1] || t.edgeFaces[2 * next + 1] == faces[i + 1]));
    }
    if (t.vertexOnBoundary[v]) {
      CHECK(t.edgeOnBoundary(edges[0]));
      CHECK(t.edgeOnBoundary(edges[ne - 1]));
      for (Index i = 1; i + 1 < ne; ++i) CHECK_FALSE(t.edgeOnBoundary(edges[i]));
    }
  }
}

// Number of closed loops the boundary edges form (each boundary vertex has exactly two).
int boundaryLoopCount(const MeshTopology& t) {
  std::vector<uint8_t> seen(t.edgeCount, 0);
  int loops = 0;
  for (Index e0 = 0; e0 < t.edgeCount; ++e0) {
    if (!t.edgeOnBoundary(e0) || seen[e0]) continue;
    ++loops;
    Index e = e0, v = t.edgeVerts[2 * e0 + 1];
    while (!seen[e]) {
      seen[e] = 1;
      const Index* edges = t.vertexEdges.data() + t.vertexEdgeStart[v];
      e = edges[0] == e ? edges[t.valence(v) - 1] : edges[0];  // the other boundary edge at v
      v = t.otherEnd(e, v);
    }
  }
  return loops;
}

// Builds `m` (with face lines 10, 20, ...) expecting an InputError on `line` mentioning `words`.
void checkRejected(PolyMesh m, int line, const char* words) {
  m.faceLine.clear();
  for (Index f = 0; f < m.faceCount(); ++f) m.faceLine.push_back(10 * (f + 1));
  try {
    buildTopology(m, "t.obj");
    FAIL("accepted a mesh that should fail with: ", words);
  } catch (const InputError& e) {
    CAPTURE(e.what());
    CHECK(e.file() == "t.obj");
    CHECK(e.line() == line);
    CHECK(std::string(e.what()).find(words) != std::string::npos);
  }
}

PolyMesh withPoints(int n) {
  PolyMesh m;
  for (int i = 0; i < n; ++i) m.points.emplace_back(i, i * i % 7, i % 3);
  return m;
}

}  // namespace

TEST_CASE("topology: closed meshes satisfy Euler's formula and have no boundary") {
  struct Closed {
    const char* name;
    PolyMesh mesh;
    int euler;
  };
  const Closed meshes[] = {{"cube", cube(), 2},
                           {"uv sphere 5x3", uvSphere(5, 3), 2},
                           {"uv sphere 16x7", uvSphere(16, 7), 2},
                           {"torus 3x3", quadGrid(3, 3, true, true), 0},
                           {"torus 12x7", quadGrid(12, 7, true, true), 0}};
  for (const Closed& c : meshes) {
    CAPTURE(c.name);
    const MeshTopology t = buildTopology(c.mesh);
    checkTablesConsistent(c.mesh, t);
    CHECK(t.vertexCount - t.edgeCount + t.faceCount == c.euler);
    for (Index e = 0; e < t.edgeCount; ++e) CHECK_FALSE(t.edgeOnBoundary(e));
    CHECK(boundaryLoopCount(t) == 0);
  }
  const MeshTopology sphere = buildTopology(uvSphere(16, 7));
  CHECK(sphere.valence(0) == 16);
}

TEST_CASE("topology: an open grid has one boundary loop through its 2(nu+nv) boundary edges") {
  for (auto [nu, nv] : {std::pair{1, 1}, {3, 2}, {8, 5}}) {
    const PolyMesh m = quadGrid(nu, nv, false, false);
    const MeshTopology t = buildTopology(m);
    checkTablesConsistent(m, t);
    int boundaryEdges = 0;
    for (Index e = 0; e < t.edgeCount; ++e) boundaryEdges += t.edgeOnBoundary(e);
    CHECK(boundaryEdges == 2 * (nu + nv));
    CHECK(boundaryLoopCount(t) == 1);
    CHECK(t.vertexCount - t.edgeCount + t.faceCount == 1);
    // Grid corners are valence-2 boundary vertices with one face.
    CHECK(t.faceValence(0) == 1);
    CHECK(t.valence(0) == 2);
  }
  // A cylinder (wrapped in u only) has two boundary loops.
  const MeshTopology cylinder = buildTopology(quadGrid(6, 3, true, false));
  CHECK(boundaryLoopCount(cylinder) == 2);
  CHECK(cylinder.vertexCount - cylinder.edgeCount + cylinder.faceCount == 0);
}

TEST_CASE("topology: tables do not depend on face order or vertex labels") {
  const PolyMesh base = uvSphere(9, 4);
  const MeshTopology baseTopo = buildTopology(base);
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Index> label(base.vertexCount()), order(base.faceCount());
    std::iota(label.begin(), label.end(), 0);
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(label.begin(), label.end(), rng);
    std::shuffle(order.begin(), order.end(), rng);
    PolyMesh m;
    m.points.resize(base.points.size());
    for (Index v = 0; v < base.vertexCount(); ++v) m.points[label[v]] = base.points[v];
    for (Index f : order) {
      std::vector<Index> loop;
      const Index k = base.faceSize(f), shift = Index(rng() % k);  // also rotate the loop's start
      for (Index i = 0; i < k; ++i) loop.push_back(label[base.face(f)[(i + shift) % k]]);
      m.addFace(loop.data(), loop.size());
    }
    const MeshTopology t = buildTopology(m);
    checkTablesConsistent(m, t);
    CHECK(t.edgeCount == baseTopo.edgeCount);
    for (Index v = 0; v < base.vertexCount(); ++v) CHECK(t.valence(label[v]) == baseTopo.valence(v));
  }
}

TEST_CASE("topology: unused vertices are kept and flagged") {
  PolyMesh m = withPoints(5);
  m.addFace({0, 1, 2});
  const MeshTopology t = buildTopology(m);
  checkTablesConsistent(m, t);
  CHECK(t.vertexUsed == std::vector<uint8_t>{1, 1, 1, 0, 0});
  CHECK(t.valence(4) == 0);
}

TEST_CASE("topology: each non-manifold or malformed mesh is rejected at its face's line") {
  SUBCASE("face with two vertices") {
    PolyMesh m = withPoints(4);
    m.addFace({0, 1, 2});
    m.addFace({2, 3});
    checkRejected(m, 20, "2 vertices");
  }
  SUBCASE("vertex repeated in one face") {
    PolyMesh m = withPoints(4);
    m.addFace({0, 1, 2, 1});
    checkRejected(m, 10, "repeats");
  }
  SUBCASE("index out of range") {
    PolyMesh m = withPoints(3);
    m.addFace({0, 1, 2});
    m.addFace({0, 2, 7});
    checkRejected(m, 20, "out of range");
  }
  SUBCASE("edge shared by three faces") {
    PolyMesh m = withPoints(5);
    m.addFace({0, 1, 2});
    m.addFace({1, 0, 3});
    m.addFace({1, 0, 4});
    checkRejected(m, 30, "non-manifold edge (v 1 - v 2) shared by 3 faces");
  }
  SUBCASE("two faces run an edge the same way") {
    PolyMesh m = withPoints(4);
    m.addFace({0, 1, 2});
    m.addFace({0, 1, 3});
    checkRejected(m, 20, "inconsistent orientation");
  }
  SUBCASE("duplicate face with the same orientation") {
    PolyMesh m = withPoints(5);
    m.addFace({0, 1, 2, 3});
    m.addFace({0, 3, 4});
    m.addFace({2, 3, 0, 1});
    checkRejected(m, 30, "inconsistent orientation");
  }
  SUBCASE("two open fans meeting at a vertex (bow tie)") {
    PolyMesh m = withPoints(5);
    m.addFace({0, 1, 2});
    m.addFace({0, 3, 4});
    checkRejected(m, 20, "non-manifold vertex v 1");
  }
  SUBCASE("two closed cones touching at their tips") {
    // Two closed triangle cones (tip 0), each capped by a triangle; vertex 0 has two closed fans.
    PolyMesh m = withPoints(7);
    m.addFace({0, 1, 2});
    m.addFace({0, 2, 3});
    m.addFace({0, 3, 1});
    m.addFace({1, 3, 2});
    m.addFace({0, 4, 5});
    m.addFace({0, 5, 6});
    m.addFace({0, 6, 4});
    m.addFace({4, 6, 5});
    checkRejected(m, 50, "non-manifold vertex v 1");
  }
  SUBCASE("an open fan and a closed fan at one vertex") {
    PolyMesh m = withPoints(7);
    m.addFace({0, 1, 2});
    m.addFace({0, 2, 3});
    m.addFace({0, 3, 1});
    m.addFace({1, 3, 2});
    m.addFace({0, 4, 5});
    checkRejected(m, 10, "non-manifold vertex v 1");
  }
}

TEST_CASE("topology: random face soups are either rejected cleanly or give consistent tables") {
  std::mt19937 rng(99);
  int accepted = 0, rejected = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int vertices = 3 + int(rng() % 6), faces = 1 + int(rng() % 8);
    PolyMesh m = withPoints(vertices);
    for (int f = 0; f < faces; ++f) {
      // Mostly triangles and quads; rarely a 2-gon or an index out of range.
      std::vector<Index> loop(rng() % 50 == 0 ? 2 : 3 + rng() % 2);
      for (Index& v : loop) v = Index(rng() % 100 == 0 ? vertices : rng() % vertices);
      m.addFace(loop.data(), loop.size());
    }
    try {
      const MeshTopology t = buildTopology(m);
      checkTablesConsistent(m, t);
      ++accepted;
    } catch (const InputError&) {
      ++rejected;
    }
  }
  MESSAGE("random face soups: ", accepted, " accepted, ", rejected, " rejected");
  CHECK(accepted > 50);
  CHECK(rejected > 50);
}

TEST_CASE("topology: without OBJ lines the error names the face") {
  PolyMesh m = withPoints(4);
  m.addFace({0, 1, 2});
  m.addFace({0, 1, 3});
  try {
    buildTopology(m, "gen");
    FAIL("accepted an inconsistently oriented mesh");
  } catch (const InputError& e) {
    CHECK(e.line() == 0);
    CHECK(std::string(e.what()).find("gen: face 2: inconsistent orientation") == 0);
  }
}

TEST_CASE("topology: a million-corner mesh builds in near-linear time") {
  const PolyMesh m = quadGrid(500, 500, true, true);
  const auto start = std::chrono::steady_clock::now();
  const MeshTopology t = buildTopology(m);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  MESSAGE("topology of 250k quads (1M corners) in ", seconds, " s");
  CHECK(t.edgeCount == 2 * 500 * 500);
  CHECK(t.vertexCount - t.edgeCount + t.faceCount == 0);
}
