// Which faces of a level are regular, i.e. get a bicubic B-spline patch there (patch_extraction.h):
// a quad whose four corners are interior valence-4 vertices with four quads around them, or
// boundary vertices of valence 3 with two quads. Shared by patch extraction and the adaptive
// refiner, which refines exactly the faces that are not.
//
// Infinitely sharp creases (Catmull-Clark's `t` tags) cut the mesh as a boundary does: the crease
// rule and its limit curve are the boundary's, and infinite sharpness never decays, so a face whose
// corners see the crease as a boundary gets the boundary patch (mirrored across its sharp sides),
// exactly, at every level (OpenSubdiv's regular inf-sharp patches): corners on a straight crease
// (valence 4, four quads, the two sharp edges opposite: Crease) or at a corner (every edge sharp,
// three or more of them or a sharp vertex: Corner). Semi-sharp features still refine to the last level.
#pragma once

#include <cstdint>

#include "core/mesh/poly_mesh.h"
#include "core/mesh/topology.h"
#include "core/subdiv/catmull_clark.h"

namespace polarview {

enum class VertexClass : uint8_t { Irregular, Interior, Boundary, Crease, Corner, Unknown };

// Whether edge e cuts the mesh for patches: a boundary, or infinitely sharp. [O(1)]
inline bool isPatchCut(const MeshTopology& topo, const CreaseSharpness* sharpness, Index e) {
  return topo.edgeOnBoundary(e) || (sharpness && !sharpness->empty() && sharpness->edge[size_t(e)] >= float(kInfiniteSharpness));
}

// The class of one vertex (never Unknown). [O(valence)]
inline VertexClass classifyVertex(const PolyMesh& mesh, const MeshTopology& topo, Index v) {
  const Index faces = topo.faceValence(v), valence = topo.valence(v);
  for (Index k = topo.vertexFaceStart[v]; k < topo.vertexFaceStart[v + 1]; ++k)
    if (mesh.faceSize(topo.vertexFaces[k]) != 4) return VertexClass::Irregular;
  if (!topo.vertexOnBoundary[v]) return valence == 4 && faces == 4 ? VertexClass::Interior : VertexClass::Irregular;
  return valence == 3 && faces == 2 ? VertexClass::Boundary : VertexClass::Irregular;
}

// Whether face f is regular; `cache` (one entry per vertex, Unknown to start) keeps the classes
// already found. [O(valences of its corners)]
inline bool isRegularFace(const PolyMesh& mesh, const MeshTopology& topo, Index f, VertexClass* cache) {
  if (mesh.faceSize(f) != 4) return false;
  const Index* loop = mesh.face(f);
  for (int c = 0; c < 4; ++c) {
    VertexClass& vertex = cache[loop[c]];
    if (vertex == VertexClass::Unknown) vertex = classifyVertex(mesh, topo, loop[c]);
    if (vertex == VertexClass::Irregular) return false;  // Interior, Boundary, Crease, Corner are regular
  }
  return true;
}

// The class of a vertex that a crease or corner tag touches (above): Crease, Corner, or Irregular
// (semi-sharp features, darts, bends of a crease, sharp corners with smooth edges). [O(valence)]
inline VertexClass classifySharpVertex(const PolyMesh& mesh, const MeshTopology& topo, const CreaseSharpness& sharpness, Index v) {
  const float infinite = float(kInfiniteSharpness);
  const float vertexSharpness = size_t(v) < sharpness.vertex.size() ? sharpness.vertex[size_t(v)] : 0.0f;
  if (vertexSharpness > 0.0f && vertexSharpness < infinite) return VertexClass::Irregular;
  for (Index k = topo.vertexFaceStart[v]; k < topo.vertexFaceStart[v + 1]; ++k)
    if (mesh.faceSize(topo.vertexFaces[k]) != 4) return VertexClass::Irregular;
  const Index first = topo.vertexEdgeStart[v], edges = topo.valence(v);
  int cuts = 0;
  for (Index k = 0; k < edges; ++k) {
    const Index e = topo.vertexEdges[first + k];
    const float s = sharpness.edge[size_t(e)];
    if (!topo.edgeOnBoundary(e) && s > 0.0f && s < infinite) return VertexClass::Irregular;
    cuts += isPatchCut(topo, &sharpness, e);
  }
  if (vertexSharpness >= infinite || cuts >= 3) return cuts == edges ? VertexClass::Corner : VertexClass::Irregular;
  // A straight crease through an interior valence-4 vertex: both sides are regular boundaries.
  if (cuts == 2 && !topo.vertexOnBoundary[v] && edges == 4 && topo.faceValence(v) == 4 &&
      isPatchCut(topo, &sharpness, topo.vertexEdges[first]) == isPatchCut(topo, &sharpness, topo.vertexEdges[first + 2]))
    return VertexClass::Crease;
  return VertexClass::Irregular;
}

// Creases and corners (Catmull-Clark's `t` tags): each vertex with sharpness, or with an edge inside
// the mesh of sharpness > 0 at it, gets its class in `cache` (classifySharpVertex): Crease and Corner
// vertices give boundary-like patches, the others are Irregular, so that their faces are refined to
// the last level (where end caps close them). No-op without sharpness. [O(edges)]
inline void markSharpVertices(const PolyMesh& mesh, const MeshTopology& topo, const CreaseSharpness& sharpness, VertexClass* cache) {
  if (sharpness.empty()) return;
  auto mark = [&](Index v) {
    if (cache[v] == VertexClass::Unknown) cache[v] = classifySharpVertex(mesh, topo, sharpness, v);
  };
  for (Index e = 0; e < topo.edgeCount; ++e)
    if (!topo.edgeOnBoundary(e) && sharpness.edge[size_t(e)] > 0.0f) mark(topo.edgeVerts[2 * e]), mark(topo.edgeVerts[2 * e + 1]);
  for (Index v = 0; v < topo.vertexCount; ++v)
    if (size_t(v) < sharpness.vertex.size() && sharpness.vertex[size_t(v)] > 0.0f) mark(v);
}

}  // namespace polarview
