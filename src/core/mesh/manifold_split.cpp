// Non-manifold meshes split into manifold ones with OpenSubdiv's sharpening (manifold_split.h).
#include "core/mesh/manifold_split.h"

#include "core/mesh/input_error.h"

#include <algorithm>
#include <numeric>
#include <unordered_map>
#include <utility>

namespace polarview {

namespace {

// The input's edges as OpenSubdiv's Vtr makes them (Level::completeTopologyFromFaceVertices): faces
// in order, each side c -> next(c) joins the first edge of its vertex pair, except that a side
// whose ends are one vertex, or whose pair this face already used, starts an edge of its own. An
// edge is non-manifold when it is such a loop or repeat, gets a third face, or a second face
// running it the same way.
struct EdgeInstances {
  std::vector<Index> next;        // per corner: the next corner of its face
  std::vector<Index> edgeOf;      // per corner: the edge its side joined
  std::vector<Index> from, to;    // per edge: its ends as first made
  std::vector<Index> firstSide, secondSide;  // per edge: its first two sides (corners; -1: none)
  std::vector<int> sides;         // per edge: how many sides joined it
  std::vector<uint8_t> nonManifold;
  std::vector<uint8_t> firstOfPair;  // per edge: the first made for its vertex pair (tags name it)

  size_t count() const { return from.size(); }
  bool manifold(size_t e) const { return !nonManifold[e] && sides[e] == 2; }
};

EdgeInstances makeEdges(const PolyMesh& mesh) {
  EdgeInstances g;
  const std::vector<Index>& fv = mesh.faceVerts;
  const size_t corners = fv.size();
  g.next.resize(corners);
  g.edgeOf.resize(corners);
  for (Index f = 0; f < mesh.faceCount(); ++f)
    for (Index c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; ++c) g.next[size_t(c)] = c + 1 < mesh.faceStart[f + 1] ? c + 1 : mesh.faceStart[f];
  std::unordered_map<uint64_t, Index> firstOfPair;  // the first edge made for a vertex pair
  firstOfPair.reserve(corners);
  std::vector<Index> lastFace;
  auto make = [&](Index a, Index b) {
    g.from.push_back(a), g.to.push_back(b), g.firstSide.push_back(-1), g.secondSide.push_back(-1);
    g.sides.push_back(0), g.nonManifold.push_back(0), g.firstOfPair.push_back(0), lastFace.push_back(-1);
    return Index(g.from.size() - 1);
  };
  for (Index f = 0; f < mesh.faceCount(); ++f)
    for (Index c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; ++c) {
      const Index v0 = fv[size_t(c)], v1 = fv[size_t(g.next[size_t(c)])];
      Index e = -1;
      if (v0 == v1) {
        e = make(v0, v1);
        g.nonManifold[size_t(e)] = 1;
      } else {
        const uint64_t key = uint64_t(uint32_t(std::min(v0, v1))) << 32 | uint32_t(std::max(v0, v1));
        const auto [at, added] = firstOfPair.try_emplace(key, -1);
        if (!added) {
          e = at->second;
          if (lastFace[size_t(e)] == f) {  // this face already runs the pair: an edge of its own
            g.nonManifold[size_t(e)] = 1;
            e = make(v0, v1);
            g.nonManifold[size_t(e)] = 1;
          } else if (g.sides[size_t(e)] > 1 || v0 == g.from[size_t(e)]) {
            g.nonManifold[size_t(e)] = 1;
          }
        } else {
          e = at->second = make(v0, v1);
          g.firstOfPair[size_t(e)] = 1;
        }
      }
      if (g.sides[size_t(e)] == 0) g.firstSide[size_t(e)] = c;
      else if (g.sides[size_t(e)] == 1) g.secondSide[size_t(e)] = c;
      ++g.sides[size_t(e)];
      lastFace[size_t(e)] = f;
      g.edgeOf[size_t(c)] = e;
    }
  return g;
}

Index findRoot(std::vector<Index>& parent, Index c) {
  while (parent[size_t(c)] != c) c = parent[size_t(c)] = parent[size_t(parent[size_t(c)])];
  return c;
}

// Fans: corners at a vertex joined across its manifold edges (both ends of each). Returns the
// union-find parents; findRoot gives a corner's fan. [O(corners)]
std::vector<Index> joinFans(const EdgeInstances& edges, size_t corners) {
  std::vector<Index> parent(corners);
  std::iota(parent.begin(), parent.end(), Index(0));
  auto join = [&](Index a, Index b) {
    a = findRoot(parent, a), b = findRoot(parent, b);
    if (a != b) parent[size_t(std::max(a, b))] = std::min(a, b);
  };
  for (size_t e = 0; e < edges.count(); ++e) {
    if (!edges.manifold(e)) continue;
    const Index c1 = edges.firstSide[e], c2 = edges.secondSide[e];
    join(c1, edges.next[size_t(c2)]);
    join(edges.next[size_t(c1)], c2);
  }
  return parent;
}

// Per input vertex what Far counts (an edge once per end, a loop twice): incident edges, boundary
// and non-manifold ones, faces (once per corner); whether it is non-manifold, and its first fan.
struct VertexCounts {
  std::vector<uint8_t> nonManifold;
  std::vector<int> edgeCount, boundaryEdges, nonManifoldEdges, cornerCount;
  std::vector<Index> firstRoot;  // the fan (root corner) of its first corner
};

// Counts at every vertex, and the non-manifold edges and vertices into `split`. [O(corners)]
VertexCounts countAtVertices(const PolyMesh& mesh, const EdgeInstances& edges, std::vector<Index>& parent,
                             ManifoldSplit& split) {
  const std::vector<Index>& fv = mesh.faceVerts;
  const size_t corners = fv.size(), vertices = size_t(mesh.vertexCount());
  VertexCounts at;
  at.nonManifold.assign(vertices, 0);
  at.edgeCount.assign(vertices, 0), at.boundaryEdges.assign(vertices, 0);
  at.nonManifoldEdges.assign(vertices, 0), at.cornerCount.assign(vertices, 0);
  for (size_t e = 0; e < edges.count(); ++e) {
    for (const Index v : {edges.from[e], edges.to[e]}) {
      ++at.edgeCount[size_t(v)];
      at.boundaryEdges[size_t(v)] += edges.sides[e] < 2;
      at.nonManifoldEdges[size_t(v)] += edges.nonManifold[e];
      if (edges.nonManifold[e]) at.nonManifold[size_t(v)] = 1;
    }
    split.nonManifoldEdges += edges.nonManifold[e];
  }
  // Several fans at a vertex (Far's orderVertexFacesAndEdges fails).
  at.firstRoot.assign(vertices, -1);
  for (size_t c = 0; c < corners; ++c) {
    const Index v = fv[c], root = findRoot(parent, Index(c));
    ++at.cornerCount[size_t(v)];
    if (at.firstRoot[size_t(v)] < 0) at.firstRoot[size_t(v)] = root;
    else if (at.firstRoot[size_t(v)] != root) at.nonManifold[size_t(v)] = 1;
  }
  split.nonManifoldVertices = size_t(std::count(at.nonManifold.begin(), at.nonManifold.end(), uint8_t(1)));
  return at;
}

// Copies: a vertex's first fan keeps its id, each further fan gets a new vertex after the input's.
// Fills split.mesh's points and faces and split.sourceVertex. [O(corners)]
void copyVertexPerFan(const PolyMesh& mesh, std::vector<Index>& parent, const std::vector<Index>& firstRoot,
                      ManifoldSplit& split) {
  const std::vector<Index>& fv = mesh.faceVerts;
  const size_t corners = fv.size(), vertices = size_t(mesh.vertexCount());
  PolyMesh& out = split.mesh;
  out.points = mesh.points;
  split.sourceVertex.resize(vertices);
  std::iota(split.sourceVertex.begin(), split.sourceVertex.end(), Index(0));
  std::vector<Index> copyOfRoot(corners, -1);
  out.faceStart = mesh.faceStart;
  out.faceLine = mesh.faceLine;
  out.faceVerts.resize(corners);
  for (size_t c = 0; c < corners; ++c) {
    const Index v = fv[c], root = findRoot(parent, Index(c));
    Index& copy = copyOfRoot[size_t(root)];
    if (copy < 0) {
      if (root == firstRoot[size_t(v)]) {
        copy = v;
      } else {
        copy = Index(split.sourceVertex.size());
        split.sourceVertex.push_back(v);
        out.points.push_back(mesh.points[size_t(v)]);
      }
    }
    out.faceVerts[c] = copy;
  }
}

// What the crease tags of the input leave for the vertex and hole rules.
struct UserCreases {
  std::vector<uint8_t> infiniteEdge;  // per edge: a tag made it infinitely sharp
  std::vector<double> userSharpest;   // per input vertex: the sharpest tag on a manifold edge at it
};

// Crease tags of the split mesh: the input's on manifold edges, every side of a non-manifold edge
// infinitely sharp; one tag per vertex pair, the sharpest. Also copies the input's tags that need
// no translation. [O(edges log edges)]
UserCreases addCreaseTags(const PolyMesh& mesh, const EdgeInstances& edges, ManifoldSplit& split) {
  const size_t corners = mesh.faceVerts.size(), vertices = size_t(mesh.vertexCount());
  const SubdivTags& in = mesh.tags;
  PolyMesh& out = split.mesh;
  SubdivTags& tags = out.tags;
  tags.creaseMethod = in.creaseMethod;
  tags.triangles = in.triangles;
  tags.holes = in.holes;
  tags.boundary = BoundaryInterpolation::EdgeOnly;  // the other rules are written out as corners and holes
  auto userCrease = [&](Index a, Index b) {
    const auto it = std::lower_bound(in.creases.begin(), in.creases.end(), std::pair<Index, Index>(a, b),
                                     [](const CreaseEdge& e, const std::pair<Index, Index>& k) {
                                       return std::pair<Index, Index>(e.v0, e.v1) < k;
                                     });
    return it != in.creases.end() && it->v0 == a && it->v1 == b ? it->sharpness : 0.0;
  };
  auto addCrease = [&](Index c, double sharpness) {
    const Index a = out.faceVerts[size_t(c)], b = out.faceVerts[size_t(edges.next[size_t(c)])];
    tags.creases.push_back({std::min(a, b), std::max(a, b), sharpness});
  };
  // A tag names a vertex pair: Far's FindEdge gives it to the pair's first edge.
  UserCreases user{std::vector<uint8_t>(edges.count(), 0), std::vector<double>(vertices, 0.0)};
  for (size_t e = 0; e < edges.count(); ++e) {
    if (!edges.firstOfPair[e]) continue;
    const double sharpness = userCrease(std::min(edges.from[e], edges.to[e]), std::max(edges.from[e], edges.to[e]));
    user.infiniteEdge[e] = sharpness >= kInfiniteSharpness;
    if (!edges.nonManifold[e] && sharpness > 0.0) {
      addCrease(edges.firstSide[e], sharpness);
      for (const Index v : {edges.from[e], edges.to[e]})
        user.userSharpest[size_t(v)] = std::max(user.userSharpest[size_t(v)], sharpness);
    }
  }
  for (size_t c = 0; c < corners; ++c)
    if (edges.nonManifold[size_t(edges.edgeOf[c])]) addCrease(Index(c), kInfiniteSharpness);
  std::sort(tags.creases.begin(), tags.creases.end(), [](const CreaseEdge& x, const CreaseEdge& y) {
    return x.v0 != y.v0 ? x.v0 < y.v0 : x.v1 != y.v1 ? x.v1 < y.v1 : x.sharpness > y.sharpness;
  });
  tags.creases.erase(std::unique(tags.creases.begin(), tags.creases.end(),
                                 [](const CreaseEdge& x, const CreaseEdge& y) { return x.v0 == y.v0 && x.v1 == y.v1; }),
                     tags.creases.end());
  return user;
}

// Corner tags of the split mesh: the input's, sharpened non-manifold vertices, and
// `interpolateboundary 1`'s topological corners, on every copy. [O(vertices)]
void addCornerTags(const PolyMesh& mesh, const VertexCounts& at, const std::vector<double>& userSharpest,
                   ManifoldSplit& split) {
  const SubdivTags& in = mesh.tags;
  const size_t vertices = size_t(mesh.vertexCount());
  std::vector<double> vertexSharpness(vertices, 0.0);
  for (const CornerVertex& corner : in.corners) vertexSharpness[size_t(corner.vertex)] = corner.sharpness;
  for (size_t v = 0; v < vertices; ++v) {
    const bool topologicalCorner = at.cornerCount[v] == 1 && at.edgeCount[v] == 2;
    const bool interiorCrease = at.nonManifoldEdges[v] == 2 && at.boundaryEdges[v] == 0 && at.cornerCount[v] > at.edgeCount[v];
    if ((topologicalCorner && in.boundary == BoundaryInterpolation::EdgeAndCorner) || (at.nonManifold[v] && !interiorCrease))
      vertexSharpness[v] = kInfiniteSharpness;
    // An interior non-manifold crease with a tagged edge more has three sharp edges, Far's corner
    // rule, until the tag decays; each copy's fan sees only its own edges, so every copy gets the
    // tag's sharpness as a vertex sharpness: the same rule, decay and transition weight under
    // CREASE_UNIFORM for one tagged edge (with several, the sharpest: an approximation).
    else if (interiorCrease && userSharpest[v] > 0.0)
      vertexSharpness[v] = std::max(vertexSharpness[v], userSharpest[v]);
  }
  for (size_t w = 0; w < split.sourceVertex.size(); ++w)
    if (const double s = vertexSharpness[size_t(split.sourceVertex[w])]; s > 0.0)
      split.mesh.tags.corners.push_back({Index(w), s});
}

// interpolateboundary 0: faces at a boundary or non-manifold vertex with a boundary edge the
// tags did not make infinitely sharp are holes (decided before any sharpening, as Far does).
void addBoundaryHoles(const PolyMesh& mesh, const EdgeInstances& edges, const VertexCounts& at,
                      const std::vector<uint8_t>& infiniteEdge, SubdivTags& tags) {
  std::vector<uint8_t> excluded(size_t(mesh.vertexCount()), 0);
  for (size_t e = 0; e < edges.count(); ++e) {
    if (edges.sides[e] != 1 || infiniteEdge[e]) continue;
    for (const Index v : {edges.from[e], edges.to[e]})
      if (at.edgeCount[size_t(v)] != at.cornerCount[size_t(v)] || at.nonManifold[size_t(v)]) excluded[size_t(v)] = 1;
  }
  for (Index f = 0; f < mesh.faceCount(); ++f)
    for (Index c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; ++c)
      if (excluded[size_t(mesh.faceVerts[size_t(c)])]) {
        tags.holes.push_back(f);
        break;
      }
  std::sort(tags.holes.begin(), tags.holes.end());
  tags.holes.erase(std::unique(tags.holes.begin(), tags.holes.end()), tags.holes.end());
}

}  // namespace

std::vector<Point> ManifoldSplit::splitPoints(const std::vector<Point>& inputPoints) const {
  std::vector<Point> points(sourceVertex.size());
  for (size_t v = 0; v < sourceVertex.size(); ++v) points[v] = inputPoints[size_t(sourceVertex[v])];
  return points;
}

ManifoldSplit splitNonManifold(const PolyMesh& mesh) {
  const EdgeInstances edges = makeEdges(mesh);
  std::vector<Index> parent = joinFans(edges, mesh.faceVerts.size());
  ManifoldSplit split;
  const VertexCounts at = countAtVertices(mesh, edges, parent, split);
  if (split.nonManifoldEdges == 0 && split.nonManifoldVertices == 0) return ManifoldSplit{};

  copyVertexPerFan(mesh, parent, at.firstRoot, split);
  // Tags: OpenSubdiv's sharpening of the input, on the copies.
  const UserCreases user = addCreaseTags(mesh, edges, split);
  addCornerTags(mesh, at, user.userSharpest, split);
  if (mesh.tags.boundary == BoundaryInterpolation::None)
    addBoundaryHoles(mesh, edges, at, user.infiniteEdge, split.mesh.tags);
  return split;
}

const PolyMesh& refinableMesh(const PolyMesh& mesh, ManifoldSplit& storage, MeshTopology& topology,
                              const std::string& sourceName) {
  storage = ManifoldSplit{};
  try {
    topology = buildTopology(mesh, sourceName);  // the common case: no split to make
    return mesh;
  } catch (const InputError&) {
    storage = splitNonManifold(mesh);
    if (storage.empty()) throw;  // not a matter of manifoldness: the tables' own error
  }
  topology = buildTopology(storage.mesh, sourceName);
  return storage.mesh;
}

}  // namespace polarview
