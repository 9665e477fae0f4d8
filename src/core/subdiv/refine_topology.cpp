// Catmull-Clark connectivity derived from the parent's tables (see refine_topology.h).
//
// Parent corner c (vertex v, outgoing edge a, incoming edge b, face f) owns child corners
// base(c).. in this order:
//   quad     (V, E_a, F, E_b):            V->E_a, E_a->F, F->E_b, E_b->V
//   split    (V, E_a, F) and (V, F, E_b): V->E_a, E_a->F, F->V | V->F, F->E_b, E_b->V
// so base(c) = 4c + 2 (splits before c). Every child half-edge's twin follows from the parent's:
//   V->E_a  <->  E_a->V of the corner after twin(c)      E_a->F  <->  F->E_a of next(c)
//   F->E_b  <->  E_b->F of prev(c)                        E_b->V  <->  V->E_b of twin(prev(c))
// and every child vertex's ring is read off the parent without walking: the face point's ring runs
// over its face's corners in order, an edge point's over the edge's two corners and their
// successors, a vertex point's over the parent vertex's ring. Rings start where buildTopology's do:
// at the smallest corner (interior) or at the corner leaving along the boundary.
#include "core/subdiv/refine_topology.h"

#include <cassert>

namespace polarview {

std::vector<Index> cornerTwins(const PolyMesh& mesh, const MeshTopology& topo) {
  std::vector<Index> twins(mesh.faceVerts.size(), -1);
  const Index* faceStart = mesh.faceStart.data();
  // Consecutive ring corners r_i, r_i+1 at v: r_i+1 starts the opposite half-edge of r_i's incoming one.
  for (Index v = 0; v < topo.vertexCount; ++v) {
    const Index first = topo.vertexFaceStart[v], last = topo.vertexFaceStart[v + 1];
    for (Index i = first; i < last; ++i) {
      const Index corner = topo.vertexCorners[i], face = topo.vertexFaces[i];
      const Index incoming = corner == faceStart[face] ? faceStart[face + 1] - 1 : corner - 1;
      const bool lastOfBoundaryFan = i + 1 == last && topo.vertexOnBoundary[v];
      twins[incoming] = lastOfBoundaryFan ? -1 : topo.vertexCorners[i + 1 == last ? first : i + 1];
    }
  }
  return twins;
}

namespace {

template <bool kSplit>
class ConnectivityBuilder {
 public:
  ConnectivityBuilder(const PolyMesh& parent, const MeshTopology& topo, const std::vector<Index>& twins,
                      const uint8_t* splitCorner, RefinedConnectivity& out)
      : parent_(parent), topo_(topo), parentTwins_(twins.data()), split_(splitCorner), out_(out) {}

  void build() {
    countAndSize();
    buildFacesAndEdges();
    buildVertexRings();
  }

 private:
  // Parent corner navigation.
  Index parentNext(Index c) const {
    const Index f = topo_.cornerFace[c];
    return c + 1 == parent_.faceStart[f + 1] ? parent_.faceStart[f] : c + 1;
  }
  bool isSplit(Index c) const { return kSplit && split_[c]; }
  // The child face (the first of two when split) and first child corner of parent corner c.
  Index childFace(Index c) const { return kSplit ? firstChildFace_[c] : c; }
  Index base(Index c) const { return kSplit ? 2 * (c + firstChildFace_[c]) : 4 * c; }
  // Child corners of parent corner c by the half-edge they start, and the face holding the last two.
  Index vertexToEdge(Index c) const { return base(c); }
  Index edgeToFace(Index c) const { return base(c) + 1; }
  Index faceToEdge(Index c) const { return base(c) + (isSplit(c) ? 4 : 2); }
  Index edgeToVertex(Index c) const { return base(c) + (isSplit(c) ? 5 : 3); }
  Index secondChildFace(Index c) const { return childFace(c) + (isSplit(c) ? 1 : 0); }

  // Child counts: F + E + V vertices, one face per corner (+1 per split), 2 edges per parent edge
  // and 1 per corner (+1 per split).
  void countAndSize() {
    const Index C = static_cast<Index>(parent_.faceVerts.size());
    splitCount_ = 0;
    if (kSplit) {
      firstChildFace_.resize(C);
      for (Index c = 0; c < C; ++c) {
        firstChildFace_[c] = c + splitCount_;
        splitCount_ += split_[c] ? 1 : 0;
      }
    }
    vertexPointBase_ = topo_.faceCount + topo_.edgeCount;
    childCorners_ = 4 * C + 2 * splitCount_;

    MeshTopology& t = out_.topology;
    t.vertexCount = topo_.faceCount + topo_.edgeCount + topo_.vertexCount;
    t.faceCount = C + splitCount_;
    t.edgeCount = 2 * topo_.edgeCount + C + splitCount_;
    PolyMesh& mesh = out_.mesh;
    mesh.points.resize(t.vertexCount);
    mesh.faceStart.resize(size_t(t.faceCount) + 1);
    mesh.faceVerts.resize(childCorners_);
    mesh.faceLine.clear();
    out_.faceParent.resize(t.faceCount);
    out_.twins.resize(childCorners_);
    t.cornerEdge.resize(childCorners_);
    t.cornerFace.resize(childCorners_);
    t.edgeVerts.resize(2 * size_t(t.edgeCount));
    t.edgeFaces.resize(2 * size_t(t.edgeCount));
  }

  // Writes child corner x (vertex -> nextVertex in `face`, opposite half-edge `twin`) and numbers
  // its edge by first use: the smaller corner of a twin pair opens the edge.
  void emitCorner(Index x, Index vertex, Index nextVertex, Index face, Index twin) {
    faceVerts_[x] = vertex;
    cornerFace_[x] = face;
    twinsOut_[x] = twin;
    if (twin < 0 || twin > x) {
      const Index e = nextEdge_++;
      cornerEdge_[x] = e;
      edgeVerts_[2 * e] = vertex;
      edgeVerts_[2 * e + 1] = nextVertex;
      edgeFaces_[2 * e] = face;
      edgeFaces_[2 * e + 1] = -1;
    } else {
      const Index e = cornerEdge_[twin];
      cornerEdge_[x] = e;
      edgeFaces_[2 * e + 1] = face;
    }
  }

  // Faces, twins and edges in one pass over the parent corners (child corners in increasing order).
  void buildFacesAndEdges() {
    MeshTopology& t = out_.topology;
    faceVerts_ = out_.mesh.faceVerts.data();
    cornerFace_ = t.cornerFace.data();
    cornerEdge_ = t.cornerEdge.data();
    edgeVerts_ = t.edgeVerts.data();
    edgeFaces_ = t.edgeFaces.data();
    twinsOut_ = out_.twins.data();
    Index* faceStart = out_.mesh.faceStart.data();
    Index* faceParent = out_.faceParent.data();
    nextEdge_ = 0;
    faceStart[0] = 0;

    const Index* parentVerts = parent_.faceVerts.data();
    const Index* parentEdge = topo_.cornerEdge.data();
    const Index edgePointBase = topo_.faceCount;
    for (Index f = 0; f < topo_.faceCount; ++f) {
      const Index begin = parent_.faceStart[f], end = parent_.faceStart[f + 1];
      for (Index c = begin; c < end; ++c) {
        const Index prev = c == begin ? end - 1 : c - 1, next = c + 1 == end ? begin : c + 1;
        const Index V = vertexPointBase_ + parentVerts[c], Ea = edgePointBase + parentEdge[c],
                    Eb = edgePointBase + parentEdge[prev], F = f;
        const Index twinC = parentTwins_[c], twinPrev = parentTwins_[prev];
        const Index twinVE = twinC < 0 ? -1 : edgeToVertex(parentNext(twinC));
        const Index twinEF = faceToEdge(next);
        const Index twinFE = edgeToFace(prev);
        const Index twinEV = twinPrev < 0 ? -1 : vertexToEdge(twinPrev);
        const Index x = base(c), face = childFace(c);
        emitCorner(x, V, Ea, face, twinVE);
        emitCorner(x + 1, Ea, F, face, twinEF);
        faceParent[face] = f;
        if (!isSplit(c)) {
          emitCorner(x + 2, F, Eb, face, twinFE);
          emitCorner(x + 3, Eb, V, face, twinEV);
          faceStart[face + 1] = x + 4;
        } else {  // the diagonal V - F closes the first triangle and opens the second
          emitCorner(x + 2, F, V, face, x + 3);
          faceStart[face + 1] = x + 3;
          emitCorner(x + 3, V, F, face + 1, x + 2);
          emitCorner(x + 4, F, Eb, face + 1, twinFE);
          emitCorner(x + 5, Eb, V, face + 1, twinEV);
          faceStart[face + 2] = x + 6;
          faceParent[face + 1] = f;
        }
      }
    }
    assert(nextEdge_ == t.edgeCount);
  }

  // Appends (face, corner) to the ring of the current child vertex.
  void put(Index face, Index corner) {
    vertexFaces_[facePos_] = face;
    vertexCorners_[facePos_++] = corner;
    vertexEdges_[edgePos_++] = cornerEdge_[corner];
  }
  // Ends the current child vertex's ring (a boundary ring ends with its incoming boundary edge).
  void closeRing(bool onBoundary, Index boundaryEdge) {
    MeshTopology& t = out_.topology;
    if (onBoundary) vertexEdges_[edgePos_++] = boundaryEdge;
    t.vertexOnBoundary[vertex_] = onBoundary;
    t.vertexUsed[vertex_] = facePos_ > t.vertexFaceStart[vertex_];
    ++vertex_;
    t.vertexFaceStart[vertex_] = facePos_;
    t.vertexEdgeStart[vertex_] = edgePos_;
  }

  void buildVertexRings() {
    MeshTopology& t = out_.topology;
    // One edge more than faces per boundary vertex: edge points of boundary edges, boundary vertex points.
    Index boundaryEdges = 0, boundaryVertices = 0;
    for (Index e = 0; e < topo_.edgeCount; ++e) boundaryEdges += topo_.edgeFaces[2 * e + 1] < 0 ? 1 : 0;
    for (Index v = 0; v < topo_.vertexCount; ++v) boundaryVertices += topo_.vertexOnBoundary[v];
    t.vertexFaceStart.resize(size_t(t.vertexCount) + 1);
    t.vertexEdgeStart.resize(size_t(t.vertexCount) + 1);
    t.vertexFaces.resize(childCorners_);
    t.vertexCorners.resize(childCorners_);
    t.vertexEdges.resize(size_t(childCorners_) + boundaryEdges + boundaryVertices);
    t.vertexOnBoundary.resize(t.vertexCount);
    t.vertexUsed.resize(t.vertexCount);
    vertexFaces_ = t.vertexFaces.data();
    vertexCorners_ = t.vertexCorners.data();
    vertexEdges_ = t.vertexEdges.data();
    vertex_ = facePos_ = edgePos_ = 0;
    t.vertexFaceStart[0] = t.vertexEdgeStart[0] = 0;
    buildFacePointRings();
    buildEdgePointRings();
    buildVertexPointRings();
    assert(vertex_ == t.vertexCount && facePos_ == childCorners_);
  }

  // Face point of f: the corners of f in order; a split corner contributes its second triangle,
  // then its first (the walk crosses the diagonal). Starts at the first corner's first face.
  void buildFacePointRings() {
    for (Index f = 0; f < topo_.faceCount; ++f) {
      const Index begin = parent_.faceStart[f], end = parent_.faceStart[f + 1];
      for (Index c = begin; c < end; ++c) {
        if (isSplit(c) && c != begin) put(childFace(c) + 1, base(c) + 4);
        put(childFace(c), base(c) + 2);
      }
      if (isSplit(begin)) put(childFace(begin) + 1, base(begin) + 4);
      closeRing(false, -1);
    }
  }

  // Edge point of e, led by corner c (twin d): E->F(c), E->V(next d), E->F(d), E->V(next c),
  // rotated to start at the smallest; on a boundary E->V(next c), E->F(c), then the edge to V(c).
  // Edges are numbered by their leading corner, so leaders in corner order visit them in order.
  void buildEdgePointRings() {
    for (Index f = 0; f < topo_.faceCount; ++f) {
      const Index begin = parent_.faceStart[f], end = parent_.faceStart[f + 1];
      for (Index c = begin; c < end; ++c) {
        const Index d = parentTwins_[c];
        if (d >= 0 && d < c) continue;  // not the edge's leading corner
        const Index next = c + 1 == end ? begin : c + 1;
        if (d < 0) {
          put(secondChildFace(next), edgeToVertex(next));
          put(childFace(c), edgeToFace(c));
          closeRing(true, cornerEdge_[vertexToEdge(c)]);
          continue;
        }
        const Index nextD = parentNext(d);
        const Index faces[4] = {childFace(c), secondChildFace(nextD), childFace(d), secondChildFace(next)};
        const Index corners[4] = {edgeToFace(c), edgeToVertex(nextD), edgeToFace(d), edgeToVertex(next)};
        int start = 0;
        for (int i = 1; i < 4; ++i)
          if (corners[i] < corners[start]) start = i;
        for (int i = 0; i < 4; ++i) put(faces[(start + i) & 3], corners[(start + i) & 3]);
        closeRing(false, -1);
      }
    }
  }

  // Vertex point of v: the parent ring's corners in the parent's order (a split corner gives both
  // triangles); a boundary ring ends with the edge into the last corner.
  void buildVertexPointRings() {
    for (Index v = 0; v < topo_.vertexCount; ++v) {
      const Index first = topo_.vertexFaceStart[v], last = topo_.vertexFaceStart[v + 1];
      for (Index i = first; i < last; ++i) {
        const Index c = topo_.vertexCorners[i];
        put(childFace(c), base(c));
        if (isSplit(c)) put(childFace(c) + 1, base(c) + 3);
      }
      const bool onBoundary = topo_.vertexOnBoundary[v];
      closeRing(onBoundary, onBoundary ? cornerEdge_[edgeToVertex(topo_.vertexCorners[last - 1])] : -1);
    }
  }

  const PolyMesh& parent_;
  const MeshTopology& topo_;
  const Index* parentTwins_;
  const uint8_t* split_;
  RefinedConnectivity& out_;

  std::vector<Index> firstChildFace_;  // split mode: per parent corner, its first child face
  Index splitCount_ = 0, vertexPointBase_ = 0, childCorners_ = 0;

  // Output cursors and table pointers.
  Index nextEdge_ = 0, vertex_ = 0, facePos_ = 0, edgePos_ = 0;
  Index *faceVerts_ = nullptr, *cornerFace_ = nullptr, *cornerEdge_ = nullptr, *edgeVerts_ = nullptr,
        *edgeFaces_ = nullptr, *twinsOut_ = nullptr;
  Index *vertexFaces_ = nullptr, *vertexCorners_ = nullptr, *vertexEdges_ = nullptr;
};

}  // namespace

void refineCatmullClarkConnectivity(const PolyMesh& parent, const MeshTopology& topo, const std::vector<Index>& twins,
                                    const std::vector<uint8_t>* splitCorner, RefinedConnectivity& out) {
  if (splitCorner)
    ConnectivityBuilder<true>(parent, topo, twins, splitCorner->data(), out).build();
  else
    ConnectivityBuilder<false>(parent, topo, twins, nullptr, out).build();
}

}  // namespace polarview
