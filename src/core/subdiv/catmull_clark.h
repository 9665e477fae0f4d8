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


// Fills all F + E + V child points from the parent points (childPoints must hold
// ccChildVertexCount(topo) points). Vertices no face uses are copied through. No allocation but the
// threads it starts on large meshes: `threads` of them, or (0) as many as pay (parallel_for.h);
// the results never depend on them. [O(corners)]
void computeCatmullClarkPoints(const MeshTopology& topo, const PolyMesh& parent, const Point* parentPoints,
                               Point* childPoints, unsigned threads = 0);

// Sharpness of one level's edges and vertices as OpenSubdiv's Vtr keeps it, in float as there (so
// fractional weights round the same): crease edges and corners from the mesh's `t` tags at level 0,
// boundary edges infinitely sharp (and, under BoundaryInterpolation::EdgeAndCorner, vertices with one
// face); each level 1 less than its parent (CREASE_UNIFORM), or by Chaikin's rule at each end
// (CreaseMethod::Chaikin: 3/4 of the edge's and 1/4 of the mean of the other semi-sharp edges
// there, less 1); kInfiniteSharpness stays. Empty when no edge inside the mesh and no vertex is
// sharp: the smooth rules above then apply unchanged.
struct CreaseSharpness {
  std::vector<float> edge;    // per edge
  std::vector<float> vertex;  // per vertex
  bool chaikin = false;       // the decay rule: CREASE_CHAIKIN, else CREASE_UNIFORM
  // Sdc::Options::TRI_SUB_SMOOTH (level 0 only: Catmull-Clark leaves no triangles after a step):
  // an edge point next to a triangle weighs that triangle's face point 0.47 instead of 0.25.
  bool smoothTriangles = false;
  bool empty() const { return edge.empty(); }
};

// Hole faces (Far's face tag `_hole`): `t hole` tags, and under `t interpolateboundary 0`
// (VTX_BOUNDARY_NONE) every face at a boundary vertex with a boundary edge that is not tagged
// infinitely sharp. Holes change no point (the rules ignore them); they give no patches. Empty when
// there is none. [O(faces + edges)]
std::vector<uint8_t> baseHoles(const PolyMesh& mesh, const MeshTopology& topo);
// Level 0's sharpness from mesh.tags (the crease edges must be edges of `topo`, as loadObj checks).
// [O(edges + vertices + tags valence)]
CreaseSharpness baseSharpness(const PolyMesh& mesh, const MeshTopology& topo);
// The sharpness one Catmull-Clark step makes of `parent` (level tables `parentTopo`, child tables
// `childTopo`): each half of an edge and the vertex point of a vertex get the parent's value
// decayed (see CreaseSharpness), the new edges inside faces are smooth. [O(child edges)]
CreaseSharpness childSharpness(const MeshTopology& parentTopo, const CreaseSharpness& parent, const MeshTopology& childTopo);
// The crease and corner tags that give `sharpness` (boundary edges left out: they are sharp anyway),
// with the options of `options`; for a refined level's mesh. [O(edges + vertices)]
SubdivTags sharpnessTags(const MeshTopology& topo, const CreaseSharpness& sharpness, const SubdivTags& options);

// computeCatmullClarkPoints with OpenSubdiv's crease rules (Sdc::Scheme<CATMARK>): an edge point
// is the midpoint while both halves of its edge stay sharp, else s of the midpoint and 1 - s of
// the smooth point for an edge of sharpness s (s > 1 too, as OpenSubdiv does under Chaikin); a
// vertex point follows the vertex's rule (smooth or dart: under 2 sharp edges; crease: 2; corner:
// more, or a sharp vertex), blended with the child's rule by OpenSubdiv's fractional weight where
// the rule changes. An empty `sharpness` gives the smooth rules. [O(corners)]
void computeCatmullClarkPoints(const MeshTopology& topo, const PolyMesh& parent, const Point* parentPoints,
                               Point* childPoints, const CreaseSharpness& sharpness, unsigned threads = 0);


// A sparse step (OpenSubdiv's sparse refinement, adaptive_refiner.h): the child vertices that exist,
// by parent element, numbered in this order: face points of `faces`, then edge points of `edges`,
// then vertex points of `vertices`.
struct SparseChildVertices {
  std::vector<Index> faces, edges, vertices;
  size_t count() const { return faces.size() + edges.size() + vertices.size(); }
};
// The points of `which` from the parent's (the rules above, every neighbour the rule reads taken
// from the parent level as it is). `facePoints`: scratch, resized to the parent's face count.
// [O(corners around the elements of `which`) + O(parent faces) for the scratch]
void computeSparseCatmullClarkPoints(const MeshTopology& topo, const PolyMesh& parent, const Point* parentPoints,
                                     const SparseChildVertices& which, const CreaseSharpness& sharpness,
                                     std::vector<Point>& facePoints, Point* childPoints, unsigned threads = 0);
// childSharpness for a sparse child numbered as `which`: the halves of the parent's edges at the ends
// whose vertex points exist, decayed; vertex points decayed. [O(child edges)]
CreaseSharpness sparseChildSharpness(const MeshTopology& parentTopo, const CreaseSharpness& parent, const SparseChildVertices& which,
                                     const MeshTopology& childTopo);

// Limit positions of the vertices of an all-quad mesh (e.g. any level >= 1): smooth valence k:
// k/(k+5) v + 4/(k(k+5)) sum of edge ends + 1/(k(k+5)) sum of face diagonals; boundary:
// 2/3 v + 1/6 (a + b); unused vertices copied. Interior valence 2 gets the same formula, the true
// limit (OpenSubdiv's Limit returns the vertex itself there; elsewhere it agrees). Throws std::invalid_argument when a used vertex
// touches a face that is not a quad. [O(corners)]
std::vector<Point> catmullClarkLimitPoints(const MeshTopology& topo, const PolyMesh& mesh);

// The interior limit mask of a smooth valence-k vertex (above): weights of the vertex, of each
// edge end and of each face diagonal. Shared with the end caps (patch_extraction.cpp). [O(1)]
struct LimitMask {
  double vertex, edge, diagonal;
};
inline LimitMask catmullClarkLimitMask(double k) { return {k / (k + 5.0), 4.0 / (k * (k + 5.0)), 1.0 / (k * (k + 5.0))}; }

}  // namespace polarview
