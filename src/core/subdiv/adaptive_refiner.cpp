// Feature-adaptive refinement (rules and exactness: adaptive_refiner.h).
// [SECTION] selecting the faces to refine
// [SECTION] the selection as a mesh of its own
// [SECTION] the radial step (RTS/BPS caps and globes, the tail's poles)
// [SECTION] the sparse step (Catmull-Clark and C2PS connectivity)
// [SECTION] AdaptiveRefinement
#include "core/subdiv/adaptive_refiner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/mesh/input_error.h"
#include "core/mesh/manifold_split.h"
#include "core/subdiv/catmull_clark.h"
#include "core/subdiv/face_regularity.h"
#include "core/subdiv/parallel_for.h"
#include "core/subdiv/refine_steps.h"
#include "core/subdiv/refine_topology.h"

namespace polarview {

namespace {

// Rings of support around the faces a radial step refines (RTS/BPS caps and globes, the tail's
// poles), copied out whole: the cubic radial rules and (11) read up to two rows beyond. Catmull-Clark
// and C2PS steps are sparse and need none (adaptive_refiner.h).
constexpr int kRadialSupportRings = 3;
// RTS/BPS outside caps and globes run on C2PS's connectivity (the polar valence doubles a level,
// with points from each pole's own radial grid refined periodically). From this level on a pole's
// region keeps its columns and is refined radially (the tail): the same surface (periodic
// refinement is knot insertion), one ring a level, so these schemes go as deep as on caps. Up to
// it the patches equal the uniform refinement's patch for patch; beyond, a tail ring patch spans
// 2^(m - kRadialTailLevel) of the uniform level m's.
constexpr int kRadialTailLevel = 5;

// [SECTION] selecting the faces to refine

// Faces of `level` to refine: needed and not regular. [O(faces)]
std::vector<uint8_t> facesToRefine(const RefinedLevel& level, const std::vector<uint8_t>& needed) {
  std::vector<VertexClass> classes(level.mesh.vertexCount(), VertexClass::Unknown);
  markSharpVertices(level.mesh, level.topology, level.sharpness, classes.data());
  std::vector<uint8_t> refine(level.mesh.faceCount(), 0);
  for (Index f = 0; f < level.mesh.faceCount(); ++f)
    refine[f] = needed[f] && !isRegularFace(level.mesh, level.topology, f, classes.data());
  return refine;
}

// `selected` grown by `rings` rings (every face sharing a vertex with a selected face), then closed
// so that the selected faces around every vertex form one fan (a copied-out mesh must be manifold).
void growSelection(const RefinedLevel& level, std::vector<uint8_t>& selected, int rings) {
  const PolyMesh& mesh = level.mesh;
  const MeshTopology& topo = level.topology;
  std::vector<uint8_t> touched(mesh.vertexCount());
  auto addFacesAround = [&](Index v) {
    for (Index k = topo.vertexFaceStart[v]; k < topo.vertexFaceStart[v + 1]; ++k) selected[topo.vertexFaces[k]] = 1;
  };
  for (int ring = 0; ring < rings; ++ring) {
    std::fill(touched.begin(), touched.end(), 0);
    for (Index f = 0; f < mesh.faceCount(); ++f)
      if (selected[f])
        for (Index c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; ++c) touched[mesh.faceVerts[c]] = 1;
    for (Index v = 0; v < mesh.vertexCount(); ++v)
      if (touched[v]) addFacesAround(v);
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (Index v = 0; v < mesh.vertexCount(); ++v) {
      const Index first = topo.vertexFaceStart[v], count = topo.faceValence(v);
      int runs = 0, in = 0;
      for (Index k = 0; k < count; ++k) {
        const bool now = selected[topo.vertexFaces[first + k]];
        // A run starts where a selected face follows an unselected one (rotational order; an
        // interior vertex's ring wraps round, a boundary vertex's does not).
        const bool before = k > 0 ? bool(selected[topo.vertexFaces[first + k - 1]])
                                  : !topo.vertexOnBoundary[v] && bool(selected[topo.vertexFaces[first + count - 1]]);
        runs += now && !before;
        in += now;
      }
      if (in > 0 && in < count && runs > 1) {
        addFacesAround(v);
        changed = true;
      }
    }
  }
}

// [SECTION] the selection as a mesh of its own

// Per vertex of `level`: 1 when every face around it is selected.
std::vector<uint8_t> verticesInside(const RefinedLevel& level, const std::vector<uint8_t>& selected) {
  const MeshTopology& topo = level.topology;
  std::vector<uint8_t> inside(level.mesh.vertexCount(), 0);
  for (Index v = 0; v < level.mesh.vertexCount(); ++v) {
    bool all = topo.vertexFaceStart[v + 1] > topo.vertexFaceStart[v];
    for (Index k = topo.vertexFaceStart[v]; k < topo.vertexFaceStart[v + 1] && all; ++k)
      all = selected[topo.vertexFaces[k]];
    inside[v] = all;
  }
  return inside;
}

// A pole of `level` in the copied-out mesh: the same columns and first links, truncated to the
// links whose inner rows lie wholly inside the selection.
PolarConfig truncatedConfig(const PolarConfig& config, const std::vector<uint8_t>& inside, const std::vector<Index>& toSub,
                            bool radial) {
  if (!inside[config.pole]) throw std::logic_error("adaptive refinement: a pole's fan was not selected");
  int links = 1;  // links 0..links-1 have all their faces selected, so rows 0..links-1 are whole
  while (links < config.linkCount) {
    bool all = true;
    for (int j = 0; j < config.valence && all; ++j) all = inside[config.links[size_t(links - 1) * config.valence + j]];
    if (!all) break;
    ++links;
  }
  PolarConfig sub = config;
  sub.pole = toSub[config.pole];
  sub.links.resize(size_t(links) * config.valence);
  for (size_t k = 0; k < sub.links.size(); ++k) sub.links[k] = toSub[config.links[k]];
  // A radial part must end at a boundary or a pole: where its configuration runs into the rest of
  // a (sparse) level, its last link is a cut.
  if (links < config.linkCount || (radial && config.outer == PolarConfig::Outer::Mesh)) {
    sub.linkCount = links;
    sub.regularLinks = std::min(config.regularLinks, links);
    // The cut is a boundary of the copied-out mesh: a radial step then treats the part as a cap.
    sub.outer = radial ? PolarConfig::Outer::Boundary : PolarConfig::Outer::Mesh;
    sub.oppositePole = -1;
  } else if (config.oppositePole >= 0) {
    sub.oppositePole = toSub[config.oppositePole];
  }
  return sub;
}

}  // namespace

// A part of level m copied out as a mesh of its own, refined one step.
struct CopiedPart {
  RefinedLevel sub;               // the selected faces (points gathered on each update)
  std::vector<Index> subToLevel;  // sub vertex -> level m vertex
  std::vector<Index> subFaces;    // sub face -> level m face
  std::vector<RadialRegion> regions, childRegions;  // radial parts: regions of sub and of the child
  // Per sub vertex: exact at level m, and whether its faces in sub are the uniform level's.
  std::vector<uint8_t> ok, full;
  // Precision: per sub vertex its connected component (faces sharing vertices); per component the
  // level m vertex its children's frame is anchored at (its pole where it has one).
  std::vector<uint32_t> component;
  std::vector<Index> anchors;
};

// A sparse Catmull-Clark/C2PS step of level m (adaptive_refiner.h): the children of its faces at
// the corners of the selected vertices, made from level m itself. What the points need again.
struct SparsePart {
  SparseChildVertices children;       // per child vertex its parent element (catmull_clark.h)
  std::vector<Index> parentVertices;  // the level m vertices the rules read: the corners of the faces refined
  std::vector<uint32_t> parentFrame;  // ... and the child frame (component) each is read in
  std::vector<Index> anchors;         // per component: the level m vertex its frame is anchored at
};

struct AdaptiveRefinement::Step {
  // Refined sparsely by Catmull-Clark's connectivity (+ C2PS's split pole corners), or (radial_)
  // radially in caps and globes, copied out. In a tail step (RTS/BPS outside caps and globes, from
  // kRadialTailLevel on) the poles' regions were refined radially apart; their points come from
  // each pole's own radial grid, so the step keeps nothing of them.
  SparsePart sparse;
  CopiedPart radial;
  // The child's frames (RefinedLevel::frameOrigins): per frame the level m vertex it is anchored at
  // (the sparse or radial part's components, then the tail's pole regions).
  std::vector<Index> frameAnchors;
};

namespace {

// Precision: the connected components of a part (faces sharing a vertex), each anchored at its
// pole where it has one, else at its first vertex. Deep levels are made of small components
// around poles and extraordinary vertices, each refined in a frame of its own. [O(part)]
void markComponents(CopiedPart& part) {
  const PolyMesh& mesh = part.sub.mesh;
  std::vector<Index> parent(size_t(mesh.vertexCount()));
  for (Index v = 0; v < mesh.vertexCount(); ++v) parent[size_t(v)] = v;
  auto find = [&](Index v) {
    while (parent[size_t(v)] != v) v = parent[size_t(v)] = parent[size_t(parent[size_t(v)])];
    return v;
  };
  for (Index f = 0; f < mesh.faceCount(); ++f)
    for (Index c = mesh.faceStart[f] + 1; c < mesh.faceStart[f + 1]; ++c) {
      const Index a = find(mesh.faceVerts[mesh.faceStart[f]]), b = find(mesh.faceVerts[c]);
      if (a != b) parent[size_t(std::max(a, b))] = std::min(a, b);
    }
  part.component.assign(size_t(mesh.vertexCount()), 0);
  std::vector<int64_t> componentOfRoot(size_t(mesh.vertexCount()), -1);
  for (Index v = 0; v < mesh.vertexCount(); ++v) {
    int64_t& id = componentOfRoot[size_t(find(v))];
    if (id < 0) {
      id = int64_t(part.anchors.size());
      part.anchors.push_back(part.subToLevel[size_t(v)]);
    }
    part.component[size_t(v)] = uint32_t(id);
  }
  for (const PolarConfig& config : part.sub.poles) part.anchors[part.component[size_t(config.pole)]] = part.subToLevel[size_t(config.pole)];
}

// Copies the selected faces of `level` out (faces in order, vertices numbered by first use), with
// `poles` mapped and truncated to the links whose rows were selected whole.
CopiedPart copyOut(const RefinedLevel& level, const std::vector<uint8_t>& selected, const std::vector<PolarConfig>& poles,
                   bool radial, const std::vector<uint8_t>& exact, const std::vector<uint8_t>& complete,
                   const std::string& source) {
  CopiedPart part;
  std::vector<Index> toSub(level.mesh.vertexCount(), -1);
  std::vector<Index> loop;
  for (Index f = 0; f < level.mesh.faceCount(); ++f) {
    if (!selected[f]) continue;
    part.subFaces.push_back(f);
    loop.assign(level.mesh.face(f), level.mesh.face(f) + level.mesh.faceSize(f));
    for (Index& v : loop) {
      if (toSub[v] < 0) {
        toSub[v] = Index(part.subToLevel.size());
        part.subToLevel.push_back(v);
      }
      v = toSub[v];
    }
    part.sub.mesh.addFace(loop.data(), loop.size());
  }
  part.sub.mesh.points.assign(part.subToLevel.size(), Point(0.0));
  part.sub.topology = buildTopology(part.sub.mesh, source);
  // Creases and corners: the part's edges and vertices keep the level's sharpness.
  if (!level.sharpness.empty()) {
    CreaseSharpness& sharpness = part.sub.sharpness;
    sharpness.chaikin = level.sharpness.chaikin;
    sharpness.smoothTriangles = level.sharpness.smoothTriangles;
    sharpness.edge.assign(size_t(part.sub.topology.edgeCount), 0.0f);
    sharpness.vertex.assign(part.subToLevel.size(), 0.0f);
    for (Index e = 0; e < part.sub.topology.edgeCount; ++e) {
      const Index a = part.subToLevel[size_t(part.sub.topology.edgeVerts[2 * e])];
      const Index b = part.subToLevel[size_t(part.sub.topology.edgeVerts[2 * e + 1])];
      const Index edge = level.topology.edgeBetween(a, b);
      if (edge >= 0) sharpness.edge[size_t(e)] = level.sharpness.edge[size_t(edge)];
    }
    for (size_t v = 0; v < part.subToLevel.size(); ++v) sharpness.vertex[v] = level.sharpness.vertex[size_t(part.subToLevel[v])];
  }
  const std::vector<uint8_t> inside = verticesInside(level, selected);
  for (const PolarConfig& config : poles) part.sub.poles.push_back(truncatedConfig(config, inside, toSub, radial));
  for (const Index w : part.subToLevel) {
    part.ok.push_back(exact[w]);
    part.full.push_back(complete[w] && inside[w]);
  }
  markComponents(part);
  return part;
}

// The faces of rows 0 and 1 of each pole (its fan and the quads at its 1-link): what a pole needs
// refined at every level.
std::vector<uint8_t> poleRows(const RefinedLevel& level) {
  std::vector<uint8_t> rows(level.mesh.faceCount(), 0);
  auto markFaces = [&](Index v) {
    for (Index k = level.topology.vertexFaceStart[v]; k < level.topology.vertexFaceStart[v + 1]; ++k)
      rows[level.topology.vertexFaces[k]] = 1;
  };
  for (const PolarConfig& config : level.poles) {
    markFaces(config.pole);
    for (int j = 0; j < config.valence; ++j) markFaces(config.links[j]);
  }
  return rows;
}

// Whether two face selections share a vertex.
bool selectionsTouch(const RefinedLevel& level, const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  std::vector<uint8_t> used(level.mesh.vertexCount(), 0);
  for (Index f = 0; f < level.mesh.faceCount(); ++f)
    if (a[f])
      for (Index c = level.mesh.faceStart[f]; c < level.mesh.faceStart[f + 1]; ++c) used[level.mesh.faceVerts[c]] = 1;
  for (Index f = 0; f < level.mesh.faceCount(); ++f)
    if (b[f])
      for (Index c = level.mesh.faceStart[f]; c < level.mesh.faceStart[f + 1]; ++c)
        if (used[level.mesh.faceVerts[c]]) return true;
  return false;
}

// Appends `part` (a child level of its own) to `into`: vertices and faces after those there, its
// frames after `frameBase`.
void appendLevel(RefinedLevel& into, const RefinedLevel& part, uint32_t frameBase) {
  const Index vertexBase = into.mesh.vertexCount();
  for (Index f = 0; f < part.mesh.faceCount(); ++f) {
    std::vector<Index> loop(part.mesh.face(f), part.mesh.face(f) + part.mesh.faceSize(f));
    for (Index& v : loop) v += vertexBase;
    into.mesh.addFace(loop.data(), loop.size());
    into.faceParent.push_back(part.faceParent[f]);
  }
  into.mesh.points.resize(size_t(vertexBase) + part.mesh.points.size());
  into.vertexFrame.resize(size_t(vertexBase), 0);
  for (const uint32_t frame : part.vertexFrame) into.vertexFrame.push_back(frameBase + frame);
  for (PolarConfig config : part.poles) {
    config.pole += vertexBase;
    for (Index& v : config.links) v += vertexBase;
    if (config.oppositePole >= 0) config.oppositePole += vertexBase;
    into.poles.push_back(std::move(config));
  }
}

// [SECTION] the radial step (RTS/BPS caps and globes, the tail's poles)

// Refines a copied-out part one radial step (its regions); the child's faceParent is mapped back to
// level m, and the exactness and completeness of its vertices follow the rows the rules read.
void refineRadialPart(CopiedPart& part, const std::string& source, RefinedLevel& child, std::vector<uint8_t>& childExact,
                      std::vector<uint8_t>& childComplete) {
  const std::vector<uint8_t>& ok = part.ok;
  const std::vector<uint8_t>& full = part.full;
  part.regions = findRadialRegions(part.sub);
  if (part.regions.empty() && part.sub.mesh.faceCount() > 0)
    throw std::logic_error("adaptive refinement: the selection is not made of polar regions");
  child = refineRadialTopology(part.regions, part.childRegions, source);
  childExact.assign(child.mesh.vertexCount(), 0);
  childComplete.assign(child.mesh.vertexCount(), 0);
  for (size_t r = 0; r < part.regions.size(); ++r) {
    const RadialRegion& parent = part.regions[r];
    const RadialRegion& region = part.childRegions[r];
    // Parent rows exact in a row (0..K, then B); the last ring of an open region counts when
    // it is a real boundary (kept in place by the rule) and not a cut.
    auto rowOk = [&](int row) {
      const int n = parent.n;
      for (int j = 0; j < (row == 0 || row == parent.links + 1 ? 1 : n); ++j) {
        const Index v = parent.vertexIds[row == 0 ? 0 : row == parent.links + 1 ? parent.vertexIds.size() - 1 : 1 + size_t(row - 1) * n + j];
        if (!ok[v] || (!parent.closed && row == parent.links && !full[v])) return false;
      }
      return true;
    };
    std::vector<uint8_t> prefixOk(size_t(parent.rowCount()), 0);  // rows 0..r all exact
    for (int row = 0; row < parent.rowCount(); ++row) prefixOk[row] = rowOk(row) && (row == 0 || prefixOk[row - 1]);
    const bool realRim = parent.closed || prefixOk[parent.links];
    for (int row = 0; row < region.rowCount(); ++row) {
      // A child row reads parent rows up to row / 2 + 2 (a closed region: all of them).
      const int reads = parent.closed ? parent.rowCount() - 1 : std::min(parent.links, row / 2 + 2);
      const bool rowExact = prefixOk[reads];
      const bool rowComplete = parent.closed || row < region.links || realRim;
      for (int j = 0; j < (row == 0 || row == region.links + 1 ? 1 : region.n); ++j) {
        childExact[region.vertex(row, j)] = rowExact;
        childComplete[region.vertex(row, j)] = rowComplete;
      }
    }
  }
  // Each child vertex lies in the frame of its parent face's component.
  child.vertexFrame.assign(size_t(child.mesh.vertexCount()), 0);
  for (Index f = 0; f < child.mesh.faceCount(); ++f) {
    const uint32_t frame = part.component[size_t(part.sub.mesh.faceVerts[part.sub.mesh.faceStart[child.faceParent[f]]])];
    for (Index c = child.mesh.faceStart[f]; c < child.mesh.faceStart[f + 1]; ++c) child.vertexFrame[size_t(child.mesh.faceVerts[c])] = frame;
  }
  for (Index& parent : child.faceParent) parent = part.subFaces[parent];
}

// [SECTION] the sparse step (Catmull-Clark and C2PS connectivity)

// The vertices whose corners a sparse step refines: the corners of the faces to refine. [O(corners)]
std::vector<uint8_t> selectVertices(const RefinedLevel& level, const std::vector<uint8_t>& refine) {
  const PolyMesh& mesh = level.mesh;
  std::vector<uint8_t> selected(size_t(mesh.vertexCount()), 0);
  for (Index f = 0; f < mesh.faceCount(); ++f)
    if (refine[size_t(f)])
      for (Index c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; ++c) selected[size_t(mesh.faceVerts[c])] = 1;
  return selected;
}

// Faces with a selected corner: those a sparse step gives children. [O(corners)]
std::vector<uint8_t> facesTouching(const RefinedLevel& level, const std::vector<uint8_t>& selected) {
  const PolyMesh& mesh = level.mesh;
  std::vector<uint8_t> touched(size_t(mesh.faceCount()), 0);
  for (Index f = 0; f < mesh.faceCount(); ++f)
    for (Index c = mesh.faceStart[f]; c < mesh.faceStart[f + 1] && !touched[size_t(f)]; ++c)
      touched[size_t(f)] = selected[size_t(mesh.faceVerts[c])];
  return touched;
}

// Numbers the face points of face f (appended to `faces`, one per run of selected corners) and
// records each selected corner's in cornerFacePoint; returns the first. [O(face size)]
Index assignFacePoints(const PolyMesh& mesh, Index f, const std::vector<uint8_t>& selected, std::vector<Index>& faces,
                       std::vector<Index>& cornerFacePoint) {
  const Index begin = mesh.faceStart[f], end = mesh.faceStart[f + 1], size = end - begin;
  auto isSelected = [&](Index i) { return selected[size_t(mesh.faceVerts[begin + (i % size)])] != 0; };
  Index start = 0;  // a corner that starts a run (any corner when all are selected)
  while (start < size && !(isSelected(start) && !isSelected(start + size - 1))) ++start;
  if (start == size) start = 0;
  const Index first = Index(faces.size());
  for (Index i = start; i < start + size; ++i) {
    if (!isSelected(i)) continue;
    if (i == start || !isSelected(i - 1)) faces.push_back(f);
    cornerFacePoint[size_t(begin + (i % size))] = Index(faces.size()) - 1;
  }
  return first;
}

// C2PS's split corners (each quad at a pole's corner becomes two triangles): per corner of `level`;
// empty when there is no pole.
std::vector<uint8_t> splitPoleCorners(const RefinedLevel& level, const std::vector<PolarConfig>& poles) {
  std::vector<uint8_t> split;
  if (poles.empty()) return split;
  split.assign(level.mesh.faceVerts.size(), 0);
  for (const PolarConfig& pole : poles)
    for (Index k = level.topology.vertexFaceStart[pole.pole]; k < level.topology.vertexFaceStart[pole.pole + 1]; ++k)
      split[size_t(level.topology.vertexCorners[k])] = 1;
  return split;
}

// Faces a sparse step makes: one per selected corner, two where split. [O(corners)]
size_t sparseChildFaces(const RefinedLevel& level, const std::vector<uint8_t>& selected, const std::vector<uint8_t>& split) {
  size_t faces = 0;
  for (size_t c = 0; c < level.mesh.faceVerts.size(); ++c)
    if (selected[size_t(level.mesh.faceVerts[c])]) faces += split.empty() || !split[c] ? 1 : 2;
  return faces;
}

// A pole's configuration in the sparse child: deriveChildConfig of its links up to the first that
// is not wholly selected (I selected links give child links 1..2I, and 2I+1 from the radial edges
// and faces beyond when there is a link I+1), mapped to the child's numbering by `childOf`.
template <class ChildOf>
PolarConfig sparseChildConfig(const RefinedLevel& level, const PolarConfig& config, const std::vector<uint8_t>& selected,
                              ChildOf childOf) {
  if (!selected[size_t(config.pole)]) throw std::logic_error("adaptive refinement: a pole's fan was not refined");
  const int n = config.valence, K = config.linkCount;
  int whole = 0;  // links 1..whole are selected
  while (whole < K) {
    bool all = true;
    for (int j = 0; j < n && all; ++j) all = selected[size_t(config.links[size_t(whole) * n + j])];
    if (!all) break;
    ++whole;
  }
  PolarConfig parent = config;
  parent.linkCount = std::min(K, whole + 1);
  parent.regularLinks = std::min(parent.regularLinks, parent.linkCount);
  parent.links.resize(size_t(parent.linkCount) * n);
  PolarConfig child = deriveChildConfig(parent, level.mesh, level.topology);
  const int links = whole == K ? 2 * K : 2 * whole + 1;
  child.linkCount = links;
  child.regularLinks = std::min(child.regularLinks, links);
  child.links.resize(size_t(links) * child.valence);
  child.pole = childOf(child.pole);
  for (Index& v : child.links) {
    v = childOf(v);
    if (v < 0) throw std::logic_error("adaptive refinement: a pole's link was not refined");
  }
  if (whole < K || (config.oppositePole >= 0 && !selected[size_t(config.oppositePole)])) {
    child.outer = PolarConfig::Outer::Mesh;
    child.oppositePole = -1;
  } else if (config.oppositePole >= 0) {
    child.oppositePole = childOf(child.oppositePole);
  }
  return child;
}

// Precision (adaptive_refiner.h): the components of the faces refined (sharing corners), each
// anchored at its pole where it has one, else at its first vertex; every point a rule reads lies
// in one of them. Fills part.parentVertices, parentFrame, anchors; returns the component of each
// level m vertex (-1: not read). [O(level m)]
std::vector<int32_t> sparseComponents(const RefinedLevel& level, const std::vector<uint8_t>& touched, const std::vector<PolarConfig>& poles,
                                      SparsePart& part) {
  const PolyMesh& mesh = level.mesh;
  std::vector<Index> parent(size_t(mesh.vertexCount()), -1);
  auto find = [&](Index v) {
    while (parent[size_t(v)] != v) v = parent[size_t(v)] = parent[size_t(parent[size_t(v)])];
    return v;
  };
  for (Index f = 0; f < mesh.faceCount(); ++f)
    if (touched[size_t(f)])
      for (Index c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; ++c) parent[size_t(mesh.faceVerts[c])] = mesh.faceVerts[c];
  for (Index f = 0; f < mesh.faceCount(); ++f)
    if (touched[size_t(f)])
      for (Index c = mesh.faceStart[f] + 1; c < mesh.faceStart[f + 1]; ++c) {
        const Index a = find(mesh.faceVerts[mesh.faceStart[f]]), b = find(mesh.faceVerts[c]);
        if (a != b) parent[size_t(std::max(a, b))] = std::min(a, b);
      }
  std::vector<int32_t> component(size_t(mesh.vertexCount()), -1);
  for (Index v = 0; v < mesh.vertexCount(); ++v) {
    if (parent[size_t(v)] < 0) continue;
    const Index root = find(v);
    if (component[size_t(root)] < 0) {
      component[size_t(root)] = int32_t(part.anchors.size());
      part.anchors.push_back(v);
    }
    component[size_t(v)] = component[size_t(root)];
    part.parentVertices.push_back(v);
    part.parentFrame.push_back(uint32_t(component[size_t(v)]));
  }
  for (const PolarConfig& config : poles) part.anchors[size_t(component[size_t(config.pole)])] = config.pole;
  return component;
}

// Exactness and completeness of a sparse child's vertices (refineSparse). [O(corners around them)]
void markSparseChildren(const RefinedLevel& level, const SparsePart& part, const std::vector<uint8_t>& selected,
                        const std::vector<uint8_t>& exact, const std::vector<uint8_t>& complete, std::vector<uint8_t>& childExact,
                        std::vector<uint8_t>& childComplete) {
  const PolyMesh& mesh = level.mesh;
  const MeshTopology& topo = level.topology;
  const SparseChildVertices& children = part.children;
  childExact.assign(children.count(), 0);
  childComplete.assign(children.count(), 0);
  std::vector<uint8_t> faceOk(size_t(topo.faceCount), 0);
  size_t i = 0;
  for (Index f : children.faces) {
    bool ok = true, all = true;
    for (Index c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; ++c)
      ok = ok && exact[size_t(mesh.faceVerts[c])], all = all && selected[size_t(mesh.faceVerts[c])];
    faceOk[size_t(f)] = ok;
    childExact[i] = ok;
    childComplete[i++] = all;
  }
  for (Index e : children.edges) {
    const Index a = topo.edgeVerts[2 * e], b = topo.edgeVerts[2 * e + 1];
    const bool boundary = topo.edgeOnBoundary(e);
    const bool real = !boundary || complete[size_t(a)] || complete[size_t(b)];  // a boundary, not a cut
    const bool facesOk = faceOk[size_t(topo.edgeFaces[2 * e])] && (boundary || faceOk[size_t(topo.edgeFaces[2 * e + 1])]);
    childExact[i] = real && exact[size_t(a)] && exact[size_t(b)] && facesOk;
    childComplete[i++] = real && selected[size_t(a)] && selected[size_t(b)];
  }
  for (Index v : children.vertices) {
    bool ok = complete[size_t(v)];
    for (Index k = topo.vertexFaceStart[v]; k < topo.vertexFaceStart[v + 1] && ok; ++k) ok = faceOk[size_t(topo.vertexFaces[k])];
    childExact[i] = ok;
    childComplete[i++] = complete[size_t(v)];
  }
}

// The corner of level m's face across corner c's edge that starts the opposite half-edge (-1 on a
// boundary). [O(size of that face)]
Index parentTwin(const PolyMesh& mesh, const MeshTopology& topo, Index c) {
  const Index e = topo.cornerEdge[c];
  const Index g = topo.faceAcross(e, topo.cornerFace[c]);
  if (g < 0) return -1;
  for (Index d = mesh.faceStart[g]; d < mesh.faceStart[g + 1]; ++d)
    if (topo.cornerEdge[d] == e) return d;
  return -1;
}

// The half-edge twins of a sparse child's corners (buildTopologyFromTwins), from level m's.
// `childCorner[c]`: the first corner of parent corner c's child face (-1: none), a quad
// (V, E(c), F, E(prev)), or at a split corner two triangles (V, E(c), F) (V, F, E(prev)). Each child
// face's four half-edges (V->E(c), E(c)->F, F->E(prev), E(prev)->V) meet the child faces of the
// corners next to c in its face and across its two edges at the same vertex. [O(corners)]
std::vector<Index> sparseChildTwins(const RefinedLevel& level, const std::vector<Index>& childCorner, const std::vector<uint8_t>& split) {
  const PolyMesh& mesh = level.mesh;
  const MeshTopology& topo = level.topology;
  struct Slots {
    Index toEdge, toFace, fromFace, fromEdge;  // V->E(c), E(c)->F, F->E(prev), E(prev)->V
  };
  auto slots = [&](Index c) {
    const Index base = childCorner[size_t(c)];
    if (!split.empty() && split[size_t(c)]) return Slots{base, base + 1, base + 4, base + 5};
    return Slots{base, base + 1, base + 2, base + 3};
  };
  std::vector<Index> twin;
  size_t childCorners = 0;
  for (Index c = 0; c < Index(childCorner.size()); ++c)
    if (childCorner[size_t(c)] >= 0) childCorners += !split.empty() && split[size_t(c)] ? 6 : 4;
  twin.assign(childCorners, -1);
  for (Index f = 0; f < mesh.faceCount(); ++f) {
    const Index begin = mesh.faceStart[f], end = mesh.faceStart[f + 1];
    for (Index c = begin; c < end; ++c) {
      if (childCorner[size_t(c)] < 0) continue;
      const Index prev = c == begin ? end - 1 : c - 1, next = c + 1 == end ? begin : c + 1;
      const Slots mine = slots(c);
      if (const Index across = parentTwin(mesh, topo, c); across >= 0) {  // its face's corner at v_c follows it
        const Index g = topo.cornerFace[across];
        twin[size_t(mine.toEdge)] = slots(across + 1 == mesh.faceStart[g + 1] ? mesh.faceStart[g] : across + 1).fromEdge;
      }
      if (childCorner[size_t(next)] >= 0) twin[size_t(mine.toFace)] = slots(next).fromFace;
      if (childCorner[size_t(prev)] >= 0) twin[size_t(mine.fromFace)] = slots(prev).toFace;
      if (const Index across = parentTwin(mesh, topo, prev); across >= 0) twin[size_t(mine.fromEdge)] = slots(across).toEdge;
      if (!split.empty() && split[size_t(c)]) {  // the diagonal V - F
        twin[size_t(mine.toEdge + 2)] = mine.toEdge + 3;
        twin[size_t(mine.toEdge + 3)] = mine.toEdge + 2;
      }
    }
  }
  return twin;
}

// Levels of at least this many corners (8,192 quads) split a sparse step into two tasks on two threads (a
// thread's start, ~20-50 us here, against ~0.1 us a corner of work moved; docs/performance.md).
constexpr size_t kTwoTaskCorners = 32768;

// One sparse step of `level` (adaptive_refiner.h): per face, the child faces at its selected corners
// (Catmull-Clark's quads, or C2PS's two triangles at a split pole corner); the child vertices they
// use, numbered [face points | edge points | vertex points] by parent id; the child's tables,
// creases and the configurations of `poles`. Exactness and completeness: markSparseChildren, and
// C2PS's pole and links 1, 2 are exact when links 0..2 of the parent are (rules (1)-(3)), RTS/BPS's
// configurations always (their own radial grids). [O(level m)]
// `split` (splitPoleCorners of `poles` for C2PS's connectivity) and `childFaces` (sparseChildFaces)
// as the caller's budget check found them.
SparsePart refineSparse(const RefinedLevel& level, const std::vector<uint8_t>& selected, const std::vector<PolarConfig>& poles,
                        const std::vector<uint8_t>& split, size_t childFaces, Scheme scheme, const std::vector<uint8_t>& exact,
                        const std::vector<uint8_t>& complete, RefinedLevel& child, std::vector<uint8_t>& childExact,
                        std::vector<uint8_t>& childComplete) {
  const PolyMesh& mesh = level.mesh;
  const MeshTopology& topo = level.topology;
  const SchemeTraits& traits = schemeTraits(scheme);
  SparsePart part;
  const std::vector<uint8_t> touched = facesTouching(level, selected);
  std::vector<Index> faceChild(size_t(topo.faceCount), -1), edgeChild(size_t(topo.edgeCount), -1), vertexChild(size_t(topo.vertexCount), -1);
  SparseChildVertices& children = part.children;
  // A face whose selected corners form several runs gets a face point per run: its child faces
  // there meet only at the face point, which one point would make non-manifold (OpenSubdiv keeps
  // such a vertex non-manifold). The copies share the parent face, so their points are the same.
  std::vector<Index> cornerFacePoint(mesh.faceVerts.size(), -1);
  children.faces.reserve(size_t(std::count(touched.begin(), touched.end(), uint8_t(1))));
  for (Index f = 0; f < topo.faceCount; ++f)
    if (touched[size_t(f)]) faceChild[size_t(f)] = assignFacePoints(mesh, f, selected, children.faces, cornerFacePoint);
  const Index faceCount = Index(children.faces.size());
  auto edgeRefined = [&](Index e) { return selected[size_t(topo.edgeVerts[2 * e])] || selected[size_t(topo.edgeVerts[2 * e + 1])]; };
  Index edgeTotal = 0;
  for (Index e = 0; e < topo.edgeCount; ++e) edgeTotal += edgeRefined(e);
  children.edges.reserve(size_t(edgeTotal));
  for (Index e = 0; e < topo.edgeCount; ++e)
    if (edgeRefined(e)) edgeChild[size_t(e)] = faceCount + Index(children.edges.size()), children.edges.push_back(e);
  const Index edgeEnd = faceCount + Index(children.edges.size());
  children.vertices.reserve(size_t(std::count(selected.begin(), selected.end(), uint8_t(1))));
  for (Index v = 0; v < topo.vertexCount; ++v)
    if (selected[size_t(v)]) vertexChild[size_t(v)] = edgeEnd + Index(children.vertices.size()), children.vertices.push_back(v);

  // The child's faces and tables on this thread; its vertices' exactness and frames, which read
  // only level m and the numbering, on a second one where the level is large enough to pay for
  // it (the same results either way: each task writes its own tables).
  auto facesAndTables = [&] {
    // Child faces in parent face and corner order, shaped as refine_topology.h's.
    child.mesh.faceStart.reserve(childFaces + 1);
    child.mesh.faceVerts.reserve(childFaces * 4);
    child.faceParent.reserve(childFaces);
    std::vector<Index> childCorner(mesh.faceVerts.size(), -1);  // per parent corner: its child face's first corner
    for (size_t i = 0; i < children.faces.size(); ++i) {
      const Index f = children.faces[i];
      if (i > 0 && children.faces[i - 1] == f) continue;  // a second face point of the same face
      const Index begin = mesh.faceStart[f], end = mesh.faceStart[f + 1];
      for (Index c = begin; c < end; ++c) {
        if (!selected[size_t(mesh.faceVerts[c])]) continue;
        const Index prev = c == begin ? end - 1 : c - 1;
        const Index vertex = vertexChild[size_t(mesh.faceVerts[c])], face = cornerFacePoint[size_t(c)];
        const Index next = edgeChild[size_t(topo.cornerEdge[c])], before = edgeChild[size_t(topo.cornerEdge[prev])];
        childCorner[size_t(c)] = Index(child.mesh.faceVerts.size());
        if (!split.empty() && split[size_t(c)]) {
          child.mesh.addFace({vertex, next, face});
          child.mesh.addFace({vertex, face, before});
          child.faceParent.push_back(f);
        } else {
          child.mesh.addFace({vertex, next, face, before});
        }
        child.faceParent.push_back(f);
      }
    }
    child.mesh.points.assign(children.count(), Point(0.0));
    // Tables are a function of the faces: a child with its parent's faces (a fixed point,
    // AdaptiveRefinement::repeatsParentLevel) takes the parent's.
    if (child.mesh.vertexCount() == mesh.vertexCount() && child.mesh.faceStart == mesh.faceStart && child.mesh.faceVerts == mesh.faceVerts)
      child.topology = topo;
    else
      child.topology = buildTopologyFromTwins(child.mesh, sparseChildTwins(level, childCorner, split));
    if (!level.sharpness.empty()) child.sharpness = sparseChildSharpness(topo, level.sharpness, children, child.topology);
  };
  auto flagsAndFrames = [&] {
    markSparseChildren(level, part, selected, exact, complete, childExact, childComplete);
    // Frames: each child vertex in its parent element's component.
    const std::vector<int32_t> component = sparseComponents(level, touched, poles, part);
    child.vertexFrame.resize(children.count());
    for (size_t i = 0; i < children.faces.size(); ++i)
      child.vertexFrame[i] = uint32_t(component[size_t(mesh.faceVerts[mesh.faceStart[children.faces[i]]])]);
    for (size_t i = 0; i < children.edges.size(); ++i)
      child.vertexFrame[size_t(faceCount) + i] = uint32_t(component[size_t(topo.edgeVerts[2 * children.edges[i]])]);
    for (size_t i = 0; i < children.vertices.size(); ++i)
      child.vertexFrame[size_t(edgeEnd) + i] = uint32_t(component[size_t(children.vertices[i])]);
  };
  runBoth(threadLimit() > 1 && mesh.faceVerts.size() >= kTwoTaskCorners, facesAndTables, flagsAndFrames);
  auto childOf = [&](Index full) {  // catmull_clark.h's full child numbering -> the sparse child's
    if (full < topo.faceCount) return faceChild[size_t(full)];
    if (full < topo.faceCount + topo.edgeCount) return edgeChild[size_t(full - topo.faceCount)];
    return vertexChild[size_t(full - topo.faceCount - topo.edgeCount)];
  };
  for (const PolarConfig& config : poles) child.poles.push_back(sparseChildConfig(level, config, selected, childOf));
  for (size_t k = 0; k < poles.size(); ++k) {
    const PolarConfig& parent = poles[k];
    const PolarConfig& config = child.poles[k];
    if (!traits.keepsValence) {  // C2PS: rules (1)-(3) read links 0..2 of the parent, write the child's pole, links 1, 2
      bool gridOk = exact[size_t(parent.pole)] && parent.linkCount >= 2;
      for (size_t i = 0; i < size_t(std::min(2, parent.linkCount)) * parent.valence; ++i) gridOk = gridOk && exact[size_t(parent.links[i])];
      childExact[size_t(config.pole)] = gridOk;
      for (size_t i = 0; i < size_t(std::min(2, config.linkCount)) * config.valence; ++i) childExact[size_t(config.links[i])] = gridOk;
    } else {  // RTS/BPS outside caps and globes: the pole's own radial grid owns the configuration's links
      childExact[size_t(config.pole)] = 1;
      for (Index v : config.links) childExact[size_t(v)] = 1;
    }
  }
  return part;
}

}  // namespace

// [SECTION] AdaptiveRefinement

struct AdaptiveRefinement::LevelState {
  bool tail = false;                   // the poles' regions are refined radially apart (from here on)
  std::vector<uint8_t> complete;       // per vertex: its faces at this level are the uniform level's
  std::vector<PolarGrid> radialGrids;  // RTS/BPS in mixed meshes: each pole's own radial grid
  std::vector<Point> gridOrigins;      // ... relative to these (its pole's frame at this level)
};

AdaptiveRefinement::AdaptiveRefinement(const PolyMesh& input, const RefineOptions& options, const std::string& sourceName,
                                       size_t maxFaces)
    : options_(options), sourceName_(sourceName) {
  if (options.levels < 0) throw InputError(sourceName, 0, "negative subdivision level " + std::to_string(options.levels));
  // Non-manifold input: refined as its manifold split with OpenSubdiv's sharpening (manifold_split.h).
  ManifoldSplit split;
  MeshTopology baseTopology;
  const PolyMesh& base = refinableMesh(input, split, baseTopology, sourceName);
  const std::vector<PolarConfig> configs = findPolarConfigs(base, baseTopology);
  start(input, base, std::move(baseTopology), std::move(split.sourceVertex), configs, maxFaces);
}

AdaptiveRefinement::AdaptiveRefinement(const PolyMesh& input, const PreparedBase& prepared, const RefineOptions& options,
                                       const std::string& sourceName, size_t maxFaces)
    : options_(options), sourceName_(sourceName) {
  if (options.levels < 0) throw InputError(sourceName, 0, "negative subdivision level " + std::to_string(options.levels));
  start(input, prepared.mesh, prepared.topology, prepared.sourceVertex, prepared.configs, maxFaces);
}

void AdaptiveRefinement::start(const PolyMesh& input, const PolyMesh& base, MeshTopology topology,
                               std::vector<Index> sourceVertex, const std::vector<PolarConfig>& configs, size_t maxFaces) {
  const Scheme scheme = options_.scheme;
  inputVertices_ = size_t(input.vertexCount());
  sourceVertex_ = std::move(sourceVertex);
  RefinedLevel level0;
  level0.mesh = base;
  level0.topology = std::move(topology);
  for (const PolarConfig& config : configs)
    if (schemeRefinesPole(scheme, config)) level0.poles.push_back(config);
  // Creases and corners: Catmull-Clark's rules wherever Catmull-Clark's connectivity refines (every
  // scheme but RTS/BPS's radial refinement of caps and globes; poles they touch are left to
  // Catmull-Clark by findPolarConfigs), as the uniform refiner.
  radial_ = schemeTraits(scheme).keepsValence && !findRadialRegions(level0).empty();
  if (!base.tags.empty() && !radial_) level0.sharpness = baseSharpness(base, level0.topology);
  // Holes give no patches: not needed (their points still support the faces around them).
  level0.faceHole = baseHoles(base, level0.topology);
  needed_.push_back(std::vector<uint8_t>(base.faceCount(), 1));
  for (size_t f = 0; f < level0.faceHole.size(); ++f) needed_.back()[f] = !level0.faceHole[f];
  exact_.push_back(std::vector<uint8_t>(base.vertexCount(), 1));
  states_.emplace_back();
  states_.back().complete.assign(base.vertexCount(), 1);
  totalFaces_ = size_t(base.faceCount());
  totalFacesAt_.push_back(totalFaces_);
  levels_.push_back(std::move(level0));
  radialRefined_.push_back(std::vector<uint8_t>(levels_.back().mesh.faceCount(), 0));
  repeats_.push_back(0);
  const int levels = options_.levels;
  options_.levels = 0;
  addLevels(levels, maxFaces);
  updatePositions(input.points);
}

AdaptiveRefinement::~AdaptiveRefinement() = default;
AdaptiveRefinement::AdaptiveRefinement(AdaptiveRefinement&&) noexcept = default;
AdaptiveRefinement& AdaptiveRefinement::operator=(AdaptiveRefinement&&) noexcept = default;

void AdaptiveRefinement::extend(int levels, size_t maxFaces) {
  if (levels <= 0) return;
  const size_t firstStep = steps_.size();
  try {
    addLevels(levels, maxFaces);
  } catch (...) {
    truncate(int(firstStep));  // the levels made before the refusal go: unchanged
    throw;
  }
  computePoints(firstStep);
}

void AdaptiveRefinement::truncate(int levels) {
  if (levels < 0 || levels >= levelCount()) return;
  const size_t count = size_t(levels) + 1;
  levels_.resize(count);
  needed_.resize(count);
  exact_.resize(count);
  states_.resize(count);
  totalFacesAt_.resize(count);
  repeats_.resize(count);
  radialRefined_.resize(count);
  radialRefined_.back().assign(levels_.back().mesh.faceCount(), 0);  // the finest level refines nothing
  steps_.resize(size_t(levels));
  totalFaces_ = totalFacesAt_.back();
  options_.levels = levels;
}

// Topology of `count` more levels (their points: computePoints). Level m+1 from level m: the
// needed faces that are not regular, refined sparsely (their corners' children and nothing else),
// or radially with their support rings copied out (adaptive_refiner.h).
void AdaptiveRefinement::addLevels(int count, size_t maxFaces) {
  const Scheme scheme = options_.scheme;
  const std::string& sourceName = sourceName_;
  const bool mixedRadialPoles = schemeTraits(scheme).keepsValence && !radial_;
  const int target = options_.levels + count;
  for (int m = options_.levels; m < target; ++m) {
    if (repeats_[size_t(m)]) {
      copyFixedPointStep(m, target, maxFaces);
      continue;
    }
    const RefinedLevel& level = levels_[m];
    const LevelState& state = states_[m];
    const std::vector<uint8_t> refine = facesToRefine(level, needed_[m]);
    Step step;
    // RTS/BPS outside caps and globes: from kRadialTailLevel on, each pole's region is refined
    // radially with its columns kept (the tail), once it is apart from the other faces refined.
    std::vector<uint8_t> sparseFaces = refine, polar(refine.size(), 0);
    std::vector<uint8_t> selected;
    bool tailStep = false;
    if (radial_) {
      growSelection(level, sparseFaces, kRadialSupportRings);
    } else {
      if (mixedRadialPoles && !level.poles.empty() && (state.tail || m >= kRadialTailLevel)) {
        const std::vector<uint8_t> rows = poleRows(level);
        for (size_t f = 0; f < refine.size(); ++f)
          if (refine[f] && rows[f]) polar[f] = 1, sparseFaces[f] = 0;
        growSelection(level, polar, kRadialSupportRings);
        selected = selectVertices(level, sparseFaces);
        tailStep = !selectionsTouch(level, polar, facesTouching(level, selected));
        if (!tailStep && state.tail) throw std::logic_error("adaptive refinement: a pole's tail meets the other refined faces");
        if (!tailStep) std::fill(polar.begin(), polar.end(), 0), sparseFaces = refine;
      }
      if (!tailStep) selected = selectVertices(level, sparseFaces);
    }

    // The budget, before anything of the level is made.
    size_t copiedFaces = 0, childFaces = 0;
    for (size_t f = 0; f < refine.size(); ++f) {
      copiedFaces += (radial_ && sparseFaces[f]) || polar[f];
      childFaces += (radial_ && sparseFaces[f]) || polar[f] ? 2 : 0;
    }
    const std::vector<PolarConfig> noPoles, &sparsePoles = tailStep ? noPoles : level.poles;
    const std::vector<uint8_t> split = !radial_ && schemeTraits(scheme).polar() ? splitPoleCorners(level, sparsePoles) : std::vector<uint8_t>{};
    const size_t sparseChildren = radial_ ? 0 : sparseChildFaces(level, selected, split);
    childFaces += sparseChildren;
    checkBudget(copiedFaces + childFaces, target, m, maxFaces);

    RefinedLevel child;
    LevelState childState;
    childState.tail = tailStep;
    std::vector<uint8_t> childExact;
    if (radial_) {
      step.radial = copyOut(level, sparseFaces, level.poles, true, exact_[m], state.complete, sourceName);
      refineRadialPart(step.radial, sourceName, child, childExact, childState.complete);
      step.frameAnchors = step.radial.anchors;
      radialRefined_[m] = sparseFaces;
    } else {
      step.sparse = refineSparse(level, selected, sparsePoles, split, sparseChildren, scheme, exact_[m], state.complete, child,
                                 childExact, childState.complete);
      step.frameAnchors = step.sparse.anchors;
      radialRefined_[m] = polar;
    }
    if (tailStep) appendTail(level, polar, m, step, child, childExact, childState.complete);
    inheritHoles(level, child);
    std::vector<uint8_t> childNeeded(child.mesh.faceCount());
    for (Index f = 0; f < child.mesh.faceCount(); ++f) childNeeded[f] = refine[child.faceParent[f]];
    totalFaces_ += copiedFaces + size_t(child.mesh.faceCount());
    totalFacesAt_.push_back(totalFaces_);
    radialRefined_.push_back(std::vector<uint8_t>(child.mesh.faceCount(), 0));
    levels_.push_back(std::move(child));
    needed_.push_back(std::move(childNeeded));
    exact_.push_back(std::move(childExact));
    states_.push_back(std::move(childState));
    steps_.push_back(std::move(step));
    repeats_.push_back(options_.copyFixedPointLevels && stepInputsEqualParent(m + 1));
    options_.levels = m + 1;
  }
}

void AdaptiveRefinement::checkBudget(size_t newFaces, int target, int m, size_t maxFaces) const {
  if (totalFaces_ + newFaces > maxFaces)
    throw InputError(sourceName_, 0,
                     "level " + std::to_string(target) + " would need more than " + std::to_string(maxFaces) +
                         " faces (feature-adaptive, all levels together); level " + std::to_string(m) + " is the deepest that fits");
}

// Fixed points (docs/performance.md): around isolated extraordinary vertices and features the
// sparse step soon makes a level that is its parent again, face for face and flag for flag (the
// refined neighbourhood keeps its size and shape, only its points shrink). Step m reads level m's
// faces and tables (a function of the faces), sharpness, holes, needed faces, exact and complete
// vertices, and poles and radial state (none here); where all equal level m-1's, step m is step
// m-1 and level m+1 level m, index for index.
bool AdaptiveRefinement::stepInputsEqualParent(int m) const {
  if (m < 1 || radial_) return false;
  const RefinedLevel &level = levels_[size_t(m)], &parent = levels_[size_t(m) - 1];
  const LevelState &state = states_[size_t(m)], &parentState = states_[size_t(m) - 1];
  auto sameSharpness = [](const CreaseSharpness& a, const CreaseSharpness& b) {
    return a.edge == b.edge && a.vertex == b.vertex && a.chaikin == b.chaikin && a.smoothTriangles == b.smoothTriangles;
  };
  return level.poles.empty() && parent.poles.empty() && !state.tail && !parentState.tail && state.radialGrids.empty() &&
         parentState.radialGrids.empty() && level.mesh.vertexCount() == parent.mesh.vertexCount() &&
         level.mesh.faceStart == parent.mesh.faceStart && level.mesh.faceVerts == parent.mesh.faceVerts &&
         level.faceHole == parent.faceHole && sameSharpness(level.sharpness, parent.sharpness) &&
         needed_[size_t(m)] == needed_[size_t(m) - 1] && exact_[size_t(m)] == exact_[size_t(m) - 1] &&
         state.complete == parentState.complete;
}

void AdaptiveRefinement::copyFixedPointStep(int m, int target, size_t maxFaces) {
  const size_t faces = size_t(levels_[size_t(m)].mesh.faceCount());
  checkBudget(faces, target, m, maxFaces);
  RefinedLevel child = levels_[size_t(m)];  // points too: computePoints writes them
  Step step = steps_[size_t(m) - 1];
  LevelState childState = states_[size_t(m)];
  std::vector<uint8_t> childNeeded = needed_[size_t(m)], childExact = exact_[size_t(m)];
  radialRefined_[size_t(m)] = radialRefined_[size_t(m) - 1];
  radialRefined_.push_back(std::vector<uint8_t>(faces, 0));
  totalFaces_ += faces;
  totalFacesAt_.push_back(totalFaces_);
  levels_.push_back(std::move(child));
  needed_.push_back(std::move(childNeeded));
  exact_.push_back(std::move(childExact));
  states_.push_back(std::move(childState));
  steps_.push_back(std::move(step));
  repeats_.push_back(1);
  options_.levels = m + 1;
}

// A tail step's poles (RTS/BPS outside caps and globes): their regions (`polar`) copied out, refined
// radially and appended to the child after the sparse part, tables rebuilt over both.
void AdaptiveRefinement::appendTail(const RefinedLevel& level, const std::vector<uint8_t>& polar, int m, Step& step, RefinedLevel& child,
                                    std::vector<uint8_t>& childExact, std::vector<uint8_t>& childComplete) const {
  CopiedPart polarPart = copyOut(level, polar, level.poles, true, exact_[m], states_[m].complete, sourceName_);
  RefinedLevel polarChild;
  std::vector<uint8_t> polarExact, polarComplete;
  refineRadialPart(polarPart, sourceName_, polarChild, polarExact, polarComplete);
  // The tail's points come from the poles' own (exact) radial grids: every row is exact.
  std::fill(polarExact.begin(), polarExact.end(), 1);
  appendLevel(child, polarChild, uint32_t(step.sparse.anchors.size()));
  step.frameAnchors.insert(step.frameAnchors.end(), polarPart.anchors.begin(), polarPart.anchors.end());
  const MeshTopology sparseTopology = std::move(child.topology);
  child.topology = buildTopology(child.mesh, sourceName_);
  // The sparse part's creases on the joined tables (its vertex ids are kept; the tail is smooth).
  if (!child.sharpness.empty()) {
    CreaseSharpness joined;
    joined.chaikin = child.sharpness.chaikin;
    joined.edge.assign(size_t(child.topology.edgeCount), 0.0f);
    joined.vertex.assign(size_t(child.topology.vertexCount), 0.0f);
    std::copy(child.sharpness.vertex.begin(), child.sharpness.vertex.end(), joined.vertex.begin());
    for (Index e = 0; e < sparseTopology.edgeCount; ++e)
      if (child.sharpness.edge[size_t(e)] > 0.0f)
        joined.edge[size_t(child.topology.edgeBetween(sparseTopology.edgeVerts[2 * e], sparseTopology.edgeVerts[2 * e + 1]))] =
            child.sharpness.edge[size_t(e)];
    for (Index e = 0; e < child.topology.edgeCount; ++e)
      if (child.topology.edgeOnBoundary(e)) joined.edge[size_t(e)] = float(kInfiniteSharpness);
    child.sharpness = std::move(joined);
  }
  childExact.insert(childExact.end(), polarExact.begin(), polarExact.end());
  childComplete.insert(childComplete.end(), polarComplete.begin(), polarComplete.end());
}

void AdaptiveRefinement::updatePositions(const std::vector<Point>& basePoints) {
  if (basePoints.size() != inputVertices_)
    throw std::invalid_argument("updatePositions: " + std::to_string(basePoints.size()) + " points for a mesh of " +
                                std::to_string(inputVertices_));
  if (sourceVertex_.empty()) {
    levels_[0].mesh.points = basePoints;
  } else {
    for (size_t v = 0; v < sourceVertex_.size(); ++v) levels_[0].mesh.points[v] = basePoints[size_t(sourceVertex_[v])];
  }
  computePoints(0);
}

// Points of levels firstStep+1.. from level firstStep's (and its state's radial grids).
void AdaptiveRefinement::computePoints(size_t firstStep) {
  const Scheme scheme = options_.scheme;
  const SchemeTraits& rules = schemeTraits(scheme);
  const bool radialPoles = rules.keepsValence && !radial_;
  if (firstStep == 0) {
    std::vector<PolarGrid>& grids = states_[0].radialGrids;
    grids.clear();
    if (radialPoles)
      for (const PolarConfig& config : levels_[0].poles) grids.push_back(gatherGrid(levels_[0].mesh.points, config, config.linkCount));
    states_[0].gridOrigins.assign(grids.size(), Point(0.0));
    fillPoleData(levels_[0], scheme, radialPoles ? &grids : nullptr);
  }

  std::vector<Point> rows, childRows, link1, link2, refined, scratch, shifted, facePoints;
  for (size_t m = firstStep; m < steps_.size(); ++m) {
    Step& step = steps_[m];
    const RefinedLevel& level = levels_[m];
    RefinedLevel& child = levels_[m + 1];
    std::vector<PolarGrid>& radialGrids = states_[m + 1].radialGrids;
    radialGrids = states_[m].radialGrids;
    states_[m + 1].gridOrigins = states_[m].gridOrigins;
    const bool uniformStep = options_.uniformFirstStep && m == 0;
    // Precision (adaptive_refiner.h): the child's frames sit at their anchors; each component's
    // points are read relative to its frame. Within a component every parent point shares one
    // frame, so the shift is one vector for all and the differences the rules take stay exact to
    // the component's own size.
    child.frameOrigins.resize(step.frameAnchors.size());
    for (size_t c = 0; c < step.frameAnchors.size(); ++c) child.frameOrigins[c] = level.absolutePoint(step.frameAnchors[c]);
    std::vector<Point>& points = child.mesh.points;
    if (radial_) {
      CopiedPart& part = step.radial;
      std::vector<Point>& subPoints = part.sub.mesh.points;
      for (size_t v = 0; v < part.subToLevel.size(); ++v) {
        const Index w = part.subToLevel[v];
        subPoints[v] = level.mesh.points[w] + (level.origin(w) - child.frameOrigins[part.component[v]]);
      }
      for (size_t r = 0; r < part.regions.size(); ++r) {
        const RadialRegion& region = part.regions[r];
        rows.clear();
        for (Index id : region.vertexIds) rows.push_back(subPoints[id]);
        refineRegionRadially(rows, region, rules, uniformStep, childRows);
        std::copy(childRows.begin(), childRows.end(), points.begin() + part.childRegions[r].vertexBase);
      }
      fillPoleData(child, scheme, nullptr);
      continue;
    }
    const SparsePart& part = step.sparse;
    shifted.resize(level.mesh.points.size());
    for (size_t i = 0; i < part.parentVertices.size(); ++i) {
      const Index w = part.parentVertices[i];
      shifted[size_t(w)] = level.mesh.points[size_t(w)] + (level.origin(w) - child.frameOrigins[part.parentFrame[i]]);
    }
    if (part.children.count() > 0)
      computeSparseCatmullClarkPoints(level.topology, level.mesh, shifted.data(), part.children, level.sharpness, facePoints, points.data());
    for (size_t k = 0; k < child.poles.size(); ++k) {
      const PolarConfig& config = child.poles[k];
      if (!rules.keepsValence) {  // C2PS: rules (1)-(3)
        const PolarGrid grid = gatherGrid(shifted, level.poles[k], 2);
        const int n2 = config.valence;
        link1.resize(n2);
        link2.resize(n2);
        rules.refineLink1(grid, link1.data());
        rules.refineLink2(grid, link2.data(), uniformStep);
        points[config.pole] = rules.refinePole(grid);
        for (int j = 0; j < n2; ++j) {
          points[config.links[j]] = link1[j];
          if (config.linkCount >= 2) points[config.links[size_t(n2) + j]] = link2[j];
        }
      } else if (radialPoles) {
        PolarGrid& grid = radialGrids[k];
        // The grid moves to its pole's frame in the child (the same rigid shift for all its points).
        Point& gridOrigin = states_[m + 1].gridOrigins[k];
        const Point shift = gridOrigin - child.origin(config.pole);
        grid.pole += shift;
        for (Point& q : grid.ring) q += shift;
        gridOrigin = child.origin(config.pole);
        grid = rules.refineGrid(grid, uniformStep);
        // Links beyond the ones this and the next level own are never read: keep the grid small.
        const int keep = std::min(grid.links, config.linkCount + 2);
        grid.links = keep;
        grid.ring.resize(size_t(keep) * grid.n);
        points[config.pole] = grid.pole;
        // The configuration's columns: the grid's refined periodically (the valence doubled on
        // C2PS's connectivity each level until the tail, which keeps it).
        int times = 0;
        while ((grid.n << times) < config.valence) ++times;
        const int owned = std::min(grid.links - 1, config.linkCount);
        for (int i = 1; i <= owned; ++i) {
          refinePeriodically(&grid.q(i, 0), grid.n, times, refined, scratch);
          for (int j = 0; j < config.valence; ++j) points[config.links[size_t(i - 1) * config.valence + j]] = refined[j];
        }
      }
    }
    fillPoleData(child, scheme, radialPoles ? &radialGrids : nullptr);
  }
}

namespace {
// estimateAdaptiveFaceCounts from its refinement of level 0.
std::vector<size_t> measureFaceCounts(AdaptiveRefinement& refinement, const RefineOptions& options, size_t maxFaces, int measured) {
  // Measured level by level; a level over maxFaces is refused before it is made (so the estimate
  // never holds more than maxFaces faces), and it and every deeper level are reported as over.
  bool over = false;
  const int wanted = std::min(options.levels, std::max(measured, 1));
  while (refinement.levelCount() - 1 < wanted && !over) {
    try {
      refinement.extend(1, maxFaces);
    } catch (const InputError&) {
      over = true;
    }
  }
  // Each level comes with the copied-out part of its parent that made it (radial steps): count them
  // in the proportion measured.
  double levelFaces = 0.0;
  for (int m = 0; m < refinement.levelCount(); ++m) levelFaces += double(refinement.level(m).mesh.faceCount());
  const double withParts = double(refinement.totalFaces()) / levelFaces;
  std::vector<size_t> totals;
  double total = 0.0;
  for (int m = 0; m < refinement.levelCount(); ++m) {
    total += double(refinement.level(m).mesh.faceCount()) * (m == 0 ? 1.0 : withParts);
    totals.push_back(size_t(total));
  }
  if (over) {
    totals.resize(size_t(options.levels) + 1, maxFaces + 1);
    return totals;
  }
  // Beyond: faces(m) = a + b 2^m through the last two measured levels. A pole of C2PS (and RTS/BPS
  // outside caps and globes, on C2PS's connectivity) doubles its valence, so its rings double a
  // level (b); Catmull-Clark's extraordinary vertices and radial rings add the same faces each
  // level (a).
  const int last = refinement.levelCount() - 1;
  const double now = double(refinement.level(last).mesh.faceCount());
  const double before = last > 0 ? double(refinement.level(last - 1).mesh.faceCount()) : now / 4.0;
  const double doubling = std::max(0.0, (now - before) / std::ldexp(1.0, std::max(last - 1, 0)));
  const double constant = std::max(0.0, now - doubling * std::ldexp(1.0, last));
  double sum = double(total);
  for (int m = last + 1; m <= options.levels; ++m) {
    const double faces = constant + doubling * std::ldexp(1.0, std::min(m, 1000));
    sum = std::min(sum + withParts * faces, 1e18);
    totals.push_back(size_t(sum));
  }
  return totals;
}
}  // namespace

std::vector<size_t> estimateAdaptiveFaceCounts(const PolyMesh& base, const RefineOptions& options, size_t maxFaces, int measured) {
  RefineOptions first = options;
  first.levels = 0;
  AdaptiveRefinement refinement(base, first, "<estimate>", maxFaces);
  return measureFaceCounts(refinement, options, maxFaces, measured);
}

std::vector<size_t> estimateAdaptiveFaceCounts(const PolyMesh& input, const PreparedBase& prepared, const RefineOptions& options,
                                               size_t maxFaces, int measured) {
  RefineOptions first = options;
  first.levels = 0;
  AdaptiveRefinement refinement(input, prepared, first, "<estimate>", maxFaces);
  return measureFaceCounts(refinement, options, maxFaces, measured);
}

}  // namespace polarview
