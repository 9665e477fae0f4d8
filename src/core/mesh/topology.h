// MeshTopology: edge and incidence tables of a manifold PolyMesh, built once per level.
// Flat arrays only (no pointers); every table is indexed by vertex, edge, face or corner.
// A corner is a position in PolyMesh::faceVerts: corner c of face f is faceStart[f] + c.
#pragma once

#include <string>
#include <vector>

#include "core/mesh/poly_mesh.h"

namespace polarview {

struct MeshTopology {
  Index vertexCount = 0, edgeCount = 0, faceCount = 0;

  // Per corner: the edge from this corner's vertex to the next corner's vertex of the same face.
  std::vector<Index> cornerEdge;
  // Per corner: the face it belongs to.
  std::vector<Index> cornerFace;
  // Per edge: its two end vertices (edgeVerts[2e], edgeVerts[2e+1]).
  std::vector<Index> edgeVerts;
  // Per edge: the faces on either side (edgeFaces[2e], edgeFaces[2e+1]); the second is -1 on a boundary edge.
  std::vector<Index> edgeFaces;

  // Per vertex, CSR: the incident faces in rotational order (consecutive faces share an edge
  // incident to the vertex). A boundary vertex's list starts at a face on a boundary edge.
  std::vector<Index> vertexFaceStart, vertexFaces;
  // Per vertex, CSR: the incident edges in the same rotational order; a boundary vertex has one
  // more edge than faces, an interior vertex as many edges as faces.
  std::vector<Index> vertexEdgeStart, vertexEdges;
  // Per vertex, parallel to vertexFaces: the corner of that face at this vertex.
  std::vector<Index> vertexCorners;

  std::vector<uint8_t> vertexOnBoundary;  // 1 when some incident edge is a boundary edge
  std::vector<uint8_t> vertexUsed;        // 0 for vertices no face references

  Index valence(Index v) const { return vertexEdgeStart[v + 1] - vertexEdgeStart[v]; }
  Index faceValence(Index v) const { return vertexFaceStart[v + 1] - vertexFaceStart[v]; }
  bool edgeOnBoundary(Index e) const { return edgeFaces[2 * e + 1] < 0; }
  // The vertex across edge e from v. [O(1)]
  Index otherEnd(Index e, Index v) const { return edgeVerts[2 * e] == v ? edgeVerts[2 * e + 1] : edgeVerts[2 * e]; }
  // The face across edge e from face f (-1 on a boundary). [O(1)]
  Index faceAcross(Index e, Index f) const { return edgeFaces[2 * e] == f ? edgeFaces[2 * e + 1] : edgeFaces[2 * e]; }
  // The edge joining a and b (-1 if none). [O(valence of a)]
  Index edgeBetween(Index a, Index b) const {
    for (Index k = vertexEdgeStart[a]; k < vertexEdgeStart[a + 1]; ++k)
      if (otherEnd(vertexEdges[k], a) == b) return vertexEdges[k];
    return -1;
  }
};

// Builds the tables of a manifold mesh. Throws InputError naming `sourceName` and the face's OBJ
// line (mesh.faceLine) for: a face with fewer than 3 vertices, a repeated vertex in one face, an
// index out of range, an edge shared by more than two faces or used twice in the same direction
// (inconsistent orientation), and non-manifold vertices (faces around a vertex forming more than
// one fan). Two faces back to back (the same vertices, opposite orientation) are a closed surface
// and accepted. Refinements take non-manifold meshes through their manifold split
// (manifold_split.h). [O(corners log)]
MeshTopology buildTopology(const PolyMesh& mesh, const std::string& sourceName = "<mesh>");
// The same tables for a mesh whose half-edge twins are known (a refinement's child, manifold by
// construction): twin[c] = the corner starting the opposite half-edge of corner c's edge, -1 on a
// boundary. No validation and no sorting; equal to buildTopology(mesh) entry for entry. [O(corners)]
MeshTopology buildTopologyFromTwins(const PolyMesh& mesh, const std::vector<Index>& twin);

}  // namespace polarview
