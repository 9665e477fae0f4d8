// Catmull-Clark refinement (Catmull & Clark 1978) with OpenSubdiv 3.5's rules and options
// (docs/schemes.md, Catmull-Clark). The point rules are straight loops over MeshTopology's flat tables.
#include "core/subdiv/catmull_clark.h"

#include <stdexcept>

#include "core/subdiv/parallel_for.h"

namespace polarview {

namespace {

// Smooth vertex rule of valence k: ((k-2)/k) v + (1/k^2) sum(edge ends) + (1/k^2) sum(face points).
inline double smoothVertexWeight(double k) { return (k - 2.0) / k; }
inline double smoothNeighbourWeight(double k) { return 1.0 / (k * k); }

// Crease rule on a boundary (VTX_BOUNDARY_EDGE_ONLY: corners of one face too): 3/4 v + 1/8 (a + b).
constexpr double kBoundaryVertexWeight = 0.75;
constexpr double kBoundaryNeighbourWeight = 0.125;

// Limit masks: smooth valence k, and the boundary crease (1/6, 2/3, 1/6).
inline double limitVertexWeight(double k) { return k / (k + 5.0); }
inline double limitEdgeWeight(double k) { return 4.0 / (k * (k + 5.0)); }
inline double limitDiagonalWeight(double k) { return 1.0 / (k * (k + 5.0)); }
constexpr double kLimitBoundaryVertexWeight = 2.0 / 3.0;
constexpr double kLimitBoundaryNeighbourWeight = 1.0 / 6.0;

// The two boundary neighbours of a boundary vertex: ends of the first and last edges of its ring.
inline void boundaryNeighbours(const MeshTopology& t, Index v, Index& a, Index& b) {
  a = t.otherEnd(t.vertexEdges[t.vertexEdgeStart[v]], v);
  b = t.otherEnd(t.vertexEdges[t.vertexEdgeStart[v + 1] - 1], v);
}

}  // namespace

PolyMesh refineCatmullClarkTopology(const PolyMesh& parent, const MeshTopology& topo, std::vector<Index>* faceParent) {
  const Index cornerCount = static_cast<Index>(parent.faceVerts.size());
  PolyMesh child;
  child.points.resize(ccChildVertexCount(topo));
  child.faceStart.resize(size_t(cornerCount) + 1);
  child.faceVerts.resize(size_t(cornerCount) * 4);
  if (faceParent) faceParent->resize(cornerCount);

  // One quad per parent corner: (vertex point, edge point of the outgoing edge, face point,
  // edge point of the incoming edge) keeps the parent's orientation.
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

namespace {

// Face points of faces [begin, end): centroids of any n-gon.
void computeFacePoints(const PolyMesh& parent, const Point* p, Point* facePoints, Index begin, Index end) {
  const Index* faceStart = parent.faceStart.data();
  const Index* faceVerts = parent.faceVerts.data();
  for (Index f = begin; f < end; ++f) {
    const Index* loop = faceVerts + faceStart[f];
    const Index k = faceStart[f + 1] - faceStart[f];
    if (k == 4) {  // the common case after one level: no loop, no division
      facePoints[f] = 0.25 * ((p[loop[0]] + p[loop[1]]) + (p[loop[2]] + p[loop[3]]));
      continue;
    }
    Point sum(0.0);
    for (Index i = 0; i < k; ++i) sum += p[loop[i]];
    facePoints[f] = sum * (1.0 / double(k));
  }
}

// Edge points of edges [begin, end): midpoint on the boundary, 1/4 (v0 + v1 + f0 + f1) inside.
void computeEdgePoints(const MeshTopology& topo, const Point* p, const Point* facePoints, Point* edgePoints, Index begin,
                       Index end) {
  const Index* edgeVerts = topo.edgeVerts.data();
  const Index* edgeFaces = topo.edgeFaces.data();
  for (Index e = begin; e < end; ++e) {
    const Point ends = p[edgeVerts[2 * e]] + p[edgeVerts[2 * e + 1]];
    if (edgeFaces[2 * e + 1] < 0)
      edgePoints[e] = 0.5 * ends;
    else
      edgePoints[e] = 0.25 * (ends + facePoints[edgeFaces[2 * e]] + facePoints[edgeFaces[2 * e + 1]]);
  }
}

// Vertex points of vertices [begin, end): crease rule on the boundary, smooth rule inside, unused
// vertices copied.
void computeVertexPoints(const MeshTopology& topo, const Point* p, const Point* facePoints, Point* vertexPoints, Index begin,
                         Index end) {
  const Index* edgeVerts = topo.edgeVerts.data();
  const Index* vertexEdgeStart = topo.vertexEdgeStart.data();
  const Index* vertexEdges = topo.vertexEdges.data();
  const Index* vertexFaceStart = topo.vertexFaceStart.data();
  const Index* vertexFaces = topo.vertexFaces.data();
  for (Index v = begin; v < end; ++v) {
    if (!topo.vertexUsed[v]) {
      vertexPoints[v] = p[v];
    } else if (topo.vertexOnBoundary[v]) {
      Index a, b;
      boundaryNeighbours(topo, v, a, b);
      vertexPoints[v] = kBoundaryVertexWeight * p[v] + kBoundaryNeighbourWeight * (p[a] + p[b]);
    } else {
      Point sum(0.0);
      for (Index i = vertexEdgeStart[v]; i < vertexEdgeStart[v + 1]; ++i) {
        const Index e = vertexEdges[i];
        sum += p[edgeVerts[2 * e] ^ edgeVerts[2 * e + 1] ^ v];  // the end that is not v, branch-free
      }
      for (Index i = vertexFaceStart[v]; i < vertexFaceStart[v + 1]; ++i) sum += facePoints[vertexFaces[i]];
      const double k = double(vertexEdgeStart[v + 1] - vertexEdgeStart[v]);
      vertexPoints[v] = smoothVertexWeight(k) * p[v] + smoothNeighbourWeight(k) * sum;
    }
  }
}

}  // namespace

void computeCatmullClarkPoints(const MeshTopology& topo, const PolyMesh& parent, const Point* parentPoints,
                               Point* childPoints, unsigned threads) {
  Point* facePoints = childPoints;
  Point* edgePoints = childPoints + topo.faceCount;
  Point* vertexPoints = childPoints + topo.faceCount + topo.edgeCount;
  // Each point depends only on parent points and face points, so ranges run on separate threads
  // with results independent of the split; face points first, as the others read them.
  const unsigned parts = threads ? threads : threadsFor(parent.faceVerts.size());
  parallelRanges(topo.faceCount, parts,
                 [&](Index begin, Index end) { computeFacePoints(parent, parentPoints, facePoints, begin, end); });
  runParts(parts, [&](unsigned k) {
    computeEdgePoints(topo, parentPoints, facePoints, edgePoints, partBound(topo.edgeCount, parts, k),
                      partBound(topo.edgeCount, parts, k + 1));
    computeVertexPoints(topo, parentPoints, facePoints, vertexPoints, partBound(topo.vertexCount, parts, k),
                        partBound(topo.vertexCount, parts, k + 1));
  });
}

PolyMesh refineCatmullClark(const PolyMesh& parent, const MeshTopology& topo, std::vector<Index>* faceParent) {
  PolyMesh child = refineCatmullClarkTopology(parent, topo, faceParent);
  computeCatmullClarkPoints(topo, parent, parent.points.data(), child.points.data());
  return child;
}

std::vector<Point> catmullClarkLimitPoints(const MeshTopology& topo, const PolyMesh& mesh) {
  const Point* p = mesh.points.data();
  std::vector<Point> limit(mesh.points);
  for (Index v = 0; v < topo.vertexCount; ++v) {
    if (!topo.vertexUsed[v]) continue;
    for (Index i = topo.vertexFaceStart[v]; i < topo.vertexFaceStart[v + 1]; ++i)
      if (mesh.faceSize(topo.vertexFaces[i]) != 4)
        throw std::invalid_argument("catmullClarkLimitPoints: vertex " + std::to_string(v) + " touches a face that is not a quad");
    if (topo.vertexOnBoundary[v]) {
      Index a, b;
      boundaryNeighbours(topo, v, a, b);
      limit[v] = kLimitBoundaryVertexWeight * p[v] + kLimitBoundaryNeighbourWeight * (p[a] + p[b]);
      continue;
    }
    Point edgeSum(0.0), diagonalSum(0.0);
    for (Index i = topo.vertexEdgeStart[v]; i < topo.vertexEdgeStart[v + 1]; ++i) edgeSum += p[topo.otherEnd(topo.vertexEdges[i], v)];
    for (Index i = topo.vertexFaceStart[v]; i < topo.vertexFaceStart[v + 1]; ++i) {
      // The quad's corner opposite v is two steps around the face from v's corner.
      const Index f = topo.vertexFaces[i], corner = topo.vertexCorners[i] - mesh.faceStart[f];
      diagonalSum += p[mesh.faceVerts[mesh.faceStart[f] + (corner + 2) % 4]];
    }
    const double k = double(topo.valence(v));
    limit[v] = limitVertexWeight(k) * p[v] + limitEdgeWeight(k) * edgeSum + limitDiagonalWeight(k) * diagonalSum;
  }
  return limit;
}

}  // namespace polarview
