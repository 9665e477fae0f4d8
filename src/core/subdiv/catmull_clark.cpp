// Catmull-Clark refinement (Catmull & Clark 1978) with OpenSubdiv 3.5's rules and options
// (docs/schemes.md, Catmull-Clark). The point rules are straight loops over MeshTopology's flat tables.
#include "core/subdiv/catmull_clark.h"

#include <algorithm>
#include <memory>
#include <stdexcept>

#include "core/subdiv/parallel_for.h"
#include "core/subdiv/prefetch.h"

namespace polarview {

namespace {

// Smooth vertex rule of valence k: ((k-2)/k) v + (1/k^2) sum(edge ends) + (1/k^2) sum(face points).
inline double smoothVertexWeight(double k) { return (k - 2.0) / k; }
inline double smoothNeighbourWeight(double k) { return 1.0 / (k * k); }

// Crease rule on a boundary (VTX_BOUNDARY_EDGE_ONLY: corners of one face too): 3/4 v + 1/8 (a + b).
constexpr double kBoundaryVertexWeight = 0.75;
constexpr double kBoundaryNeighbourWeight = 0.125;

// Limit mask of the boundary crease (1/6, 2/3, 1/6); the smooth one: catmullClarkLimitMask.
constexpr double kLimitBoundaryVertexWeight = 2.0 / 3.0;
constexpr double kLimitBoundaryNeighbourWeight = 1.0 / 6.0;

// The two boundary neighbours of a boundary vertex: ends of the first and last edges of its ring.
inline void boundaryNeighbours(const MeshTopology& t, Index v, Index& a, Index& b) {
  a = t.otherEnd(t.vertexEdges[t.vertexEdgeStart[v]], v);
  b = t.otherEnd(t.vertexEdges[t.vertexEdgeStart[v + 1] - 1], v);
}

}  // namespace

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

// [SECTION] sharpness (OpenSubdiv's Sdc::Crease)

constexpr float kInfinite = float(kInfiniteSharpness);

// Sdc::Crease::decrementSharpness: one level less sharp; infinite stays, 1 or less becomes smooth.
float decrementSharpness(float s) {
  if (s <= 0.0f) return 0.0f;
  if (s >= kInfinite) return kInfinite;
  return s > 1.0f ? s - 1.0f : 0.0f;
}

// How a level's sharpness decays a level down: Sdc::Crease::SubdivideEdgeSharpnessAtVertex (each
// half of an edge from the end it touches) and SubdivideVertexSharpness. Chaikin needs each
// vertex's semi-sharp edges: their count and sum, gathered once.
class SharpnessDecay {
 public:
  SharpnessDecay(const MeshTopology& topo, const CreaseSharpness& sharpness) : topo_(topo), s_(sharpness) {
    if (!s_.chaikin) return;
    semiSharpCount_.assign(size_t(topo.vertexCount), 0);
    semiSharpSum_.assign(size_t(topo.vertexCount), 0.0f);
    for (Index v = 0; v < topo.vertexCount; ++v) {
      // In float and in ring order, as OpenSubdiv sums (its vertex-edge order is the same
      // rotation; osd_oracle_test): with three or more edges the rounding depends on the order.
      float sum = 0.0f;
      for (Index i = topo.vertexEdgeStart[v]; i < topo.vertexEdgeStart[v + 1]; ++i) {
        const float x = s_.edge[topo.vertexEdges[i]];
        if (x > 0.0f && x < kInfinite) {
          ++semiSharpCount_[v];
          sum += x;
        }
      }
      semiSharpSum_[v] = sum;
    }
  }

  // The sharpness of the half of edge e at its end v, a level down.
  float edgeAt(Index e, Index v) const {
    float x = s_.edge[e];
    if (!s_.chaikin || topo_.valence(v) < 2) return decrementSharpness(x);
    if (x <= 0.0f) return 0.0f;
    if (x >= kInfinite) return kInfinite;
    const int count = semiSharpCount_[v];
    if (count > 1) {
      const float othersMean = (semiSharpSum_[v] - x) / float(count - 1);
      x = 0.75f * x + 0.25f * othersMean;
    }
    x -= 1.0f;
    return x > 0.0f ? x : 0.0f;
  }
  float vertex(Index v) const { return decrementSharpness(s_.vertex[v]); }

 private:
  const MeshTopology& topo_;
  const CreaseSharpness& s_;
  std::vector<int> semiSharpCount_;
  std::vector<float> semiSharpSum_;
};

// Sdc::Crease::Rule without DART, which refines as SMOOTH: from the vertex's sharpness and the
// number of sharp edges at it.
enum class VertexRule { Smooth, Crease, Corner };
VertexRule vertexRule(float vertexSharpness, int sharpEdges) {
  if (vertexSharpness > 0.0f || sharpEdges > 2) return VertexRule::Corner;
  return sharpEdges == 2 ? VertexRule::Crease : VertexRule::Smooth;
}

// [SECTION] point rules

// Smooth edge point 1/4 (v0 + v1 + f0 + f1), or (1 - w) of it plus w of the midpoint: the
// transition of an edge of sharpness w not both of whose halves stay sharp (Sdc
// ComputeEdgeVertexMask; w is not clamped to 1 there either).
inline Point edgePoint(const Point& ends, const Point& faces, double crease, double endWeight = 0.25, double faceWeight = 0.25) {
  return (crease * 0.5 + (1.0 - crease) * endWeight) * ends + (1.0 - crease) * faceWeight * faces;
}

// Sdc's smooth edge mask under TRI_SUB_SMOOTH (catmarkScheme.h, "mimics Hbr's order of
// operations"): a triangle's face weighs 0.47, a quad's 0.25, both faces get their mean and the
// ends the rest. False (weights untouched) when neither face is a triangle.
bool smoothTriangleWeights(Index size0, Index size1, double& endWeight, double& faceWeight) {
  if (size0 != 3 && size1 != 3) return false;
  const double f0 = size0 == 3 ? 0.470 : 0.25, f1 = size1 == 3 ? 0.470 : 0.25;
  faceWeight = 0.5 * (f0 + f1);
  endWeight = 0.5 * (1.0 - 2.0 * faceWeight);
  return true;
}

// Smooth vertex point of an interior vertex of valence k (also a dart's).
inline Point smoothVertexPoint(const MeshTopology& topo, const Point* p, const Point* facePoints, Index v) {
  // Edge neighbours and face points in one loop (an interior ring has as many of each): their
  // loads, scattered over two large arrays, are in flight together.
  Point edgeSum(0.0), faceSum(0.0);
  const Index e0 = topo.vertexEdgeStart[v], f0 = topo.vertexFaceStart[v];
  const Index edges = topo.vertexEdgeStart[v + 1] - e0, faces = topo.vertexFaceStart[v + 1] - f0;
  const Index both = std::min(edges, faces);
  for (Index i = 0; i < both; ++i) {
    const Index e = topo.vertexEdges[e0 + i];
    edgeSum += p[topo.edgeVerts[2 * e] ^ topo.edgeVerts[2 * e + 1] ^ v];  // the end that is not v, branch-free
    faceSum += facePoints[topo.vertexFaces[f0 + i]];
  }
  for (Index i = both; i < edges; ++i) {
    const Index e = topo.vertexEdges[e0 + i];
    edgeSum += p[topo.edgeVerts[2 * e] ^ topo.edgeVerts[2 * e + 1] ^ v];
  }
  for (Index i = both; i < faces; ++i) faceSum += facePoints[topo.vertexFaces[f0 + i]];
  const double k = double(edges);
  return smoothVertexWeight(k) * p[v] + smoothNeighbourWeight(k) * (edgeSum + faceSum);
}

// Edge points of edges [begin, end) into edgePoints[i] (or, with `ids`, of edges ids[i]: a sparse
// step's): midpoint on the boundary, 1/4 (v0 + v1 + f0 + f1) inside; with `sharpness` (and its
// `decay`), the crease rules.
void computeEdgePoints(const MeshTopology& topo, const PolyMesh& parent, const Point* p, const Point* facePoints, Point* edgePoints,
                       Index begin, Index end, const CreaseSharpness* sharpness, const SharpnessDecay* decay,
                       const Index* ids = nullptr) {
  const Index* edgeVerts = topo.edgeVerts.data();
  const Index* edgeFaces = topo.edgeFaces.data();
  const bool smoothTriangles = sharpness && sharpness->smoothTriangles;
  for (Index i = begin; i < end; ++i) {
    const Index e = ids ? ids[i] : i;
    const Point ends = p[edgeVerts[2 * e]] + p[edgeVerts[2 * e + 1]];
    const float s = sharpness ? sharpness->edge[e] : 0.0f;
    const bool staysSharp = s > 0.0f && decay->edgeAt(e, edgeVerts[2 * e]) > 0.0f && decay->edgeAt(e, edgeVerts[2 * e + 1]) > 0.0f;
    double endWeight = 0.25, faceWeight = 0.25;
    if (edgeFaces[2 * e + 1] < 0 || staysSharp)
      edgePoints[i] = 0.5 * ends;  // the boundary always
    else if (smoothTriangles && smoothTriangleWeights(parent.faceSize(edgeFaces[2 * e]), parent.faceSize(edgeFaces[2 * e + 1]), endWeight, faceWeight))
      edgePoints[i] = edgePoint(ends, facePoints[edgeFaces[2 * e]] + facePoints[edgeFaces[2 * e + 1]], double(std::max(s, 0.0f)),
                                endWeight, faceWeight);
    else if (s > 0.0f)
      edgePoints[i] = edgePoint(ends, facePoints[edgeFaces[2 * e]] + facePoints[edgeFaces[2 * e + 1]], double(s));
    else
      edgePoints[i] = 0.25 * (ends + facePoints[edgeFaces[2 * e]] + facePoints[edgeFaces[2 * e + 1]]);
  }
}

// The vertex point of a vertex at or near sharp features (Sdc ComputeVertexVertexMask): the
// parent's rule, and where the child's rule differs, OpenSubdiv's fractional weight of the
// parent's mask plus the rest of the child's.
Point sharpVertexPoint(const MeshTopology& topo, const Point* p, const Point* facePoints, const CreaseSharpness& sharpness,
                       const SharpnessDecay& decay, Index v) {
  const float parentVertex = sharpness.vertex[v], childVertex = decay.vertex(v);
  // Sharp edges now and a level down: count, and the far ends of the first and last (a crease's two).
  int parentSharp = 0, childSharp = 0;
  Index parentEnds[2] = {v, v}, childEnds[2] = {v, v};
  float transitionSum = 0.0f;  // in float and ring order, as OpenSubdiv (see SharpnessDecay)
  int transitions = 0;
  if (parentVertex > 0.0f && childVertex <= 0.0f) {
    transitionSum = parentVertex;
    transitions = 1;
  }
  for (Index i = topo.vertexEdgeStart[v]; i < topo.vertexEdgeStart[v + 1]; ++i) {
    const Index e = topo.vertexEdges[i];
    const float s = sharpness.edge[e];
    if (s <= 0.0f) continue;
    const Index far = topo.otherEnd(e, v);
    parentEnds[parentSharp++ == 0 ? 0 : 1] = far;
    if (decay.edgeAt(e, v) > 0.0f) {
      childEnds[childSharp++ == 0 ? 0 : 1] = far;
    } else {  // the edge decays to smooth here (under CREASE_UNIFORM: exactly when s <= 1)
      transitionSum += s;
      ++transitions;
    }
  }
  if (parentSharp == 1) parentEnds[1] = parentEnds[0];
  if (childSharp == 1) childEnds[1] = childEnds[0];
  auto pointByRule = [&](VertexRule rule, const Index ends[2]) {
    switch (rule) {
      case VertexRule::Smooth: return smoothVertexPoint(topo, p, facePoints, v);
      case VertexRule::Crease: return kBoundaryVertexWeight * p[v] + kBoundaryNeighbourWeight * (p[ends[0]] + p[ends[1]]);
      case VertexRule::Corner: break;
    }
    return p[v];
  };
  const VertexRule parentRule = vertexRule(parentVertex, parentSharp);
  const Point parentPoint = pointByRule(parentRule, parentEnds);
  if (parentRule == VertexRule::Smooth) return parentPoint;  // a smooth or dart vertex never blends
  const VertexRule childRule = vertexRule(childVertex, childSharp);
  if (childRule == parentRule) return parentPoint;
  // Sdc::Crease::ComputeFractionalWeightAtVertex, in float as there.
  const float weight = transitions == 0 ? 0.0f : std::min(1.0f, transitionSum / float(transitions));
  return double(weight) * parentPoint + (1.0 - double(weight)) * pointByRule(childRule, childEnds);
}

// Vertex points of vertices [begin, end) into vertexPoints[i] (or, with `ids`, of vertices ids[i]):
// crease rule on the boundary, smooth rule inside, unused vertices copied; with `sharpness`, the
// rules of sharp features.
void computeVertexPoints(const MeshTopology& topo, const Point* p, const Point* facePoints, Point* vertexPoints, Index begin,
                         Index end, const CreaseSharpness* sharpness, const SharpnessDecay* decay, const Index* ids = nullptr) {
  // The rings' reads are scattered over the level: fetched in two stages ahead of their use (the
  // face points and edge ends 16 vertices ahead, the neighbours' points through those ends 8
  // ahead): 10-18% off the positions of a 10,000-quad torus at level 5, one core.
  constexpr Index kAhead = 8;  // vertices
  for (Index i = begin; i < end; ++i) {
    const Index v = ids ? ids[i] : i;
    if (i + 2 * kAhead < end) {
      const Index w = ids ? ids[i + 2 * kAhead] : i + 2 * kAhead;
      for (Index k = topo.vertexFaceStart[w]; k < topo.vertexFaceStart[w + 1]; ++k) prefetch(facePoints + topo.vertexFaces[k]);
      for (Index k = topo.vertexEdgeStart[w]; k < topo.vertexEdgeStart[w + 1]; ++k)
        prefetch(topo.edgeVerts.data() + 2 * topo.vertexEdges[k]);
      const Index u = ids ? ids[i + kAhead] : i + kAhead;
      for (Index k = topo.vertexEdgeStart[u]; k < topo.vertexEdgeStart[u + 1]; ++k) {
        const Index e = topo.vertexEdges[k];
        prefetch(p + (topo.edgeVerts[2 * e] ^ topo.edgeVerts[2 * e + 1] ^ u));
      }
    }
    if (!topo.vertexUsed[v]) {
      vertexPoints[i] = p[v];
    } else if (sharpness) {
      vertexPoints[i] = sharpVertexPoint(topo, p, facePoints, *sharpness, *decay, v);
    } else if (topo.vertexOnBoundary[v]) {
      Index a, b;
      boundaryNeighbours(topo, v, a, b);
      vertexPoints[i] = kBoundaryVertexWeight * p[v] + kBoundaryNeighbourWeight * (p[a] + p[b]);
    } else {
      vertexPoints[i] = smoothVertexPoint(topo, p, facePoints, v);
    }
  }
}

// Both computeCatmullClarkPoints: each point depends only on parent points and face points, so
// ranges run on separate threads with results independent of the split; face points first, as
// the others read them.
void computePoints(const MeshTopology& topo, const PolyMesh& parent, const Point* parentPoints, Point* childPoints,
                   const CreaseSharpness* sharpness, unsigned threads) {
  Point* facePoints = childPoints;
  Point* edgePoints = childPoints + topo.faceCount;
  Point* vertexPoints = childPoints + topo.faceCount + topo.edgeCount;
  const unsigned parts = threads ? threads : threadsFor(parent.faceVerts.size());
  std::unique_ptr<SharpnessDecay> decay;
  if (sharpness) decay = std::make_unique<SharpnessDecay>(topo, *sharpness);
  parallelRanges(topo.faceCount, parts,
                 [&](Index begin, Index end) { computeFacePoints(parent, parentPoints, facePoints, begin, end); });
  runParts(parts, [&](unsigned k) {
    computeEdgePoints(topo, parent, parentPoints, facePoints, edgePoints, partBound(topo.edgeCount, parts, k),
                      partBound(topo.edgeCount, parts, k + 1), sharpness, decay.get());
    computeVertexPoints(topo, parentPoints, facePoints, vertexPoints, partBound(topo.vertexCount, parts, k),
                        partBound(topo.vertexCount, parts, k + 1), sharpness, decay.get());
  });
}

}  // namespace

void computeCatmullClarkPoints(const MeshTopology& topo, const PolyMesh& parent, const Point* parentPoints,
                               Point* childPoints, unsigned threads) {
  computePoints(topo, parent, parentPoints, childPoints, nullptr, threads);
}

void computeCatmullClarkPoints(const MeshTopology& topo, const PolyMesh& parent, const Point* parentPoints,
                               Point* childPoints, const CreaseSharpness& sharpness, unsigned threads) {
  computePoints(topo, parent, parentPoints, childPoints, sharpness.empty() ? nullptr : &sharpness, threads);
}

void computeSparseCatmullClarkPoints(const MeshTopology& topo, const PolyMesh& parent, const Point* parentPoints,
                                     const SparseChildVertices& which, const CreaseSharpness& sharpness,
                                     std::vector<Point>& facePoints, Point* childPoints, unsigned threads) {
  const CreaseSharpness* sharp = sharpness.empty() ? nullptr : &sharpness;
  facePoints.resize(size_t(topo.faceCount));
  const Index faces = Index(which.faces.size()), edges = Index(which.edges.size()), vertices = Index(which.vertices.size());
  const unsigned parts = threads ? threads : threadsFor(size_t(faces + edges + vertices) * 4);
  std::unique_ptr<SharpnessDecay> decay;
  if (sharp) decay = std::make_unique<SharpnessDecay>(topo, sharpness);
  // Face points by parent id first (the edge and vertex rules read them there), then copied out.
  parallelRanges(faces, parts, [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i) {
      const Index f = which.faces[size_t(i)];
      computeFacePoints(parent, parentPoints, facePoints.data(), f, f + 1);
      childPoints[i] = facePoints[size_t(f)];
    }
  });
  runParts(parts, [&](unsigned k) {
    computeEdgePoints(topo, parent, parentPoints, facePoints.data(), childPoints + faces, partBound(edges, parts, k),
                      partBound(edges, parts, k + 1), sharp, decay.get(), which.edges.data());
    computeVertexPoints(topo, parentPoints, facePoints.data(), childPoints + faces + edges, partBound(vertices, parts, k),
                        partBound(vertices, parts, k + 1), sharp, decay.get(), which.vertices.data());
  });
}

// [SECTION] sharpness per level

namespace {

// Whether anything but the boundary is sharp (else the smooth rules do the same, faster).
bool sharpInside(const MeshTopology& topo, const CreaseSharpness& s) {
  for (Index e = 0; e < topo.edgeCount; ++e)
    if (s.edge[e] > 0.0f && !topo.edgeOnBoundary(e)) return true;
  return std::any_of(s.vertex.begin(), s.vertex.end(), [](float x) { return x > 0.0f; });
}

// The boundary edges, infinitely sharp (Far's prepareComponentTagsAndSharpness), and `s` emptied
// when nothing else is sharp.
CreaseSharpness finishSharpness(const MeshTopology& topo, CreaseSharpness s) {
  for (Index e = 0; e < topo.edgeCount; ++e)
    if (topo.edgeOnBoundary(e)) s.edge[e] = kInfinite;
  return sharpInside(topo, s) || s.smoothTriangles ? s : CreaseSharpness{};
}

}  // namespace

std::vector<uint8_t> baseHoles(const PolyMesh& mesh, const MeshTopology& topo) {
  const SubdivTags& tags = mesh.tags;
  if (tags.holes.empty() && tags.boundary != BoundaryInterpolation::None) return {};
  std::vector<uint8_t> hole(size_t(mesh.faceCount()), 0);
  for (const Index f : tags.holes) hole[size_t(f)] = 1;
  if (tags.boundary == BoundaryInterpolation::None) {
    // Far's prepareComponentTagsAndSharpness: the faces around a vertex with a boundary edge that
    // the tags did not make infinitely sharp (the boundary's own sharpening comes after).
    std::vector<uint8_t> infinite(size_t(topo.edgeCount), 0);
    for (const CreaseEdge& crease : tags.creases)
      if (crease.sharpness >= kInfiniteSharpness)
        if (const Index e = topo.edgeBetween(crease.v0, crease.v1); e >= 0) infinite[size_t(e)] = 1;
    for (Index v = 0; v < topo.vertexCount; ++v) {
      bool exclude = false;
      for (Index k = topo.vertexEdgeStart[v]; k < topo.vertexEdgeStart[v + 1] && !exclude; ++k)
        exclude = topo.edgeOnBoundary(topo.vertexEdges[k]) && !infinite[size_t(topo.vertexEdges[k])];
      if (exclude)
        for (Index k = topo.vertexFaceStart[v]; k < topo.vertexFaceStart[v + 1]; ++k) hole[size_t(topo.vertexFaces[k])] = 1;
    }
  }
  return std::any_of(hole.begin(), hole.end(), [](uint8_t h) { return h != 0; }) ? hole : std::vector<uint8_t>{};
}

CreaseSharpness baseSharpness(const PolyMesh& mesh, const MeshTopology& topo) {
  const SubdivTags& tags = mesh.tags;
  const bool sharpCorners = tags.boundary == BoundaryInterpolation::EdgeAndCorner;
  bool triangles = false;
  if (tags.triangles == TriangleSubdivision::Smooth)
    for (Index f = 0; f < mesh.faceCount() && !triangles; ++f) triangles = mesh.faceSize(f) == 3;
  if (!tags.hasSharpFeatures() && !sharpCorners && !triangles) return {};
  CreaseSharpness s;
  s.edge.assign(size_t(topo.edgeCount), 0.0f);
  s.vertex.assign(size_t(topo.vertexCount), 0.0f);
  s.chaikin = tags.creaseMethod == CreaseMethod::Chaikin;
  s.smoothTriangles = triangles;
  for (const CreaseEdge& crease : tags.creases) {
    const Index e = topo.edgeBetween(crease.v0, crease.v1);
    if (e < 0) throw std::invalid_argument("baseSharpness: crease " + std::to_string(crease.v0) + "-" + std::to_string(crease.v1) + " is not an edge");
    s.edge[e] = float(crease.sharpness);
  }
  for (const CornerVertex& corner : tags.corners) s.vertex[corner.vertex] = float(corner.sharpness);
  // VTX_BOUNDARY_EDGE_AND_CORNER: a vertex with one face and two edges is a corner.
  if (sharpCorners)
    for (Index v = 0; v < topo.vertexCount; ++v)
      if (topo.faceValence(v) == 1 && topo.valence(v) == 2) s.vertex[v] = kInfinite;
  return finishSharpness(topo, std::move(s));
}

namespace {
// A child level's sharpness before the decayed values go in: every edge and vertex smooth.
CreaseSharpness smoothChildSharpness(const CreaseSharpness& parent, const MeshTopology& childTopo) {
  CreaseSharpness child;
  child.edge.assign(size_t(childTopo.edgeCount), 0.0f);
  child.vertex.assign(size_t(childTopo.vertexCount), 0.0f);
  child.chaikin = parent.chaikin;
  return child;
}
}  // namespace

CreaseSharpness childSharpness(const MeshTopology& parentTopo, const CreaseSharpness& parent, const MeshTopology& childTopo) {
  if (parent.empty()) return {};
  const SharpnessDecay decay(parentTopo, parent);
  CreaseSharpness child = smoothChildSharpness(parent, childTopo);
  for (Index e = 0; e < parentTopo.edgeCount; ++e) {
    if (parent.edge[e] <= 0.0f) continue;
    for (int end = 0; end < 2; ++end) {
      const Index v = parentTopo.edgeVerts[2 * e + end];
      const Index half = childTopo.edgeBetween(ccEdgePoint(parentTopo, e), ccVertexPoint(parentTopo, v));
      child.edge[half] = decay.edgeAt(e, v);
    }
  }
  for (Index v = 0; v < parentTopo.vertexCount; ++v) child.vertex[ccVertexPoint(parentTopo, v)] = decay.vertex(v);
  return finishSharpness(childTopo, std::move(child));
}

CreaseSharpness sparseChildSharpness(const MeshTopology& parentTopo, const CreaseSharpness& parent, const SparseChildVertices& which,
                                     const MeshTopology& childTopo) {
  if (parent.empty()) return {};
  const SharpnessDecay decay(parentTopo, parent);
  CreaseSharpness child = smoothChildSharpness(parent, childTopo);
  const Index firstEdgePoint = Index(which.faces.size()), firstVertexPoint = firstEdgePoint + Index(which.edges.size());
  std::vector<Index> vertexPoint(size_t(parentTopo.vertexCount), -1);
  for (size_t i = 0; i < which.vertices.size(); ++i) {
    vertexPoint[size_t(which.vertices[i])] = firstVertexPoint + Index(i);
    child.vertex[size_t(firstVertexPoint) + i] = decay.vertex(which.vertices[i]);
  }
  for (size_t i = 0; i < which.edges.size(); ++i) {
    const Index e = which.edges[i];
    if (parent.edge[size_t(e)] <= 0.0f) continue;
    for (int end = 0; end < 2; ++end) {  // the halves that exist: at the ends whose vertex points do
      const Index v = parentTopo.edgeVerts[2 * e + end];
      if (vertexPoint[size_t(v)] < 0) continue;
      const Index half = childTopo.edgeBetween(firstEdgePoint + Index(i), vertexPoint[size_t(v)]);
      if (half >= 0) child.edge[size_t(half)] = decay.edgeAt(e, v);
    }
  }
  return finishSharpness(childTopo, std::move(child));
}

SubdivTags sharpnessTags(const MeshTopology& topo, const CreaseSharpness& sharpness, const SubdivTags& options) {
  SubdivTags tags;
  tags.boundary = options.boundary;
  tags.creaseMethod = options.creaseMethod;
  tags.triangles = options.triangles;
  if (sharpness.empty()) return tags;
  for (Index e = 0; e < topo.edgeCount; ++e)
    if (sharpness.edge[e] > 0.0f && !topo.edgeOnBoundary(e)) {
      const Index a = topo.edgeVerts[2 * e], b = topo.edgeVerts[2 * e + 1];
      tags.creases.push_back({std::min(a, b), std::max(a, b), double(sharpness.edge[e])});
    }
  std::sort(tags.creases.begin(), tags.creases.end(),
            [](const CreaseEdge& x, const CreaseEdge& y) { return x.v0 != y.v0 ? x.v0 < y.v0 : x.v1 < y.v1; });
  for (Index v = 0; v < topo.vertexCount; ++v)
    if (sharpness.vertex[v] > 0.0f) tags.corners.push_back({v, double(sharpness.vertex[v])});
  return tags;
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
    const LimitMask mask = catmullClarkLimitMask(k);
    limit[v] = mask.vertex * p[v] + mask.edge * edgeSum + mask.diagonal * diagonalSum;
  }
  return limit;
}

}  // namespace polarview
