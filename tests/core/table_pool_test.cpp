// Table pool: recycled buffers are reused, bounded, and a refinement built on recycled (poisoned)
// tables equals one built on fresh memory, entry for entry and bit for bit.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "core/mesh/shapes.h"
#include "core/subdiv/refiner.h"
#include "core/subdiv/table_pool.h"

using namespace polarview;

namespace {

// Everything a level holds that the pool may recycle.
void requireSameLevel(const RefinedLevel& a, const RefinedLevel& b) {
  REQUIRE(a.mesh.points.size() == b.mesh.points.size());
  for (size_t v = 0; v < a.mesh.points.size(); ++v) REQUIRE(a.mesh.points[v] == b.mesh.points[v]);
  CHECK(a.mesh.faceStart == b.mesh.faceStart);
  CHECK(a.mesh.faceVerts == b.mesh.faceVerts);
  CHECK(a.faceParent == b.faceParent);
  const MeshTopology &s = a.topology, &t = b.topology;
  CHECK(s.cornerEdge == t.cornerEdge);
  CHECK(s.cornerFace == t.cornerFace);
  CHECK(s.edgeVerts == t.edgeVerts);
  CHECK(s.edgeFaces == t.edgeFaces);
  CHECK(s.vertexFaceStart == t.vertexFaceStart);
  CHECK(s.vertexFaces == t.vertexFaces);
  CHECK(s.vertexEdgeStart == t.vertexEdgeStart);
  CHECK(s.vertexEdges == t.vertexEdges);
  CHECK(s.vertexCorners == t.vertexCorners);
  CHECK(s.vertexOnBoundary == t.vertexOnBoundary);
  CHECK(s.vertexUsed == t.vertexUsed);
}

}  // namespace

TEST_CASE("table pool: a released buffer comes back for a request it fits, and clearing empties the pool") {
  clearTablePool();
  std::vector<Index> table(size_t(1) << 20, 7);  // 4 MiB
  const Index* buffer = table.data();
  releaseToPool(table);
  CHECK(table.empty());
  CHECK(pooledBytes() == (size_t(1) << 20) * sizeof(Index));

  std::vector<Index> small;
  reserveFromPool(small, size_t(1) << 21);  // too big for the pooled buffer: fresh allocation
  CHECK(small.capacity() >= (size_t(1) << 21));
  CHECK(pooledBytes() == (size_t(1) << 20) * sizeof(Index));

  std::vector<Index> reused;
  reserveFromPool(reused, 300000);
  CHECK(reused.data() == buffer);
  CHECK(reused.capacity() >= 300000);
  CHECK(pooledBytes() == 0);

  releaseToPool(reused);
  std::vector<uint8_t> tiny(100);
  releaseToPool(tiny);  // below kMinPooledBytes: freed, not pooled
  CHECK(pooledBytes() == (size_t(1) << 20) * sizeof(Index));
  clearTablePool();
  CHECK(pooledBytes() == 0);
}

TEST_CASE("table pool: never holds more than maxPooledBytes") {
  CHECK(maxPooledBytes() >= size_t(1) << 30);
  clearTablePool();
  setMaxPooledBytes(size_t(256) << 20);
  for (int i = 0; i < 8; ++i) {
    std::vector<Point> table(size_t(2) << 20);  // 48 MiB each, 384 MiB offered in all
    releaseToPool(table);
    CHECK(pooledBytes() <= maxPooledBytes());
  }
  CHECK(pooledBytes() > maxPooledBytes() / 2);
  setMaxPooledBytes(0);
  clearTablePool();
}

TEST_CASE("refinements built on recycled tables equal those built on fresh memory, for every scheme") {
  // Large enough for the threaded passes (> 32k corners at the finer levels).
  const std::pair<PolyMesh, int> meshes[] = {{shapes::mushroom(12), 6}, {shapes::globe(24, 20), 4}, {shapes::torus(40, 30), 4}};
  for (const auto& [base, levels] : meshes) {
    for (Scheme scheme : {Scheme::CatmullClark, Scheme::C2PS, Scheme::RTS, Scheme::BPS}) {
      CAPTURE(std::string(schemeName(scheme)));
      const Index baseFaces = base.faceCount();  // C++17 lambdas (CAPTURE) cannot capture a structured binding
      CAPTURE(baseFaces);
      const RefineOptions options{scheme, levels, false};
      clearTablePool();
      const Refinement fresh(base, options);
      // Fill the pool with poisoned tables of exactly the sizes the refinement asks for, so any entry
      // it failed to write would show.
      for (int m = 0; m < fresh.levelCount(); ++m) {
        const RefinedLevel& level = fresh.level(m);
        const MeshTopology& t = level.topology;
        for (const std::vector<Index>* table : {&level.mesh.faceStart, &level.mesh.faceVerts, &level.faceParent, &t.cornerEdge,
                                                &t.cornerFace, &t.edgeVerts, &t.edgeFaces, &t.vertexFaceStart, &t.vertexFaces,
                                                &t.vertexEdgeStart, &t.vertexEdges, &t.vertexCorners}) {
          std::vector<Index> poisoned(table->size(), Index(-777));
          releaseToPool(poisoned);
        }
        for (const std::vector<uint8_t>* flags : {&t.vertexOnBoundary, &t.vertexUsed}) {
          std::vector<uint8_t> poisoned(flags->size(), 0xAB);
          releaseToPool(poisoned);
        }
        std::vector<Point> poisonedPoints(level.mesh.points.size(), Point(std::nan("")));
        releaseToPool(poisonedPoints);
      }
      if (fresh.finest().mesh.faceVerts.size() * sizeof(Index) >= kMinPooledBytes) CHECK(pooledBytes() > 0);
      const Refinement recycled(base, options);
      REQUIRE(recycled.levelCount() == fresh.levelCount());
      for (int m = 0; m < fresh.levelCount(); ++m) {
        CAPTURE(m);
        requireSameLevel(recycled.level(m), fresh.level(m));
      }
    }
  }
  clearTablePool();
}
