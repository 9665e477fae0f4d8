// Non-manifold meshes as OpenSubdiv refines them (docs/schemes.md, Non-manifold meshes).
//
// OpenSubdiv's Vtr accepts edges with more than two faces, edges whose two faces run them the same
// way (inconsistent orientation), degenerate edges (a face repeating a vertex) and vertices whose
// faces form several fans, and refines them by making those edges infinitely sharp and those
// vertices infinitely sharp corners (Far::TopologyRefinerFactory's prepareComponentTagsAndSharpness;
// a vertex between exactly two non-manifold edges, with no boundary edge and more faces than edges,
// an interior non-manifold crease, is not sharpened). The same points come from a manifold mesh:
// every vertex is copied once per fan of its faces joined by manifold edges (faces keep their ids and
// order; a vertex's first fan keeps its id, the others' copies follow the input's vertices), a
// non-manifold edge becomes one edge per face side, and tags say what OpenSubdiv sharpens:
//  * every copy of a non-manifold edge infinitely sharp (most are boundaries of the split mesh);
//  * every copy of a sharpened non-manifold vertex an infinitely sharp corner;
//  * the input's own creases and corners on their copies;
//  * `interpolateboundary 1` (sharp topological corners) and `0` (faces at boundary vertices become
//    holes) decided on the input's topology and written out as corners and holes, the split mesh
//    then using the edge-only rule (the same points: boundary edges are sharp either way).
// Copies get bit-identical points at every level (a corner stays, a sharp edge's point is its
// midpoint, a crease vertex's reads the same two neighbours), so the split surface is the input's.
#pragma once

#include <string>
#include <vector>

#include "core/mesh/poly_mesh.h"
#include "core/mesh/topology.h"

namespace polarview {

struct ManifoldSplit {
  PolyMesh mesh;                    // manifold, with the tags above; empty when nothing was split
  std::vector<Index> sourceVertex;  // per vertex of `mesh`: the input's vertex (empty: nothing split)
  size_t nonManifoldEdges = 0;      // of the input, counted as Far makes edges (a loop or repeat is one more)
  size_t nonManifoldVertices = 0;

  bool empty() const { return sourceVertex.empty(); }
  // The split mesh's points from the input's. [O(vertices)]
  std::vector<Point> splitPoints(const std::vector<Point>& inputPoints) const;
};

// The manifold split of `mesh` (faces of at least 3 corners, indices in range), or an empty one
// when `mesh` is manifold and consistently oriented. [O(corners log corners)]
ManifoldSplit splitNonManifold(const PolyMesh& mesh);

// The mesh refinements start from, with its tables in `topology`: `mesh` itself when its tables
// build (manifold and consistently oriented: nothing more is done), else its split (kept in
// `storage`). Its first vertex ids are the input's, so a vertex picked on the input names the same
// vertex there. Throws buildTopology's InputError for what even the split cannot refine.
// [O(corners log corners)]
const PolyMesh& refinableMesh(const PolyMesh& mesh, ManifoldSplit& storage, MeshTopology& topology,
                              const std::string& sourceName = "<mesh>");

}  // namespace polarview
