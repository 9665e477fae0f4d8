// Which faces of a level are regular, i.e. get a bicubic B-spline patch there (patch_extraction.h):
// a quad whose four corners are interior valence-4 vertices with four quads around them, or
// boundary vertices of valence 3 with two quads. Shared by patch extraction and the adaptive
// refiner, which refines exactly the faces that are not.
#pragma once

#include <cstdint>

#include "core/mesh/poly_mesh.h"
#include "core/mesh/topology.h"
#include "core/subdiv/catmull_clark.h"

namespace polarview {

enum class VertexClass : uint8_t { Irregular, Interior, Boundary, Unknown };

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
    if (vertex == VertexClass::Irregular) return false;
  }
  return true;
}

// Creases and corners (Catmull-Clark's `t` tags): a vertex with sharpness, or with an edge inside the
// mesh of sharpness > 0 at it, is marked Irregular in `cache`, so that its faces are refined to the
// last level (where end caps close them) instead of getting a smooth B-spline patch. Boundary edges
// (sharp by the boundary rule) are the boundary patches' business. No-op without sharpness. [O(edges)]
inline void markSharpVertices(const MeshTopology& topo, const CreaseSharpness& sharpness, VertexClass* cache) {
  if (sharpness.empty()) return;
  for (Index e = 0; e < topo.edgeCount; ++e)
    if (!topo.edgeOnBoundary(e) && sharpness.edge[size_t(e)] > 0.0f)
      cache[topo.edgeVerts[2 * e]] = cache[topo.edgeVerts[2 * e + 1]] = VertexClass::Irregular;
  for (Index v = 0; v < topo.vertexCount; ++v)
    if (size_t(v) < sharpness.vertex.size() && sharpness.vertex[size_t(v)] > 0.0f)
      cache[v] = VertexClass::Irregular;
}

}  // namespace polarview
