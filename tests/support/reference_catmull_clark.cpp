// A plain Catmull-Clark step for the tests (see reference_catmull_clark.h).
#include "reference_catmull_clark.h"

#include "core/subdiv/catmull_clark.h"

namespace polarview::reference {

PolyMesh refineCatmullClarkTopology(const PolyMesh& parent, const MeshTopology& topo, std::vector<Index>* faceParent) {
  const Index cornerCount = static_cast<Index>(parent.faceVerts.size());
  PolyMesh child;
  child.points.resize(ccChildVertexCount(topo));
  child.faceStart.resize(size_t(cornerCount) + 1);
  child.faceVerts.resize(size_t(cornerCount) * 4);
  if (faceParent) faceParent->resize(cornerCount);
  Index* out = child.faceVerts.data();
  for (Index f = 0; f < topo.faceCount; ++f) {
    const Index begin = parent.faceStart[f], end = parent.faceStart[f + 1];
    Index previousEdge = topo.cornerEdge[end - 1];
    for (Index c = begin; c < end; ++c) {
      *out++ = ccVertexPoint(topo, parent.faceVerts[c]);
      *out++ = ccEdgePoint(topo, topo.cornerEdge[c]);
      *out++ = ccFacePoint(topo, f);
      *out++ = ccEdgePoint(topo, previousEdge);
      previousEdge = topo.cornerEdge[c];
      if (faceParent) (*faceParent)[c] = f;
    }
  }
  for (Index c = 0; c <= cornerCount; ++c) child.faceStart[c] = 4 * c;
  return child;
}

PolyMesh refineCatmullClark(const PolyMesh& parent, const MeshTopology& topo, std::vector<Index>* faceParent) {
  PolyMesh child = refineCatmullClarkTopology(parent, topo, faceParent);
  computeCatmullClarkPoints(topo, parent, parent.points.data(), child.points.data());
  return child;
}

}  // namespace polarview::reference
