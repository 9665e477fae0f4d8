// libFuzzer target over the mesh tables (tests/fuzz/README.md): small OBJ inputs -> buildTopology,
// and for what it refuses splitNonManifold -> buildTopology of the split (refinableMesh's path).
//
// Expected: polarview::InputError from the reader. A finding: any other exception, a crash,
// ASan/UBSan report, a hang, or a broken guarantee of topology.h / manifold_split.h:
//  * the tables (checkTopology): sizes and CSR offsets consistent; each corner's edge joins its
//    vertex to the next corner's; each edge has one or two sides, the second running it the other
//    way (the twin of a half-edge's twin is itself), edges numbered by first use, edgeBetween
//    finds each; each vertex's faces and edges in rotational order (consecutive faces share an
//    edge; a boundary vertex's list starts and ends on boundary edges, an interior one closes),
//    every corner at the vertex once, boundary and used flags right;
//  * buildTopologyFromTwins with the tables' own twins gives the same tables, entry for entry;
//  * a mesh buildTopology takes has no face repeating a vertex and an empty split. One it refuses
//    has a non-empty split unless a face repeats a vertex within one fan (obj_io.cpp: then
//    refinableMesh refuses it too). A split has the input's faces on copies of the input's
//    vertices (the first copy keeping the id, the points the same, splitPoints agreeing, every
//    copy used) and valid tags, and is manifold (buildTopology takes it, its tables pass the
//    checks, its own split is empty) unless a face of the split still repeats a vertex (refused);
//  * refinableMesh returns the mesh itself or the split, with the same tables.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh/input_error.h"
#include "core/mesh/manifold_split.h"
#include "core/mesh/topology.h"
#include "fuzz_common.h"
#include "obj_mutator.h"

using namespace polarview;
using namespace polarview::fuzz;

namespace {

constexpr InputLimits kLimits{16 << 10, 1000, 2000};

Index nextCorner(const PolyMesh& mesh, const MeshTopology& t, Index c) {
  const Index f = t.cornerFace[size_t(c)];
  return c + 1 == mesh.faceStart[size_t(f) + 1] ? mesh.faceStart[size_t(f)] : c + 1;
}
Index prevCorner(const PolyMesh& mesh, const MeshTopology& t, Index c) {
  const Index f = t.cornerFace[size_t(c)];
  return c == mesh.faceStart[size_t(f)] ? mesh.faceStart[size_t(f) + 1] - 1 : c - 1;
}

void requireSize(size_t got, size_t expected, const char* what) {
  if (got != expected) fail(std::string(what) + " has " + std::to_string(got) + " entries, " + std::to_string(expected) + " expected");
}

void checkCsr(const std::vector<Index>& start, size_t vertices, size_t entries, const char* what) {
  requireSize(start.size(), vertices + 1, what);
  if (start.front() != 0 || size_t(start.back()) != entries) fail(std::string(what) + " does not run from 0 to its entries");
  for (size_t v = 0; v < vertices; ++v)
    if (start[v + 1] < start[v]) fail(std::string(what) + " decreases at vertex " + std::to_string(v));
}

// Per corner: the corner starting the opposite half-edge of its edge (-1 on a boundary), from the
// tables; checks the edge tables on the way.
std::vector<Index> checkEdges(const PolyMesh& mesh, const MeshTopology& t) {
  const size_t corners = mesh.faceVerts.size(), edges = size_t(t.edgeCount);
  const std::vector<Index>& fv = mesh.faceVerts;
  requireSize(t.cornerEdge.size(), corners, "cornerEdge");
  requireSize(t.cornerFace.size(), corners, "cornerFace");
  requireSize(t.edgeVerts.size(), 2 * edges, "edgeVerts");
  requireSize(t.edgeFaces.size(), 2 * edges, "edgeFaces");
  for (Index f = 0; f < mesh.faceCount(); ++f)
    for (Index c = mesh.faceStart[size_t(f)]; c < mesh.faceStart[size_t(f) + 1]; ++c)
      if (t.cornerFace[size_t(c)] != f) fail("corner " + std::to_string(c) + " of face " + std::to_string(f) + " in face " + std::to_string(t.cornerFace[size_t(c)]));

  std::vector<Index> first(edges, -1), second(edges, -1);
  Index lastLeader = -1;
  for (Index c = 0; c < Index(corners); ++c) {
    const Index e = t.cornerEdge[size_t(c)];
    if (e < 0 || e >= t.edgeCount) fail("corner " + std::to_string(c) + " has edge " + std::to_string(e));
    auto edge = [&] { return "edge " + std::to_string(e); };
    const Index a = fv[size_t(c)], b = fv[size_t(nextCorner(mesh, t, c))];
    if (!((t.edgeVerts[2 * size_t(e)] == a && t.edgeVerts[2 * size_t(e) + 1] == b) ||
          (t.edgeVerts[2 * size_t(e)] == b && t.edgeVerts[2 * size_t(e) + 1] == a)))
      fail(edge() + " of corner " + std::to_string(c) + " does not join its vertices " + std::to_string(a) + ", " + std::to_string(b));
    if (first[size_t(e)] < 0) {
      if (e != lastLeader + 1) fail(edge() + " is not numbered by first use");
      lastLeader = e;
      first[size_t(e)] = c;
      if (t.edgeVerts[2 * size_t(e)] != a || t.edgeFaces[2 * size_t(e)] != t.cornerFace[size_t(c)])
        fail(edge() + " does not start as its first side runs");
    } else if (second[size_t(e)] < 0) {
      second[size_t(e)] = c;
      if (fv[size_t(first[size_t(e)])] != b) fail(edge() + ": both sides run it the same way");
      if (t.edgeFaces[2 * size_t(e) + 1] != t.cornerFace[size_t(c)]) fail(edge() + "'s second face is not its second side's");
    } else {
      fail(edge() + " has a third side");
    }
  }
  std::vector<Index> twin(corners, -1);
  for (size_t e = 0; e < edges; ++e) {
    if (first[e] < 0) fail("edge " + std::to_string(e) + " has no side");
    if ((second[e] < 0) != t.edgeOnBoundary(Index(e))) fail("edge " + std::to_string(e) + ": boundary flag and sides disagree");
    if (second[e] >= 0) twin[size_t(first[e])] = second[e], twin[size_t(second[e])] = first[e];
    const Index a = t.edgeVerts[2 * e], b = t.edgeVerts[2 * e + 1];
    if (t.edgeBetween(a, b) != Index(e) || t.edgeBetween(b, a) != Index(e))
      fail("edgeBetween(" + std::to_string(a) + ", " + std::to_string(b) + ") is not edge " + std::to_string(e));
  }
  for (size_t c = 0; c < corners; ++c)
    if (twin[c] >= 0 && twin[size_t(twin[c])] != Index(c)) fail("the twin of corner " + std::to_string(c) + "'s twin is not itself");
  return twin;
}

// Rotational order of each vertex's faces and edges.
void checkVertexRings(const PolyMesh& mesh, const MeshTopology& t) {
  const size_t vertices = size_t(mesh.vertexCount()), corners = mesh.faceVerts.size();
  const std::vector<Index>& fv = mesh.faceVerts;
  requireSize(t.vertexOnBoundary.size(), vertices, "vertexOnBoundary");
  requireSize(t.vertexUsed.size(), vertices, "vertexUsed");
  checkCsr(t.vertexFaceStart, vertices, corners, "vertexFaceStart");
  checkCsr(t.vertexEdgeStart, vertices, t.vertexEdges.size(), "vertexEdgeStart");
  requireSize(t.vertexFaces.size(), corners, "vertexFaces");
  requireSize(t.vertexCorners.size(), corners, "vertexCorners");

  std::vector<uint8_t> boundary(vertices, 0), seen(corners, 0);
  std::vector<int> edgesAt(vertices, 0);
  for (Index e = 0; e < t.edgeCount; ++e)
    for (int s = 0; s < 2; ++s) {
      const Index v = t.edgeVerts[2 * size_t(e) + size_t(s)];
      ++edgesAt[size_t(v)];
      if (t.edgeOnBoundary(e)) boundary[size_t(v)] = 1;
    }
  for (Index v = 0; v < Index(vertices); ++v) {
    auto name = [&] { return "vertex " + std::to_string(v); };
    const Index first = t.vertexFaceStart[size_t(v)], faces = t.faceValence(v), edgeStart = t.vertexEdgeStart[size_t(v)];
    if (t.vertexOnBoundary[size_t(v)] != boundary[size_t(v)]) fail(name() + ": wrong boundary flag");
    if (t.vertexUsed[size_t(v)] != (faces > 0)) fail(name() + ": wrong used flag");
    if (t.valence(v) != faces + boundary[size_t(v)] || t.valence(v) != edgesAt[size_t(v)])
      fail(name() + " has valence " + std::to_string(t.valence(v)) + " with " + std::to_string(faces) + " faces and " +
           std::to_string(edgesAt[size_t(v)]) + " edges");
    for (Index k = 0; k < faces; ++k) {
      const Index c = t.vertexCorners[size_t(first + k)];
      if (c < 0 || size_t(c) >= corners || fv[size_t(c)] != v || seen[size_t(c)])
        fail(name() + ": ring entry " + std::to_string(k) + " is corner " + std::to_string(c));
      seen[size_t(c)] = 1;
      if (t.vertexFaces[size_t(first + k)] != t.cornerFace[size_t(c)]) fail(name() + ": ring face and corner disagree at " + std::to_string(k));
      if (t.vertexEdges[size_t(edgeStart + k)] != t.cornerEdge[size_t(c)]) fail(name() + ": ring edge " + std::to_string(k) + " is not its face's");
      // The face's incoming edge at v is the next face's outgoing one (the last: the first's, or the boundary).
      const Index incoming = t.cornerEdge[size_t(prevCorner(mesh, t, c))];
      const Index expected = k + 1 < faces || boundary[size_t(v)] ? t.vertexEdges[size_t(edgeStart + k + 1)] : t.vertexEdges[size_t(edgeStart)];
      if (incoming != expected) fail(name() + ": faces " + std::to_string(k) + " and " + std::to_string(k + 1) + " of its ring share no edge");
    }
    if (boundary[size_t(v)] && faces > 0 &&
        (!t.edgeOnBoundary(t.vertexEdges[size_t(edgeStart)]) || !t.edgeOnBoundary(t.vertexEdges[size_t(edgeStart + faces)])))
      fail(name() + ": a boundary ring does not start and end on boundary edges");
  }
}

void checkTopology(const PolyMesh& mesh, const MeshTopology& t, const char* what) {
  gStage = std::string("check ") + what;
  if (t.vertexCount != mesh.vertexCount() || t.faceCount != mesh.faceCount())
    fail(std::to_string(t.vertexCount) + " vertices and " + std::to_string(t.faceCount) + " faces in the tables of a mesh of " +
         std::to_string(mesh.vertexCount()) + " and " + std::to_string(mesh.faceCount()));
  const std::vector<Index> twin = checkEdges(mesh, t);
  checkVertexRings(mesh, t);

  gStage = std::string("buildTopologyFromTwins of ") + what;
  const MeshTopology u = buildTopologyFromTwins(mesh, twin);
  if (u.vertexCount != t.vertexCount || u.edgeCount != t.edgeCount || u.faceCount != t.faceCount || u.cornerEdge != t.cornerEdge ||
      u.cornerFace != t.cornerFace || u.edgeVerts != t.edgeVerts || u.edgeFaces != t.edgeFaces ||
      u.vertexFaceStart != t.vertexFaceStart || u.vertexFaces != t.vertexFaces || u.vertexEdgeStart != t.vertexEdgeStart ||
      u.vertexEdges != t.vertexEdges || u.vertexCorners != t.vertexCorners || u.vertexOnBoundary != t.vertexOnBoundary ||
      u.vertexUsed != t.vertexUsed)
    fail("buildTopologyFromTwins differs from buildTopology");
}

bool anyFaceRepeatsVertex(const PolyMesh& mesh) {
  for (Index f = 0; f < mesh.faceCount(); ++f)
    if (repeatsVertex(mesh, f)) return true;
  return false;
}

// refinableMesh must refuse `mesh` (InputError): `what` it is.
void requireRefused(const PolyMesh& mesh, const std::string& what) {
  gStage = "refinableMesh";
  ManifoldSplit storage;
  MeshTopology topology;
  try {
    refinableMesh(mesh, storage, topology, kSource);
  } catch (const InputError&) {
    return;
  }
  fail("refinableMesh takes " + what);
}

// Checks the split and returns its tables; none where it cannot be refined either.
std::optional<MeshTopology> checkSplit(const PolyMesh& mesh, const ManifoldSplit& split) {
  gStage = "check splitNonManifold";
  const PolyMesh& out = split.mesh;
  const Index inputVertices = mesh.vertexCount();
  if (split.nonManifoldEdges + split.nonManifoldVertices == 0) fail("a split without non-manifold edges or vertices");
  requireSize(split.sourceVertex.size(), size_t(out.vertexCount()), "sourceVertex");
  if (out.vertexCount() < inputVertices) fail("the split has fewer vertices than the input");
  if (out.faceStart != mesh.faceStart) fail("the split's faces are not the input's");
  checkFaces(out, "split mesh");
  for (Index v = 0; v < out.vertexCount(); ++v) {
    const Index s = split.sourceVertex[size_t(v)];
    if (v < inputVertices ? s != v : (s < 0 || s >= inputVertices))
      fail("split vertex " + std::to_string(v) + " comes from input vertex " + std::to_string(s));
    if (out.points[size_t(v)] != mesh.points[size_t(s)]) fail("split vertex " + std::to_string(v) + " is not where its input vertex is");
  }
  std::vector<uint8_t> used(size_t(out.vertexCount()), 0);
  for (size_t c = 0; c < mesh.faceVerts.size(); ++c) {
    used[size_t(out.faceVerts[c])] = 1;
    if (split.sourceVertex[size_t(out.faceVerts[c])] != mesh.faceVerts[c])
      fail("split corner " + std::to_string(c) + " is on a copy of another vertex");
  }
  for (Index v = inputVertices; v < out.vertexCount(); ++v)
    if (!used[size_t(v)]) fail("split copy " + std::to_string(v) + " is in no face");
  if (split.splitPoints(mesh.points) != out.points) fail("splitPoints differs from the split's points");
  // The one thing the split leaves (obj_io.cpp, manifold_split.h): a face repeating a vertex
  // whose corners there lie in one fan.
  gStage = "buildTopology of the split";
  MeshTopology topology;
  try {
    topology = buildTopology(out, kSource);
  } catch (const InputError& e) {
    if (!anyFaceRepeatsVertex(out)) fail(std::string("the split (no face repeating a vertex) is not manifold: ") + e.what());
    return std::nullopt;
  }
  gStage = "check splitNonManifold";
  checkTags(out, "split mesh");
  if (out.tags.boundary != BoundaryInterpolation::EdgeOnly || out.tags.creaseMethod != mesh.tags.creaseMethod ||
      out.tags.triangles != mesh.tags.triangles)
    fail("the split's tag options are not the input's (with the edge-only boundary rule)");
  for (Index h : mesh.tags.holes)
    if (!std::binary_search(out.tags.holes.begin(), out.tags.holes.end(), h)) fail("input hole " + std::to_string(h) + " is no hole of the split");

  checkTopology(out, topology, "the split's tables");
  gStage = "splitNonManifold of the split";
  if (!splitNonManifold(out).empty()) fail("the split of the split is not empty");
  return topology;
}

void run(const uint8_t* data, size_t size) {
  PolyMesh mesh;
  if (!parseInput(data, size, kLimits, mesh)) return;
  gStage = "buildTopology";
  MeshTopology topology;
  bool manifold = true;
  std::string refusal;
  try {
    topology = buildTopology(mesh, kSource);
  } catch (const InputError& e) {
    manifold = false;
    refusal = e.what();
  }
  gStage = "splitNonManifold";
  const ManifoldSplit split = splitNonManifold(mesh);
  if (manifold) {
    checkTopology(mesh, topology, "buildTopology's tables");
    for (Index f = 0; f < mesh.faceCount(); ++f)
      if (repeatsVertex(mesh, f)) fail("buildTopology takes face " + std::to_string(f) + ", which repeats a vertex");
    if (!split.empty()) fail("a mesh buildTopology takes has a manifold split");
  } else {
    if (split.empty()) {
      // Not a matter of manifoldness (manifold_split.h): only a face repeating a vertex whose
      // corners there lie in one fan (obj_io.cpp), which refinableMesh refuses as buildTopology.
      if (!anyFaceRepeatsVertex(mesh)) fail("buildTopology refuses a mesh without repeated vertices whose manifold split is empty: " + refusal);
      return requireRefused(mesh, "a mesh buildTopology refuses and splitNonManifold leaves");
    }
    std::optional<MeshTopology> splitTopology = checkSplit(mesh, split);
    if (!splitTopology) return requireRefused(mesh, "a mesh whose split buildTopology refuses");
    topology = std::move(*splitTopology);
  }

  gStage = "refinableMesh";
  ManifoldSplit storage;
  MeshTopology refinableTopology;
  const PolyMesh& refinable = refinableMesh(mesh, storage, refinableTopology, kSource);
  if (manifold ? &refinable != &mesh || !storage.empty() : &refinable != &storage.mesh || storage.sourceVertex != split.sourceVertex)
    fail("refinableMesh returns neither the mesh nor its split");
  if (refinableTopology.cornerEdge != topology.cornerEdge || refinableTopology.vertexEdges != topology.vertexEdges)
    fail("refinableMesh's tables are not buildTopology's");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return runInput([&] { run(data, size); });
}
