// Non-manifold meshes split into manifold ones with OpenSubdiv's sharpening (manifold_split.h).
// The points against OpenSubdiv itself: tests/osd/osd_oracle_test.cpp.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "core/mesh/manifold_split.h"
#include "core/mesh/shapes.h"
#include "core/mesh/topology.h"
#include "core/subdiv/refiner.h"

using namespace polarview;

namespace {

PolyMesh withPoints(int count) {
  PolyMesh m;
  for (int i = 0; i < count; ++i) m.points.emplace_back(0.3 * i, 0.7 * (i % 3), 0.2 * (i * i % 5));
  return m;
}

bool hasCorner(const ManifoldSplit& s, Index v) {
  return std::any_of(s.mesh.tags.corners.begin(), s.mesh.tags.corners.end(),
                     [&](const CornerVertex& c) { return c.vertex == v && c.sharpness >= kInfiniteSharpness; });
}

}  // namespace

TEST_CASE("manifold split: a manifold, consistently oriented mesh is left alone") {
  CHECK(splitNonManifold(shapes::cube()).empty());
  CHECK(splitNonManifold(shapes::mushroom(8)).empty());
  // Back to back faces (the same vertices, opposite ways) are a closed surface, also for Far.
  PolyMesh pillow = withPoints(3);
  pillow.addFace({0, 1, 2});
  pillow.addFace({2, 1, 0});
  CHECK(splitNonManifold(pillow).empty());
  const MeshTopology topo = buildTopology(pillow);
  CHECK(topo.edgeCount == 3);
  for (Index e = 0; e < topo.edgeCount; ++e) CHECK_FALSE(topo.edgeOnBoundary(e));
}

TEST_CASE("manifold split: three faces on an edge: one copy of the edge per face, sharp ends") {
  PolyMesh fin = withPoints(5);
  fin.addFace({0, 1, 2});
  fin.addFace({1, 0, 3});
  fin.addFace({1, 0, 4});
  const ManifoldSplit s = splitNonManifold(fin);
  REQUIRE_FALSE(s.empty());
  CHECK(s.nonManifoldEdges == 1);
  CHECK(s.nonManifoldVertices == 2);
  // Faces 0 and 1 share the edge the manifold way?  No: three sides make it non-manifold for all,
  // so vertices 0 and 1 get a copy per face (3 each), the others stay.
  CHECK(s.mesh.vertexCount() == 5 + 4);
  CHECK(s.sourceVertex.size() == 9u);
  const MeshTopology topo = buildTopology(s.mesh);  // manifold now
  CHECK(topo.edgeCount == 9);
  // Each copy of the edge is infinitely sharp, each copy of its ends a corner (not the interior
  // crease case: the edge has boundary edges around it).
  size_t sharpCopies = 0;
  for (const CreaseEdge& c : s.mesh.tags.creases)
    sharpCopies += s.sourceVertex[size_t(c.v0)] + s.sourceVertex[size_t(c.v1)] == 1 && c.sharpness >= kInfiniteSharpness;
  CHECK(sharpCopies == 3);
  for (Index v = 0; v < s.mesh.vertexCount(); ++v) CHECK(hasCorner(s, v) == (s.sourceVertex[size_t(v)] <= 1));
  // The copies refine to one point each level (bit for bit): the same surface as one mesh.
  const Refinement r(fin, {Scheme::CatmullClark, 3, false});
  CHECK(r.splitInput());
  const PolyMesh out = r.outputMesh();
  CHECK(out.faceCount() == r.finest().mesh.faceCount());
  CHECK(out.vertexCount() < r.finest().mesh.vertexCount());
  for (size_t c = 0; c < out.faceVerts.size(); ++c)
    CHECK(out.points[size_t(out.faceVerts[c])] == r.finest().mesh.points[size_t(r.finest().mesh.faceVerts[c])]);
}

TEST_CASE("manifold split: two cones touching at a vertex, a face repeating a vertex, a flipped face") {
  SUBCASE("bow tie of closed cones: the tip is copied per cone and made a corner") {
    PolyMesh cones = withPoints(7);
    for (const auto& f : std::vector<std::vector<Index>>{{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}, {0, 5, 4}, {0, 6, 5}, {0, 4, 6}, {4, 5, 6}})
      cones.addFace(f.data(), f.size());
    const ManifoldSplit s = splitNonManifold(cones);
    CHECK(s.nonManifoldEdges == 0);
    CHECK(s.nonManifoldVertices == 1);
    CHECK(s.mesh.vertexCount() == 8);
    CHECK(hasCorner(s, 0));
    CHECK(hasCorner(s, 7));
    CHECK(s.sourceVertex[7] == 0);
    CHECK_NOTHROW(buildTopology(s.mesh));
  }
  SUBCASE("a quad repeating a vertex (OpenSubdiv's degenerate edge)") {
    PolyMesh m = withPoints(4);
    m.addFace({0, 1, 2, 2});
    m.addFace({1, 3, 2});
    const ManifoldSplit s = splitNonManifold(m);
    REQUIRE_FALSE(s.empty());
    CHECK(s.nonManifoldEdges == 1);  // the loop 2-2
    CHECK_NOTHROW(buildTopology(s.mesh));
    const Refinement r(m, {Scheme::CatmullClark, 2, false});
    for (const Point& p : r.finest().mesh.points) CHECK(std::isfinite(p.x + p.y + p.z));
  }
  SUBCASE("a face turned against its neighbours: its edges are sharp, as in OpenSubdiv") {
    PolyMesh grid = shapes::grid(3, 3, nullptr);
    std::reverse(grid.faceVerts.begin() + grid.faceStart[4], grid.faceVerts.begin() + grid.faceStart[5]);
    const ManifoldSplit s = splitNonManifold(grid);
    CHECK(s.nonManifoldEdges == 4);
    CHECK_NOTHROW(buildTopology(s.mesh));
  }
}
