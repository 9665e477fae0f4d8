// Edge and incidence tables of a manifold PolyMesh (see topology.h).
// Everything is built with counting sorts over flat arrays: corners are bucketed by their lower
// edge end, then by the upper one, so half-edges of one edge become neighbours. [O(corners log)]
// Error messages number vertices and faces 1-based, as an OBJ file does.
#include "core/mesh/topology.h"

#include <algorithm>
#include <stdexcept>

#include "core/mesh/input_error.h"

namespace polarview {

namespace {

class TopologyBuilder {
 public:
  TopologyBuilder(const PolyMesh& mesh, const std::string& sourceName) : mesh_(mesh), source_(sourceName) {}

  MeshTopology build() {
    t_.vertexCount = mesh_.vertexCount();
    t_.faceCount = mesh_.faceCount();
    validateFaces();
    buildEdges();
    buildVertexRings();
    return std::move(t_);
  }

  // The same tables from known half-edge twins (a refinement's child): no validation, no sorting.
  MeshTopology buildFromTwins(const std::vector<Index>& twin) {
    t_.vertexCount = mesh_.vertexCount();
    t_.faceCount = mesh_.faceCount();
    t_.cornerFace.resize(mesh_.faceVerts.size());
    for (Index f = 0; f < t_.faceCount; ++f)
      std::fill(t_.cornerFace.begin() + mesh_.faceStart[f], t_.cornerFace.begin() + mesh_.faceStart[f + 1], f);
    buildEdgesFromTwins(twin);
    twin_ = &twin;
    quadsOnly_ = true;
    for (Index f = 0; f <= t_.faceCount && quadsOnly_; ++f) quadsOnly_ = mesh_.faceStart[f] == 4 * f;
    buildVertexRings();
    return std::move(t_);
  }

 private:
  [[noreturn]] void fail(Index face, const std::string& what) const {
    int64_t line = 0;
    if (face >= 0 && face < Index(mesh_.faceLine.size())) line = mesh_.faceLine[face];
    // Without OBJ lines, name the face itself so the message still points somewhere.
    if (line <= 0 && face >= 0) throw InputError(source_, 0, "face " + std::to_string(face + 1) + ": " + what);
    throw InputError(source_, line, what);
  }
  std::string faceName(Index f) const {
    if (f < Index(mesh_.faceLine.size()) && mesh_.faceLine[f] > 0) return "the face on line " + std::to_string(mesh_.faceLine[f]);
    return "face " + std::to_string(f + 1);
  }
  static std::string vertexName(Index v) { return "v " + std::to_string(int64_t(v) + 1); }
  std::string edgeName(Index a, Index b) const { return "(" + vertexName(std::min(a, b)) + " - " + vertexName(std::max(a, b)) + ")"; }

  Index cornerNext(Index c) const { return c + 1 == mesh_.faceStart[t_.cornerFace[c] + 1] ? mesh_.faceStart[t_.cornerFace[c]] : c + 1; }
  Index cornerPrev(Index c) const {
    if (quadsOnly_) return (c & ~Index(3)) | ((c + 3) & 3);
    return c == mesh_.faceStart[t_.cornerFace[c]] ? mesh_.faceStart[t_.cornerFace[c] + 1] - 1 : c - 1;
  }

  // Face sizes, index ranges, repeated vertices; fills cornerFace.
  void validateFaces() {
    const Index cornerCount = static_cast<Index>(mesh_.faceVerts.size());
    if (mesh_.faceStart.empty() || mesh_.faceStart.back() != cornerCount)
      throw InputError(source_, 0, "face offsets do not match the face vertex list");
    t_.cornerFace.resize(cornerCount);
    for (Index f = 0; f < t_.faceCount; ++f) {
      const Index k = mesh_.faceSize(f);
      if (k < 3) fail(f, "face has " + std::to_string(k) + " vertices (at least 3 needed)");
      const Index* loop = mesh_.face(f);
      for (Index i = 0; i < k; ++i) {
        if (loop[i] < 0 || loop[i] >= t_.vertexCount)
          fail(f, "vertex index " + std::to_string(int64_t(loop[i]) + 1) + " out of range (" + std::to_string(t_.vertexCount) + " vertices)");
        t_.cornerFace[mesh_.faceStart[f] + i] = f;
      }
      if (hasRepeatedVertex(loop, k)) fail(f, "face repeats a vertex");
    }
  }

  bool hasRepeatedVertex(const Index* loop, Index k) {
    constexpr Index kSmallFace = 16;  // pairwise is fastest for ordinary faces
    if (k <= kSmallFace) {
      for (Index i = 0; i < k; ++i)
        for (Index j = i + 1; j < k; ++j)
          if (loop[i] == loop[j]) return true;
      return false;
    }
    scratch_.assign(loop, loop + k);
    std::sort(scratch_.begin(), scratch_.end());
    return std::adjacent_find(scratch_.begin(), scratch_.end()) != scratch_.end();
  }

  // Groups the corners' half-edges by edge, numbers edges in order of first use, and checks
  // that each edge has at most two faces running it in opposite directions.
  void buildEdges() {
    const Index cornerCount = static_cast<Index>(mesh_.faceVerts.size());
    const std::vector<Index>& fv = mesh_.faceVerts;

    // Bucket corners by the lower end of their half-edge (counting sort).
    std::vector<Index> bucketStart(size_t(t_.vertexCount) + 1, 0);
    for (Index c = 0; c < cornerCount; ++c) ++bucketStart[std::min(fv[c], fv[cornerNext(c)]) + 1];
    for (Index v = 0; v < t_.vertexCount; ++v) bucketStart[v + 1] += bucketStart[v];
    std::vector<Index> sorted(cornerCount), fill(bucketStart.begin(), bucketStart.end() - 1);
    for (Index c = 0; c < cornerCount; ++c) sorted[fill[std::min(fv[c], fv[cornerNext(c)])]++] = c;

    // Within a bucket, order by the upper end then by corner: each edge is a run, led by its first corner.
    std::vector<Index> leader(cornerCount);
    for (Index v = 0; v < t_.vertexCount; ++v) {
      Index* begin = sorted.data() + bucketStart[v];
      Index* end = sorted.data() + bucketStart[v + 1];
      std::sort(begin, end, [&](Index a, Index b) {
        const Index ha = std::max(fv[a], fv[cornerNext(a)]), hb = std::max(fv[b], fv[cornerNext(b)]);
        return ha != hb ? ha < hb : a < b;
      });
      for (Index* run = begin; run != end;) {
        const Index hi = std::max(fv[*run], fv[cornerNext(*run)]);
        Index* runEnd = run + 1;
        while (runEnd != end && std::max(fv[*runEnd], fv[cornerNext(*runEnd)]) == hi) ++runEnd;
        checkEdgeRun(run, runEnd);
        for (Index* c = run; c != runEnd; ++c) leader[*c] = *run;
        run = runEnd;
      }
    }

    // Number edges by first use (the leader is the run's smallest corner), fill the edge tables.
    t_.cornerEdge.resize(cornerCount);
    edgeCorners_.clear();
    for (Index c = 0; c < cornerCount; ++c) {
      if (leader[c] == c) {
        t_.cornerEdge[c] = t_.edgeCount++;
        t_.edgeVerts.push_back(fv[c]);
        t_.edgeVerts.push_back(fv[cornerNext(c)]);
        t_.edgeFaces.push_back(t_.cornerFace[c]);
        t_.edgeFaces.push_back(-1);
        edgeCorners_.push_back(c);
        edgeCorners_.push_back(-1);
      } else {
        const Index e = t_.cornerEdge[leader[c]];
        t_.cornerEdge[c] = e;
        t_.edgeFaces[2 * e + 1] = t_.cornerFace[c];
        edgeCorners_[2 * e + 1] = c;
      }
    }
  }

  // buildEdges' numbering (by first use: an edge's leader is its smaller corner) from the twins.
  void buildEdgesFromTwins(const std::vector<Index>& twin) {
    const Index cornerCount = static_cast<Index>(mesh_.faceVerts.size());
    const std::vector<Index>& fv = mesh_.faceVerts;
    Index edges = 0;
    for (Index c = 0; c < cornerCount; ++c) edges += twin[size_t(c)] < 0 || twin[size_t(c)] > c;
    t_.edgeCount = edges;
    t_.cornerEdge.resize(size_t(cornerCount));
    t_.edgeVerts.resize(2 * size_t(edges));
    t_.edgeFaces.resize(2 * size_t(edges));
    edgeCorners_.resize(2 * size_t(edges));
    Index e = 0;
    for (Index c = 0; c < cornerCount; ++c) {
      const Index other = twin[size_t(c)];
      if (other >= 0 && other < c) {
        const Index led = t_.cornerEdge[other];
        t_.cornerEdge[c] = led;
        t_.edgeFaces[2 * led + 1] = t_.cornerFace[c];
        edgeCorners_[2 * led + 1] = c;
        continue;
      }
      t_.cornerEdge[c] = e;
      t_.edgeVerts[2 * e] = fv[c];
      t_.edgeVerts[2 * e + 1] = fv[cornerNext(c)];
      t_.edgeFaces[2 * e] = t_.cornerFace[c];
      t_.edgeFaces[2 * e + 1] = -1;
      edgeCorners_[2 * e] = c;
      edgeCorners_[2 * e + 1] = -1;
      ++e;
    }
  }

  void checkEdgeRun(const Index* run, const Index* runEnd) const {
    const std::vector<Index>& fv = mesh_.faceVerts;
    const Index a = fv[run[0]], b = fv[cornerNext(run[0])];
    if (runEnd - run > 2)
      fail(t_.cornerFace[run[2]], "non-manifold edge " + edgeName(a, b) + " shared by " + std::to_string(runEnd - run) + " faces");
    if (runEnd - run == 2 && fv[run[1]] == a)
      fail(t_.cornerFace[run[1]], "inconsistent orientation: edge " + edgeName(a, b) + " runs the same way in " +
                                      faceName(t_.cornerFace[run[0]]));
  }

  // Per vertex: walk the fan of faces rotationally. Corner c's incoming edge (prev -> v) is the
  // outgoing edge (v -> prev) of the next face's corner at v. A boundary fan starts at the face
  // whose outgoing edge is a boundary edge; a vertex whose corners are not all reached by one
  // walk has more than one fan (non-manifold).
  void buildVertexRings() {
    const Index cornerCount = static_cast<Index>(mesh_.faceVerts.size());
    const Index V = t_.vertexCount;

    // Where each ring starts; fills vertexFaceStart (the face-list sizes) and vertexOnBoundary.
    std::vector<Index> cornersOfVertex, ringStart;
    if (twin_) {
      ringStartsFromTwins(ringStart);
    } else {
      // Corners by vertex (counting sort): the face-list sizes.
      t_.vertexFaceStart.assign(size_t(V) + 1, 0);
      for (Index c = 0; c < cornerCount; ++c) ++t_.vertexFaceStart[mesh_.faceVerts[c] + 1];
      for (Index v = 0; v < V; ++v) t_.vertexFaceStart[v + 1] += t_.vertexFaceStart[v];
      cornersOfVertex.resize(size_t(cornerCount));
      std::vector<Index> fill(t_.vertexFaceStart.begin(), t_.vertexFaceStart.end() - 1);
      for (Index c = 0; c < cornerCount; ++c) cornersOfVertex[fill[mesh_.faceVerts[c]]++] = c;
      t_.vertexOnBoundary.assign(V, 0);
      for (Index e = 0; e < t_.edgeCount; ++e)
        if (t_.edgeOnBoundary(e)) t_.vertexOnBoundary[t_.edgeVerts[2 * e]] = t_.vertexOnBoundary[t_.edgeVerts[2 * e + 1]] = 1;
    }

    t_.vertexUsed.assign(V, 0);
    for (Index v = 0; v < V; ++v) t_.vertexUsed[v] = t_.faceValence(v) > 0;
    t_.vertexEdgeStart.assign(size_t(V) + 1, 0);
    for (Index v = 0; v < V; ++v) t_.vertexEdgeStart[v + 1] = t_.vertexEdgeStart[v] + t_.faceValence(v) + t_.vertexOnBoundary[v];
    t_.vertexFaces.resize(cornerCount);
    t_.vertexCorners.resize(cornerCount);
    t_.vertexEdges.resize(t_.vertexEdgeStart[V]);

    for (Index v = 0; v < V; ++v) {
      const Index first = t_.vertexFaceStart[v], count = t_.faceValence(v);
      if (count == 0) continue;
      const Index start = twin_ ? ringStart[size_t(v)] : fanStart(v, cornersOfVertex.data() + first, count);
      Index pos = first, edgePos = t_.vertexEdgeStart[v];
      for (Index c = start;;) {
        t_.vertexFaces[pos] = t_.cornerFace[c];
        t_.vertexCorners[pos] = c;
        t_.vertexEdges[edgePos++] = t_.cornerEdge[c];
        ++pos;
        const Index incoming = cornerPrev(c);
        // The next face's corner at v starts the twin of the incoming half-edge (none: boundary).
        const Index e = t_.cornerEdge[incoming];
        const Index next = twin_ ? (*twin_)[size_t(incoming)] : t_.edgeOnBoundary(e) ? -1
                                   : edgeCorners_[2 * e] == incoming ? edgeCorners_[2 * e + 1] : edgeCorners_[2 * e];
        if (next < 0) {
          t_.vertexEdges[edgePos++] = e;
          break;
        }
        c = next;
        if (c == start || pos - first == count) break;
      }
      if (pos - first == count) continue;
      if (twin_) throw std::logic_error("buildTopologyFromTwins: the twins leave " + vertexName(v) + " with more than one fan");
      failNonManifoldFan(v, cornersOfVertex.data() + first, count, pos - first);
    }
  }

  // buildVertexRings' starts from the twins, in one pass over the corners instead of a counting
  // sort: an interior ring starts at its vertex's smallest corner, a boundary ring at the corner
  // leaving along the boundary (its twin is missing), as fanStart picks them.
  void ringStartsFromTwins(std::vector<Index>& ringStart) {
    const std::vector<Index>& twin = *twin_;
    const Index cornerCount = static_cast<Index>(mesh_.faceVerts.size());
    const Index V = t_.vertexCount;
    t_.vertexFaceStart.assign(size_t(V) + 1, 0);
    t_.vertexOnBoundary.assign(V, 0);
    ringStart.assign(size_t(V), -1);
    for (Index c = 0; c < cornerCount; ++c) {
      const Index v = mesh_.faceVerts[c];
      ++t_.vertexFaceStart[v + 1];
      if (twin[size_t(c)] < 0) {  // a boundary edge: both its ends lie on the boundary
        ringStart[size_t(v)] = c;
        t_.vertexOnBoundary[v] = t_.vertexOnBoundary[mesh_.faceVerts[cornerNext(c)]] = 1;
      } else if (ringStart[size_t(v)] < 0) {
        ringStart[size_t(v)] = c;
      }
    }
    for (Index v = 0; v < V; ++v) t_.vertexFaceStart[v + 1] += t_.vertexFaceStart[v];
  }

  // The corner a vertex's walk starts at: any corner for an interior vertex, the one whose
  // outgoing edge is on the boundary otherwise (a second such corner starts a second fan).
  Index fanStart(Index v, const Index* corners, Index count) const {
    if (!t_.vertexOnBoundary[v]) return corners[0];
    Index start = -1;
    for (Index i = 0; i < count; ++i) {
      if (!t_.edgeOnBoundary(t_.cornerEdge[corners[i]])) continue;
      if (start >= 0) failNonManifoldVertex(v, t_.cornerFace[corners[i]]);
      start = corners[i];
    }
    return start;
  }

  // Names a face outside the fan the walk found (the walk wrote that fan's corners to vertexCorners).
  [[noreturn]] void failNonManifoldFan(Index v, const Index* corners, Index count, Index walked) const {
    const Index* fan = t_.vertexCorners.data() + t_.vertexFaceStart[v];
    Index culprit = t_.cornerFace[corners[count - 1]];
    for (Index i = 0; i < count; ++i)
      if (std::find(fan, fan + walked, corners[i]) == fan + walked) { culprit = t_.cornerFace[corners[i]]; break; }
    failNonManifoldVertex(v, culprit);
  }
  [[noreturn]] void failNonManifoldVertex(Index v, Index culprit) const {
    fail(culprit, "non-manifold vertex " + vertexName(v) + " (its faces form more than one fan)");
  }

  const PolyMesh& mesh_;
  const std::string& source_;
  MeshTopology t_;
  std::vector<Index> edgeCorners_;  // per edge: the corner starting each side's half-edge (-1 on a boundary)
  const std::vector<Index>* twin_ = nullptr;  // buildFromTwins: per corner, the twin half-edge's corner
  bool quadsOnly_ = false;                     // face f's corners are 4f..4f+3 (a refinement's quads)
  std::vector<Index> scratch_;
};

}  // namespace

MeshTopology buildTopology(const PolyMesh& mesh, const std::string& sourceName) {
  return TopologyBuilder(mesh, sourceName).build();
}

MeshTopology buildTopologyFromTwins(const PolyMesh& mesh, const std::vector<Index>& twin) {
  static const std::string source = "<refined>";
  return TopologyBuilder(mesh, source).buildFromTwins(twin);
}

}  // namespace polarview
