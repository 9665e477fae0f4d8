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

#include <algorithm>
#include <stdexcept>

#include "core/mesh/check.h"
#include "core/subdiv/parallel_for.h"
#include "core/subdiv/prefetch.h"
#include "core/subdiv/table_pool.h"

namespace polarview {

std::vector<Index> cornerLinks(const PolyMesh& mesh, const MeshTopology& topo) {
  std::vector<Index> links;
  reserveFromPool(links, 2 * mesh.faceVerts.size());  // a refinement's completion hands it back
  links.assign(2 * mesh.faceVerts.size(), -1);
  const Index *faceStart = mesh.faceStart.data(), *ringStart = topo.vertexFaceStart.data();
  const Index *ringCorners = topo.vertexCorners.data(), *ringFaces = topo.vertexFaces.data();
  const uint8_t* onBoundary = topo.vertexOnBoundary.data();
  Index* out = links.data();
  // Consecutive ring corners r_i, r_i+1 at v: r_i+1 starts the opposite half-edge of r_i's incoming
  // one, and the corner after r_i+1 in its face is the twin's successor. Each incoming half-edge
  // lies in one ring: vertex ranges write disjoint entries.
  parallelRanges(topo.vertexCount, threadsFor(mesh.faceVerts.size()), [&](Index vBegin, Index vEnd) {
    for (Index v = vBegin; v < vEnd; ++v) {
      const Index first = ringStart[v], last = ringStart[v + 1];
      for (Index i = first; i < last; ++i) {
        const Index corner = ringCorners[i], face = ringFaces[i];
        const Index incoming = corner == faceStart[face] ? faceStart[face + 1] - 1 : corner - 1;
        if (i + 1 == last && onBoundary[v]) continue;  // the boundary edge: no twin
        const Index j = i + 1 == last ? first : i + 1;
        const Index twin = ringCorners[j], twinFace = ringFaces[j];
        out[2 * size_t(incoming)] = twin;
        out[2 * size_t(incoming) + 1] = twin + 1 == faceStart[twinFace + 1] ? faceStart[twinFace] : twin + 1;
      }
    }
  });
  return links;
}

namespace {

// Per part of the parent (a range of faces and a range of vertices): what it adds to the child, so
// every part knows where its output starts before any part writes.
struct PartCounts {
  Index newEdges = 0;          // child edges led by the part's child corners
  Index interiorLeaders = 0;   // parent edges led by the part's corners (interior / boundary)
  Index boundaryLeaders = 0;
  Index splitRingCorners = 0;  // split corners in the rings of the part's vertices
  Index boundaryVertices = 0;
  Index splitCorners = 0;      // split corners among the part's faces
};

// Sizing one output table: reserve (a pooled buffer or an allocation), map its fresh pages (a
// share per part: one table can be most of a step's new memory) and resize (first touch: the zero
// fill) may run on different threads. Every entry is written later, so a pooled buffer's old
// contents never show.
struct TableJob {
  size_t bytes;
  void (*reserve)(void* table, size_t size);
  void (*prefaultShare)(void* table, size_t size, unsigned part, unsigned parts);
  void (*resize)(void* table, size_t size);
  void* table;
  size_t size;
};
template <class T>
TableJob tableJob(std::vector<T>& table, size_t size) {
  return {size * sizeof(T), [](void* v, size_t n) { reserveFromPool(*static_cast<std::vector<T>*>(v), n); },
          [](void* v, size_t n, unsigned part, unsigned parts) {
            std::vector<T>& t = *static_cast<std::vector<T>*>(v);
            if (t.size() >= n) return;  // no fresh pages (a pooled buffer)
            const size_t fresh = n - t.size();
            const size_t begin = t.size() + fresh * part / parts, end = t.size() + fresh * (part + 1) / parts;
            prefault(t.data() + begin, (end - begin) * sizeof(T));  // within the reserved capacity
          },
          [](void* v, size_t n) { static_cast<std::vector<T>*>(v)->resize(n); }, &table, size};
}

constexpr Index kPrefetchDistance = 16;  // ring entries ahead

// Where a ring-writing pass stands: the child vertex, its ring's first entry, the next entries.
struct RingCursor {
  Index vertex = 0, ringStart = 0, facePos = 0, edgePos = 0;
};

template <bool kSplit>
class ConnectivityBuilder {
 public:
  ConnectivityBuilder(const PolyMesh& parent, const MeshTopology& topo, const std::vector<Index>& links,
                      const uint8_t* splitCorner, RefinedConnectivity& out, const ConnectivityOptions& options)
      : parent_(parent), topo_(topo), parentLinks_(links.data()), split_(splitCorner), out_(out), options_(options) {}

  void build() {
    if (!options_.edges && (options_.vertexRings || options_.childLinks))
      throw std::logic_error("refineCatmullClarkConnectivity: rings and links need the edges");
    countAndNumber();
    sizeTables();
    if (options_.edges)
      buildFacesAndEdges();
    else
      buildFaces();
    if (options_.vertexRings)
      buildVertexRings();
    else
      buildVertexFlags();
    releaseToPool(firstChildFace_);
  }

  // The ring pass alone, over a child whose faces and edges a build without rings made.
  void completeRings() {
    countAndNumber();
    MeshTopology& t = out_.topology;
    POLARVIEW_CHECK_EQ(Index(t.cornerEdge.size()), childCorners_);
    cornerEdge_ = t.cornerEdge.data();
    ringTables_ = ringJobs();
    for (const TableJob& job : ringTables_) job.reserve(job.table, job.size);
    buildVertexRings();
    releaseToPool(firstChildFace_);
  }

 private:
  // What both passes need first: the parts, their counts, the split corners' child faces, and
  // where the child's vertex points and corners start.
  void countAndNumber() {
    parentCorners_ = static_cast<Index>(parent_.faceVerts.size());
    parts_ = options_.threads ? options_.threads : threadsFor(size_t(parentCorners_));
    countParts();
    numberChildFaces();
    vertexPointBase_ = topo_.faceCount + topo_.edgeCount;
    childCorners_ = 4 * parentCorners_ + 2 * splitCount_;
  }

  // Parent corner links (cornerLinks): the twin of c and the corner after the twin.
  Index twinOf(Index c) const { return parentLinks_[2 * size_t(c)]; }
  Index twinNextOf(Index c) const { return parentLinks_[2 * size_t(c) + 1]; }
  bool isSplit(Index c) const { return kSplit && split_[c]; }
  // The child face (the first of two when split) and first child corner of parent corner c.
  Index childFace(Index c) const { return kSplit ? firstChildFace_[c] : c; }
  Index base(Index c) const { return kSplit ? 2 * (c + firstChildFace_[c]) : 4 * c; }
  // Child faces of the parent corners before c (c may be the corner count).
  Index childFacesBefore(Index c) const { return c == parentCorners_ ? parentCorners_ + splitCount_ : childFace(c); }
  // Child corners of parent corner c by the half-edge they start, and the face holding the last two.
  Index vertexToEdge(Index c) const { return base(c); }
  Index edgeToFace(Index c) const { return base(c) + 1; }
  Index faceToEdge(Index c) const { return base(c) + (isSplit(c) ? 4 : 2); }
  Index edgeToVertex(Index c) const { return base(c) + (isSplit(c) ? 5 : 3); }
  Index secondChildFace(Index c) const { return childFace(c) + (isSplit(c) ? 1 : 0); }

  Index faceBound(unsigned k) const { return partBound(topo_.faceCount, parts_, k); }
  Index vertexBound(unsigned k) const { return partBound(topo_.vertexCount, parts_, k); }
  // Part k's parent faces, their corners and its parent vertices, computed once: a bound in a loop
  // condition is a division the compiler must redo after every store (an Index store may alias
  // the counts it reads).
  struct PartRange {
    Index fBegin, fEnd, cBegin, cEnd, vBegin, vEnd;
  };
  PartRange partRange(unsigned k) const {
    const Index fBegin = faceBound(k), fEnd = faceBound(k + 1);
    return {fBegin, fEnd, parent_.faceStart[fBegin], parent_.faceStart[fEnd], vertexBound(k), vertexBound(k + 1)};
  }

  // Split mode: each parent corner's first child face (corners before it, plus splits before it),
  // filled by the parts from their split counts.
  void numberChildFaces() {
    if (!kSplit) return;
    reserveFromPool(firstChildFace_, size_t(parentCorners_));
    firstChildFace_.resize(parentCorners_);
    runParts(parts_, [&](unsigned k) {
      Index splits = counts_[k].splitCorners;
      const PartRange part = partRange(k);
      for (Index c = part.cBegin; c < part.cEnd; ++c) {
        firstChildFace_[c] = c + splits;
        splits += split_[c] ? 1 : 0;
      }
    });
  }

  // Each part counts what it will write; prefix sums turn the counts into start positions.
  // A child corner opens an edge when its twin is later or missing (numbering by first use).
  void countParts() {
    counts_.assign(parts_ + 1, PartCounts());
    runParts(parts_, [&](unsigned k) {
      PartCounts count;
      const PartRange part = partRange(k);
      if (!options_.edges) {  // faces only: just the splits (no edges to number, no rings)
        if (kSplit)
          for (Index c = part.cBegin; c < part.cEnd; ++c) count.splitCorners += split_[c];
        counts_[k + 1] = count;
        return;
      }
      for (Index f = part.fBegin; f < part.fEnd; ++f) {
        const Index begin = parent_.faceStart[f], end = parent_.faceStart[f + 1];
        for (Index c = begin; c < end; ++c) {
          const Index twin = twinOf(c), twinPrev = twinOf(c == begin ? end - 1 : c - 1);
          count.newEdges += (twin < 0 || twinNextOf(c) > c) + (c + 1 != end) + (c == begin) +
                            (twinPrev < 0 || twinPrev > c) + (isSplit(c) ? 1 : 0);
          count.boundaryLeaders += twin < 0;
          count.splitCorners += isSplit(c) ? 1 : 0;
          count.interiorLeaders += twin > c;
        }
      }
      for (Index v = part.vBegin; v < part.vEnd; ++v) {
        count.boundaryVertices += topo_.vertexOnBoundary[v];
        if (kSplit)
          for (Index i = topo_.vertexFaceStart[v]; i < topo_.vertexFaceStart[v + 1]; ++i)
            count.splitRingCorners += split_[topo_.vertexCorners[i]];
      }
      counts_[k + 1] = count;
    });
    for (unsigned k = 1; k <= parts_; ++k) {  // counts_[k]: everything before part k
      counts_[k].newEdges += counts_[k - 1].newEdges;
      counts_[k].interiorLeaders += counts_[k - 1].interiorLeaders;
      counts_[k].boundaryLeaders += counts_[k - 1].boundaryLeaders;
      counts_[k].splitRingCorners += counts_[k - 1].splitRingCorners;
      counts_[k].boundaryVertices += counts_[k - 1].boundaryVertices;
      counts_[k].splitCorners += counts_[k - 1].splitCorners;
    }
    splitCount_ = counts_[parts_].splitCorners;
  }

  // Child counts: F + E + V vertices, one face per corner (+1 per split), 2 edges per parent edge
  // and 1 per corner (+1 per split).
  void sizeTables() {
    const Index C = parentCorners_;
    MeshTopology& t = out_.topology;
    t.vertexCount = topo_.faceCount + topo_.edgeCount + topo_.vertexCount;
    t.faceCount = C + splitCount_;
    t.edgeCount = 2 * topo_.edgeCount + C + splitCount_;
    if (options_.edges) POLARVIEW_CHECK_EQ(counts_[parts_].newEdges, t.edgeCount);
    const size_t corners = size_t(childCorners_), faces = size_t(t.faceCount) + 1, vertices = size_t(t.vertexCount);
    PolyMesh& mesh = out_.mesh;
    mesh.faceLine.clear();
    if (!options_.childLinks) out_.links.clear();

    faceTables_ = {tableJob(mesh.faceVerts, corners), tableJob(mesh.faceStart, faces), tableJob(out_.faceParent, faces - 1)};
    if (options_.edges)
      for (TableJob job : {tableJob(t.cornerEdge, corners), tableJob(t.cornerFace, corners), tableJob(t.edgeVerts, 2 * size_t(t.edgeCount)),
                           tableJob(t.edgeFaces, 2 * size_t(t.edgeCount))})
        faceTables_.push_back(job);
    if (options_.childLinks) faceTables_.push_back(tableJob(out_.links, 2 * corners));
    ringTables_ = ringJobs();
    ringTables_.push_back(tableJob(mesh.points, vertices));
    if (!options_.vertexRings) ringTables_ = {tableJob(mesh.points, vertices), tableJob(t.vertexOnBoundary, vertices),
                                              tableJob(t.vertexUsed, vertices)};
    // Allocate (or take from the pool) on the calling thread, in its malloc arena; touch later, on the parts.
    for (const TableJob& job : faceTables_) job.reserve(job.table, job.size);
    for (const TableJob& job : ringTables_) job.reserve(job.table, job.size);
  }

  // The tables of the ring pass (the points are sized with them when the faces are built).
  std::vector<TableJob> ringJobs() {
    MeshTopology& t = out_.topology;
    const size_t corners = size_t(childCorners_), vertices = size_t(t.vertexCount);
    const size_t ringEdges = corners + size_t(counts_[parts_].boundaryLeaders + counts_[parts_].boundaryVertices);
    return {tableJob(t.vertexFaces, corners),       tableJob(t.vertexCorners, corners),
            tableJob(t.vertexEdges, ringEdges),     tableJob(t.vertexFaceStart, vertices + 1),
            tableJob(t.vertexEdgeStart, vertices + 1), tableJob(t.vertexOnBoundary, vertices),
            tableJob(t.vertexUsed, vertices)};
  }

  // Without rings: the child vertices' boundary and use flags as the ring pass would set them (a
  // face point is interior, an edge point lies on the boundary with its edge, a vertex point as its
  // vertex; an unused parent vertex's point is unused).
  void buildVertexFlags() {
    touchTables(ringTables_);
    uint8_t* onBoundary = out_.topology.vertexOnBoundary.data();
    uint8_t* used = out_.topology.vertexUsed.data();
    const uint8_t* parentOnBoundary = topo_.vertexOnBoundary.data();
    const uint8_t* parentUsed = topo_.vertexUsed.data();
    const Index* edgeFaces = topo_.edgeFaces.data();
    const Index F = topo_.faceCount, E = topo_.edgeCount, V = topo_.vertexCount;
    // A boundary edge has boundary ends: without boundary vertices the edges' flags are all 0,
    // and the 8-byte stride through edgeFaces (a tenth of this step) is skipped.
    const bool anyBoundary = std::find(parentOnBoundary, parentOnBoundary + V, uint8_t(1)) != parentOnBoundary + V;
    runParts(parts_, [&](unsigned k) {
      const Index fBegin = partBound(F, parts_, k), fEnd = partBound(F, parts_, k + 1);
      const Index eBegin = partBound(E, parts_, k), eEnd = partBound(E, parts_, k + 1);
      const Index vBegin = partBound(V, parts_, k), vEnd = partBound(V, parts_, k + 1);
      std::fill(onBoundary + fBegin, onBoundary + fEnd, uint8_t(0));
      std::fill(used + fBegin, used + fEnd, uint8_t(1));
      if (anyBoundary)
        for (Index e = eBegin; e < eEnd; ++e) onBoundary[F + e] = edgeFaces[2 * e + 1] < 0;
      else
        std::fill(onBoundary + F + eBegin, onBoundary + F + eEnd, uint8_t(0));
      std::fill(used + F + eBegin, used + F + eEnd, uint8_t(1));
      std::copy(parentOnBoundary + vBegin, parentOnBoundary + vEnd, onBoundary + F + E + vBegin);
      std::copy(parentUsed + vBegin, parentUsed + vEnd, used + F + E + vBegin);
    });
  }

  // Sizes a pass's tables just before the pass, so they are still cached: first every part maps its
  // share of every table's fresh pages (the kernel's faults, the bigger cost), then the zero fill,
  // largest table first, each to the least loaded part.
  void touchTables(std::vector<TableJob>& jobs) {
    std::sort(jobs.begin(), jobs.end(), [](const TableJob& a, const TableJob& b) { return a.bytes > b.bytes; });
    std::vector<size_t> load(parts_, 0);
    std::vector<unsigned> owner(jobs.size());
    for (size_t j = 0; j < jobs.size(); ++j) {
      owner[j] = unsigned(std::min_element(load.begin(), load.end()) - load.begin());
      load[owner[j]] += jobs[j].bytes;
    }
    runParts(parts_, [&](unsigned k) {
      for (const TableJob& job : jobs) job.prefaultShare(job.table, job.size, k, parts_);
    });
    runParts(parts_, [&](unsigned k) {
      for (size_t j = 0; j < jobs.size(); ++j)
        if (owner[j] == k) jobs[j].resize(jobs[j].table, jobs[j].size);
    });
  }

  // Writes child corner x (vertex -> nextVertex in `face`, opposite half-edge `twin`, the corner
  // after it `twinNext`) and numbers
  // its edge by first use: the smaller corner of a twin pair opens the edge. A twin in an earlier
  // part may not be numbered yet: such corners wait in `deferred`.
  void emitCorner(Index x, Index vertex, Index nextVertex, Index face, Index twin, Index twinNext, Index partFirstCorner,
                  Index& nextEdge, std::vector<std::pair<Index, Index>>& deferred) {
    faceVerts_[x] = vertex;
    cornerFace_[x] = face;
    if (linksOut_) {
      linksOut_[2 * size_t(x)] = twin;
      linksOut_[2 * size_t(x) + 1] = twinNext;
    }
    if (twin < 0 || twin > x) {
      const Index e = nextEdge++;
      cornerEdge_[x] = e;
      edgeVerts_[2 * e] = vertex;
      edgeVerts_[2 * e + 1] = nextVertex;
      edgeFaces_[2 * e] = face;
      edgeFaces_[2 * e + 1] = -1;
    } else if (twin < partFirstCorner) {
      deferred.emplace_back(x, twin);
    } else {
      const Index e = cornerEdge_[twin];
      cornerEdge_[x] = e;
      edgeFaces_[2 * e + 1] = face;
    }
  }

  // Faces, twins and edges, each part over its parent faces (child corners in increasing order).
  void buildFacesAndEdges() {
    touchTables(faceTables_);
    MeshTopology& t = out_.topology;
    faceVerts_ = out_.mesh.faceVerts.data();
    cornerFace_ = t.cornerFace.data();
    cornerEdge_ = t.cornerEdge.data();
    edgeVerts_ = t.edgeVerts.data();
    edgeFaces_ = t.edgeFaces.data();
    linksOut_ = options_.childLinks ? out_.links.data() : nullptr;
    out_.mesh.faceStart[0] = 0;
    std::vector<std::vector<std::pair<Index, Index>>> deferred(parts_);
    runParts(parts_, [&](unsigned k) { buildFacesAndEdgesOfPart(k, deferred[k]); });
    for (const auto& list : deferred)
      for (const auto& [x, twin] : list) {
        const Index e = cornerEdge_[twin];
        cornerEdge_[x] = e;
        edgeFaces_[2 * e + 1] = cornerFace_[x];
      }
  }

  void buildFacesAndEdgesOfPart(unsigned k, std::vector<std::pair<Index, Index>>& deferred) {
    Index* faceStart = out_.mesh.faceStart.data();
    Index* faceParent = out_.faceParent.data();
    const Index* parentVerts = parent_.faceVerts.data();
    const Index* parentEdge = topo_.cornerEdge.data();
    const Index edgePointBase = topo_.faceCount;
    const Index fBegin = faceBound(k), fEnd = faceBound(k + 1);
    const Index partFirstCorner = fBegin < fEnd ? base(parent_.faceStart[fBegin]) : 0;
    Index nextEdge = counts_[k].newEdges;
    auto emit = [&](Index x, Index vertex, Index nextVertex, Index face, Index twin, Index twinNext) {
      emitCorner(x, vertex, nextVertex, face, twin, twinNext, partFirstCorner, nextEdge, deferred);
    };
    const Index cornerEnd = parent_.faceStart[fEnd];
    for (Index f = fBegin; f < fEnd; ++f) {
      const Index begin = parent_.faceStart[f], end = parent_.faceStart[f + 1];
      for (Index c = begin; c < end; ++c) {
        // The twins' edges a few corners ahead lie elsewhere in the child (their own faces).
        if (c + kPrefetchDistance < cornerEnd) {
          const Index ahead = c + kPrefetchDistance;
          if (twinNextOf(ahead) >= 0) prefetch(cornerEdge_ + base(twinNextOf(ahead)));
        }
        const Index prev = c == begin ? end - 1 : c - 1, next = c + 1 == end ? begin : c + 1;
        const Index V = vertexPointBase_ + parentVerts[c], Ea = edgePointBase + parentEdge[c],
                    Eb = edgePointBase + parentEdge[prev], F = f;
        // Twins of the child half-edges (see the top of this file) and the corners after them.
        const Index twinC = twinOf(c), twinPrev = twinOf(prev), afterTwinC = twinNextOf(c);
        const Index twinVE = twinC < 0 ? -1 : edgeToVertex(afterTwinC);
        const Index afterVE = twinC < 0 ? -1 : base(afterTwinC) + (isSplit(afterTwinC) ? 3 : 0);
        const Index twinEF = faceToEdge(next), afterEF = edgeToVertex(next);
        const Index twinFE = edgeToFace(prev), afterFE = base(prev) + 2;
        const Index twinEV = twinPrev < 0 ? -1 : vertexToEdge(twinPrev);
        const Index afterEV = twinPrev < 0 ? -1 : base(twinPrev) + 1;
        const Index x = base(c), face = childFace(c);
        emit(x, V, Ea, face, twinVE, afterVE);
        emit(x + 1, Ea, F, face, twinEF, afterEF);
        faceParent[face] = f;
        if (!isSplit(c)) {
          emit(x + 2, F, Eb, face, twinFE, afterFE);
          emit(x + 3, Eb, V, face, twinEV, afterEV);
          faceStart[face + 1] = x + 4;
        } else {  // the diagonal V - F closes the first triangle and opens the second
          emit(x + 2, F, V, face, x + 3, x + 4);
          faceStart[face + 1] = x + 3;
          emit(x + 3, V, F, face + 1, x + 2, x);
          emit(x + 4, F, Eb, face + 1, twinFE, afterFE);
          emit(x + 5, Eb, V, face + 1, twinEV, afterEV);
          faceStart[face + 2] = x + 6;
          faceParent[face + 1] = f;
        }
      }
    }
    POLARVIEW_CHECK_EQ(nextEdge, counts_[k + 1].newEdges);
  }

  // Faces only (no edges, no twins): each parent corner's child quad, or its two triangles.
  void buildFaces() {
    touchTables(faceTables_);
    Index* faceVerts = out_.mesh.faceVerts.data();
    Index* faceStart = out_.mesh.faceStart.data();
    Index* faceParent = out_.faceParent.data();
    const Index* parentStart = parent_.faceStart.data();
    const Index* parentVerts = parent_.faceVerts.data();
    const Index* parentEdge = topo_.cornerEdge.data();
    const Index edgePointBase = topo_.faceCount;
    faceStart[0] = 0;
    const bool stream = !kSplit && reinterpret_cast<uintptr_t>(faceVerts) % 16 == 0;
    runParts(parts_, [&](unsigned k) {
      const PartRange part = partRange(k);
      if (stream) {
        streamQuads(part.fBegin, part.fEnd, faceVerts, faceStart, faceParent);
        return;
      }
      for (Index f = part.fBegin; f < part.fEnd; ++f) {
        const Index begin = parentStart[f], end = parentStart[f + 1];
        for (Index c = begin; c < end; ++c) {
          const Index prev = c == begin ? end - 1 : c - 1;
          const Index V = vertexPointBase_ + parentVerts[c], Ea = edgePointBase + parentEdge[c],
                      Eb = edgePointBase + parentEdge[prev];
          const Index x = base(c), face = childFace(c);
          faceVerts[x] = V;
          faceVerts[x + 1] = Ea;
          faceVerts[x + 2] = f;
          faceParent[face] = f;
          if (!isSplit(c)) {
            faceVerts[x + 3] = Eb;
            faceStart[face + 1] = x + 4;
          } else {  // (V, E_a, F) and (V, F, E_b), as buildFacesAndEdgesOfPart writes them
            faceStart[face + 1] = x + 3;
            faceVerts[x + 3] = V;
            faceVerts[x + 4] = f;
            faceVerts[x + 5] = Eb;
            faceStart[face + 2] = x + 6;
            faceParent[face + 1] = f;
          }
        }
      }
    });
  }

  // buildFaces without splits (child face = parent corner c, its quad at 4c: 16 aligned bytes):
  // streamed past the caches, as nothing reads a finest level's faces before its points are done.
  // Every input in a local, so no store makes the compiler reload it.
  void streamQuads(Index fBegin, Index fEnd, Index* faceVerts, Index* faceStart, Index* faceParent) const {
    const Index* parentStart = parent_.faceStart.data();
    const Index* parentVerts = parent_.faceVerts.data();
    const Index* parentEdge = topo_.cornerEdge.data();
    const Index edgePointBase = topo_.faceCount, vertexPointBase = vertexPointBase_;
    for (Index f = fBegin; f < fEnd; ++f) {
      const Index begin = parentStart[f], end = parentStart[f + 1];
      for (Index c = begin, prev = end - 1; c < end; prev = c++) {
        streamStore4(faceVerts + 4 * size_t(c), vertexPointBase + parentVerts[c], edgePointBase + parentEdge[c], f,
                     edgePointBase + parentEdge[prev]);
        streamStore(faceParent + c, f);
        streamStore(faceStart + c + 1, 4 * c + 4);
      }
    }
    storeFence();
  }

  // Appends (face, corner) to the ring of the cursor's child vertex.
  void put(RingCursor& at, Index face, Index corner) {
    vertexFaces_[at.facePos] = face;
    vertexCorners_[at.facePos++] = corner;
    vertexEdges_[at.edgePos++] = cornerEdge_[corner];
  }
  // Ends the cursor's ring (a boundary ring ends with its incoming boundary edge).
  void closeRing(RingCursor& at, bool onBoundary, Index boundaryEdge) {
    MeshTopology& t = out_.topology;
    if (onBoundary) vertexEdges_[at.edgePos++] = boundaryEdge;
    t.vertexOnBoundary[at.vertex] = onBoundary;
    t.vertexUsed[at.vertex] = at.facePos > at.ringStart;
    ++at.vertex;
    t.vertexFaceStart[at.vertex] = at.ringStart = at.facePos;
    t.vertexEdgeStart[at.vertex] = at.edgePos;
  }

  // Rings in three blocks (face points, edge points, vertex points); each part writes its own
  // stretch of each block, starting where the counts put it.
  void buildVertexRings() {
    touchTables(ringTables_);
    MeshTopology& t = out_.topology;
    vertexFaces_ = t.vertexFaces.data();
    vertexCorners_ = t.vertexCorners.data();
    vertexEdges_ = t.vertexEdges.data();
    t.vertexFaceStart[0] = t.vertexEdgeStart[0] = 0;
    const Index facePointEntries = parentCorners_ + splitCount_;  // also the edge-point block's first entry
    const Index boundaryEdges = counts_[parts_].boundaryLeaders;
    const Index vertexBlockFaces = facePointEntries + 2 * parentCorners_;
    const Index vertexBlockEdges = vertexBlockFaces + boundaryEdges;
    runParts(parts_, [&](unsigned k) {
      const PartCounts& before = counts_[k];
      const Index fBegin = faceBound(k), fEnd = faceBound(k + 1), vBegin = vertexBound(k), vEnd = vertexBound(k + 1);
      const Index firstFaceEntry = childFacesBefore(parent_.faceStart[fBegin]);
      RingCursor facePoints{fBegin, firstFaceEntry, firstFaceEntry, firstFaceEntry};
      buildFacePointRings(facePoints, fBegin, fEnd);
      const Index edgeEntries = 4 * before.interiorLeaders + 2 * before.boundaryLeaders;
      RingCursor edgePoints{topo_.faceCount + before.interiorLeaders + before.boundaryLeaders, facePointEntries + edgeEntries,
                            facePointEntries + edgeEntries, facePointEntries + edgeEntries + before.boundaryLeaders};
      buildEdgePointRings(edgePoints, fBegin, fEnd);
      const Index vertexEntries = vertexBlockFaces + topo_.vertexFaceStart[vBegin] + before.splitRingCorners;
      RingCursor vertexPoints{vertexPointBase_ + vBegin, vertexEntries, vertexEntries,
                              vertexBlockEdges + topo_.vertexEdgeStart[vBegin] + before.splitRingCorners};
      buildVertexPointRings(vertexPoints, vBegin, vEnd);
    });
  }

  // Face point of f: the corners of f in order; a split corner contributes its second triangle,
  // then its first (the walk crosses the diagonal). Starts at the first corner's first face.
  void buildFacePointRings(RingCursor& at, Index fBegin, Index fEnd) {
    for (Index f = fBegin; f < fEnd; ++f) {
      const Index begin = parent_.faceStart[f], end = parent_.faceStart[f + 1];
      for (Index c = begin; c < end; ++c) {
        if (isSplit(c) && c != begin) put(at, childFace(c) + 1, base(c) + 4);
        put(at, childFace(c), base(c) + 2);
      }
      if (isSplit(begin)) put(at, childFace(begin) + 1, base(begin) + 4);
      closeRing(at, false, -1);
    }
  }

  // Edge point of e, led by corner c (twin d): E->F(c), E->V(next d), E->F(d), E->V(next c),
  // rotated to start at the smallest; on a boundary E->V(next c), E->F(c), then the edge to V(c).
  // Edges are numbered by their leading corner, so leaders in corner order visit them in order.
  void buildEdgePointRings(RingCursor& at, Index fBegin, Index fEnd) {
    for (Index f = fBegin; f < fEnd; ++f) {
      const Index begin = parent_.faceStart[f], end = parent_.faceStart[f + 1];
      for (Index c = begin; c < end; ++c) {
        const Index d = twinOf(c);
        if (d >= 0 && d < c) continue;  // not the edge's leading corner
        const Index next = c + 1 == end ? begin : c + 1;
        if (d < 0) {
          put(at, secondChildFace(next), edgeToVertex(next));
          put(at, childFace(c), edgeToFace(c));
          closeRing(at, true, cornerEdge_[vertexToEdge(c)]);
          continue;
        }
        const Index nextD = twinNextOf(c);
        const Index faces[4] = {childFace(c), secondChildFace(nextD), childFace(d), secondChildFace(next)};
        const Index corners[4] = {edgeToFace(c), edgeToVertex(nextD), edgeToFace(d), edgeToVertex(next)};
        int start = 0;
        for (int i = 1; i < 4; ++i)
          if (corners[i] < corners[start]) start = i;
        for (int i = 0; i < 4; ++i) put(at, faces[(start + i) & 3], corners[(start + i) & 3]);
        closeRing(at, false, -1);
      }
    }
  }

  // Vertex point of v: the parent ring's corners in the parent's order (a split corner gives both
  // triangles); a boundary ring ends with the edge into the last corner.
  void buildVertexPointRings(RingCursor& at, Index vBegin, Index vEnd) {
    const Index* ringCorners = topo_.vertexCorners.data();
    const Index ringEnd = topo_.vertexFaceStart[vEnd];
    for (Index v = vBegin; v < vEnd; ++v) {
      const Index first = topo_.vertexFaceStart[v], last = topo_.vertexFaceStart[v + 1];
      for (Index i = first; i < last; ++i) {
        // The parent's rings visit corners all over the mesh: fetch the edges a few rings ahead.
        if (i + kPrefetchDistance < ringEnd) prefetch(cornerEdge_ + base(ringCorners[i + kPrefetchDistance]));
        const Index c = ringCorners[i];
        put(at, childFace(c), base(c));
        if (isSplit(c)) put(at, childFace(c) + 1, base(c) + 3);
      }
      const bool onBoundary = topo_.vertexOnBoundary[v];
      closeRing(at, onBoundary, onBoundary ? cornerEdge_[edgeToVertex(topo_.vertexCorners[last - 1])] : -1);
    }
  }

  const PolyMesh& parent_;
  const MeshTopology& topo_;
  const Index* parentLinks_;
  const uint8_t* split_;
  RefinedConnectivity& out_;
  const ConnectivityOptions& options_;

  unsigned parts_ = 1;
  std::vector<TableJob> faceTables_, ringTables_;  // written by the faces-and-edges pass / the ring pass
  std::vector<PartCounts> counts_;     // counts_[k]: totals of parts before k (counts_[parts_]: all)
  std::vector<Index> firstChildFace_;  // split mode: per parent corner, its first child face
  Index parentCorners_ = 0, splitCount_ = 0, vertexPointBase_ = 0, childCorners_ = 0;

  Index *faceVerts_ = nullptr, *cornerFace_ = nullptr, *cornerEdge_ = nullptr, *edgeVerts_ = nullptr,
        *edgeFaces_ = nullptr, *linksOut_ = nullptr;
  Index *vertexFaces_ = nullptr, *vertexCorners_ = nullptr, *vertexEdges_ = nullptr;
};

}  // namespace

void completeChildTopology(const PolyMesh& parent, const MeshTopology& topo, const std::vector<Index>& links,
                           const std::vector<uint8_t>* splitCorner, RefinedConnectivity& child, const ConnectivityOptions& options) {
  ConnectivityOptions complete = options;
  complete.vertexRings = complete.edges = true;
  complete.childLinks = false;
  const bool hasEdges = child.topology.cornerEdge.size() == child.mesh.faceVerts.size() && !child.mesh.faceVerts.empty();
  // Without edges: the whole step again (it rewrites the faces as they are and keeps the points,
  // whose size it sets to theirs); with them, the ring pass alone.
  std::vector<Index> keptLinks;
  keptLinks.swap(child.links);
  if (splitCorner) {
    ConnectivityBuilder<true> builder(parent, topo, links, splitCorner->data(), child, complete);
    hasEdges ? builder.completeRings() : builder.build();
  } else {
    ConnectivityBuilder<false> builder(parent, topo, links, nullptr, child, complete);
    hasEdges ? builder.completeRings() : builder.build();
  }
  child.links.swap(keptLinks);
}

void refineCatmullClarkConnectivity(const PolyMesh& parent, const MeshTopology& topo, const std::vector<Index>& links,
                                    const std::vector<uint8_t>* splitCorner, RefinedConnectivity& out,
                                    const ConnectivityOptions& options) {
  if (splitCorner)
    ConnectivityBuilder<true>(parent, topo, links, splitCorner->data(), out, options).build();
  else
    ConnectivityBuilder<false>(parent, topo, links, nullptr, out, options).build();
}

}  // namespace polarview
