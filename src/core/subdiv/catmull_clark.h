// Catmull-Clark refinement with OpenSubdiv 3.5's conventions (docs/schemes.md, Catmull-Clark): options
// VTX_BOUNDARY_EDGE_ONLY, CREASE_UNIFORM, TRI_SUB_CATMARK; smooth rules for any valence and any
// n-gon; boundary edges are midpoints; boundary vertices (valence-2 corners included) are
// 3/4 v + 1/8 (a + b). Topology and positions are separate so positions can be recomputed cheaply.
//
// Child vertex order (as OpenSubdiv): [face points (F) | edge points (E) | vertex points (V)]:
// child vertex of face f is f, of edge e is F + e, of vertex v is F + E + v.
// Child faces: corner c (global index into faceVerts) of parent face f gives child face c with the
// loop (vertexPoint(v_c), edgePoint(edge c), facePoint(f), edgePoint(edge of the previous corner)).
#pragma once

#include <vector>

#include "core/mesh/poly_mesh.h"
#include "core/mesh/topology.h"

namespace polarview {

// Child vertex ids of a parent element. [O(1)]
inline Index ccFacePoint(const MeshTopology&, Index f) { return f; }
inline Index ccEdgePoint(const MeshTopology& t, Index e) { return t.faceCount + e; }
inline Index ccVertexPoint(const MeshTopology& t, Index v) { return t.faceCount + t.edgeCount + v; }
// Number of child vertices F + E + V. [O(1)]
inline Index ccChildVertexCount(const MeshTopology& t) { return t.faceCount + t.edgeCount + t.vertexCount; }

// The child mesh's faces (all quads, one per parent corner); `points` is sized F + E + V but left
// unset. faceParent (optional) receives each child face's parent face. [O(corners)]
PolyMesh refineCatmullClarkTopology(const PolyMesh& parent, const MeshTopology& topo, std::vector<Index>* faceParent);

// Fills all F + E + V child points from the parent points (childPoints must hold
// ccChildVertexCount(topo) points). Vertices no face uses are copied through. No allocation but the
// threads it starts on large meshes: `threads` of them, or (0) as many as pay (parallel_for.h);
// the results never depend on them. [O(corners)]
void computeCatmullClarkPoints(const MeshTopology& topo, const PolyMesh& parent, const Point* parentPoints,
                               Point* childPoints, unsigned threads = 0);

// One full step: topology and points. [O(corners)]
PolyMesh refineCatmullClark(const PolyMesh& parent, const MeshTopology& topo, std::vector<Index>* faceParent = nullptr);

// Limit positions of the vertices of an all-quad mesh (e.g. any level >= 1): smooth valence k:
// k/(k+5) v + 4/(k(k+5)) sum of edge ends + 1/(k(k+5)) sum of face diagonals; boundary:
// 2/3 v + 1/6 (a + b); unused vertices copied. Interior valence 2 gets the same formula, the true
// limit (OpenSubdiv's Limit returns the vertex itself there; elsewhere it agrees). Throws std::invalid_argument when a used vertex
// touches a face that is not a quad. [O(corners)]
std::vector<Point> catmullClarkLimitPoints(const MeshTopology& topo, const PolyMesh& mesh);

}  // namespace polarview
