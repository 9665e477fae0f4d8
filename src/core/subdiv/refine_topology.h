// Catmull-Clark connectivity derived from the parent's tables (as OpenSubdiv's Vtr does): the child
// mesh and its MeshTopology in O(corners), with no sorting and no validation (the child of a valid
// manifold mesh is a valid manifold mesh). The tables equal buildTopology(child mesh) entry for
// entry: edges numbered by first use, rings in the same rotational order from the same start.
//
// Child faces follow catmull_clark.h: parent corner c gives the quad (V(v_c), E(edge c), F(f),
// E(edge of the previous corner)). A corner marked for splitting (C2PS's pole corners) gives two
// triangles instead, (V, E_a, F) then (V, F, E_b): one extra face and one extra edge (V - F).
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh/poly_mesh.h"
#include "core/mesh/topology.h"

namespace polarview {

// Per corner c, two entries: links[2c] = the twin, the corner starting the opposite half-edge of
// c's edge (the neighbouring face's corner at c's next vertex); links[2c+1] = the corner after the
// twin in its face (the corner before c in c's vertex ring). Both -1 on a boundary edge. Read from
// the vertex rings. [O(corners)]
std::vector<Index> cornerLinks(const PolyMesh& mesh, const MeshTopology& topo);

// One level of refined connectivity.
struct RefinedConnectivity {
  PolyMesh mesh;                 // faces; points sized F + E + V, values left for the point rules
  MeshTopology topology;         // equal to buildTopology(mesh)
  std::vector<Index> faceParent; // per child face: its parent face
  std::vector<Index> links;      // cornerLinks of the child, for the next level (if asked for)
};

struct ConnectivityOptions {
  bool childLinks = true;  // fill RefinedConnectivity::links (not needed at the finest level)
  // Fill the child's vertex rings (vertexFaceStart, vertexFaces, vertexEdgeStart, vertexEdges,
  // vertexCorners). Without them (a finest level nobody walks around: OpenSubdiv's
  // fullTopologyInLastLevel = false) those tables stay empty, vertexOnBoundary and vertexUsed are
  // still filled, and completeChildTopology adds the rings later: a third fewer bytes to write.
  bool vertexRings = true;
  // Fill the child's edges (cornerEdge, cornerFace, edgeVerts, edgeFaces; false needs vertexRings
  // and childLinks false too, else std::logic_error). Without them the child has its faces only (faceVerts, faceStart, faceParent), its counts
  // and vertexOnBoundary / vertexUsed: OpenSubdiv's minimal topology of the last uniform level, what
  // the points and `refine` read. completeChildTopology adds the rest later.
  bool edges = true;
  unsigned threads = 0;    // 0: as many as pay for the mesh size (parallel_for.h); results never depend on it
};

// One Catmull-Clark step of the connectivity of `parent` (tables `topo`, `links` from cornerLinks
// or the previous step). `splitCorner` (nullptr, or one flag per parent corner) marks the corners whose
// quads are split along the diagonal V - F. [O(corners)]
void refineCatmullClarkConnectivity(const PolyMesh& parent, const MeshTopology& topo, const std::vector<Index>& links,
                                    const std::vector<uint8_t>* splitCorner, RefinedConnectivity& out,
                                    const ConnectivityOptions& options = {});

// The tables a refineCatmullClarkConnectivity(..., vertexRings = false, edges = true or false) left
// out, from the same parent, `links` and `splitCorner`: the child's mesh (its points untouched),
// faceParent and topology then equal what the full step gives; its links stay as they were.
// [O(corners)]
void completeChildTopology(const PolyMesh& parent, const MeshTopology& topo, const std::vector<Index>& links,
                           const std::vector<uint8_t>* splitCorner, RefinedConnectivity& child,
                           const ConnectivityOptions& options = {});

}  // namespace polarview
