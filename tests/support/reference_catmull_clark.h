// A plain Catmull-Clark step, written apart from the refiner's table-driven one (refine_topology,
// refiner): the tests check the refiner, the OpenSubdiv oracle and the Fig. 14 conversion against it.
#pragma once

#include <vector>

#include "core/mesh/poly_mesh.h"
#include "core/mesh/topology.h"

namespace polarview::reference {

// The child mesh's faces (all quads, one per parent corner: vertex point, edge point of the
// outgoing edge, face point, edge point of the incoming edge); `points` sized F + E + V but unset.
// faceParent (optional) receives each child face's parent face. [O(corners)]
PolyMesh refineCatmullClarkTopology(const PolyMesh& parent, const MeshTopology& topo, std::vector<Index>* faceParent);

// One full step: the faces above, the points by computeCatmullClarkPoints. [O(corners)]
PolyMesh refineCatmullClark(const PolyMesh& parent, const MeshTopology& topo, std::vector<Index>* faceParent = nullptr);

}  // namespace polarview::reference
