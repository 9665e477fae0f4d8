// Refiner: Catmull-Clark everywhere, the chosen polar scheme at polar configurations.
// [SECTION] helpers: grids and lookups
// [SECTION] generic levels: Catmull-Clark connectivity (+ C2PS's split pole quads)
// [SECTION] radial levels: RTS/BPS on meshes made only of polar regions
// [SECTION] Refinement
#include "core/subdiv/refiner.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "core/mesh/input_error.h"
#include "core/mesh/manifold_split.h"
#include "core/subdiv/parallel_for.h"
#include "core/subdiv/catmull_clark.h"
#include "core/subdiv/polar_rules.h"
#include "core/subdiv/refine_steps.h"
#include "core/subdiv/refine_topology.h"
#include "core/subdiv/table_pool.h"

namespace polarview {

// [SECTION] helpers: grids and lookups


// Copies a configuration's points (pole and links 1..linkCount) into a PolarGrid.
PolarGrid gatherGrid(const std::vector<Point>& points, const PolarConfig& config, int linkCount) {
  PolarGrid grid(config.valence, linkCount);
  grid.pole = points[config.pole];
  for (size_t k = 0; k < grid.ring.size(); ++k) grid.ring[k] = points[config.links[k]];
  return grid;
}

namespace {

// The face on edge (a,b) that also holds vertex c (-1 if none). [O(valence + face size)]
Index faceWith(const PolyMesh& mesh, const MeshTopology& topo, Index a, Index b, Index c) {
  Index e = topo.edgeBetween(a, b);
  if (e < 0) return -1;
  for (int s = 0; s < 2; ++s) {
    Index f = topo.edgeFaces[2 * e + s];
    if (f < 0) continue;
    const Index* loop = mesh.face(f);
    if (std::find(loop, loop + mesh.faceSize(f), c) != loop + mesh.faceSize(f)) return f;
  }
  return -1;
}

// The face on edge e that also holds `toward`, a neighbour of e's end `from` in that face, and the
// face's edge joining the two. False if neither face of e qualifies. [O(face size)]
bool faceAndEdgeToward(const PolyMesh& mesh, const MeshTopology& topo, Index e, Index from, Index toward, Index& face,
                       Index& edge) {
  if (e < 0) return false;
  for (int side = 0; side < 2; ++side) {
    const Index f = topo.edgeFaces[2 * e + side];
    if (f < 0) continue;
    const Index begin = mesh.faceStart[f], end = mesh.faceStart[f + 1];
    for (Index c = begin; c < end; ++c) {
      if (mesh.faceVerts[c] != from) continue;
      const Index next = c + 1 == end ? begin : c + 1, prev = c == begin ? end - 1 : c - 1;
      if (mesh.faceVerts[next] == toward) edge = topo.cornerEdge[c];
      else if (mesh.faceVerts[prev] == toward) edge = topo.cornerEdge[prev];
      else break;
      face = f;
      return true;
    }
  }
  return false;
}

}  // namespace

// Repeats periodic refinement (5) `times` times: n points -> n 2^times points.
void refinePeriodically(const Point* link, int n, int times, std::vector<Point>& out, std::vector<Point>& scratch) {
  out.assign(link, link + n);
  for (int t = 0; t < times; ++t) {
    scratch.resize(out.size() * 2);
    refinePeriodicLink(out.data(), int(out.size()), scratch.data());
    out.swap(scratch);
  }
}

// [SECTION] generic levels: Catmull-Clark connectivity (+ C2PS's split pole quads)

// The configuration one Catmull-Clark/C2PS step makes of `parent` (column j -> 2j). Link 2i holds
// the vertex points of link i (even columns) and the edge points of its edges (odd); link 2i+1
// the edge points of the radial edges i->i+1 (even) and the face points between (odd).
PolarConfig deriveChildConfig(const PolarConfig& parent, const PolyMesh& mesh, const MeshTopology& topo) {
  const int n = parent.valence, K = parent.linkCount;
  auto q = [&](int i, int j) { return i == 0 ? parent.pole : parent.links[size_t(i - 1) * n + ((j % n) + n) % n]; };
  PolarConfig child;
  child.pole = ccVertexPoint(topo, parent.pole);
  child.valence = 2 * n;
  child.linkCount = 2 * K;
  child.links.resize(size_t(2 * K) * 2 * n);
  // Rows are independent: large configurations (a globe's pole spans the mesh) use all threads.
  parallelRanges(K + 1, threadsFor(size_t(K + 1) * n), [&](Index rowBegin, Index rowEnd) {
    for (int i = rowBegin; i < rowEnd; ++i) {
      for (int j = 0; j < n; ++j) {
        // The edge along link max(i, 1) from column j; the face beyond it toward the pole side's
        // neighbour holds the radial edge too, so one edge search serves all three lookups.
        const Index along = topo.edgeBetween(q(std::max(i, 1), j), q(std::max(i, 1), j + 1));
        if (i >= 1) {  // link 2i
          Index* row = &child.links[size_t(2 * i - 1) * 2 * n];
          row[2 * j] = ccVertexPoint(topo, q(i, j));
          row[2 * j + 1] = ccEdgePoint(topo, along);
        }
        if (i < K) {  // link 2i+1
          Index* row = &child.links[size_t(2 * i) * 2 * n];
          const Index from = q(std::max(i, 1), j), toward = i == 0 ? parent.pole : q(i + 1, j);
          Index face = -1, radial = -1;
          if (!faceAndEdgeToward(mesh, topo, along, from, toward, face, radial)) {  // not a valid configuration
            radial = topo.edgeBetween(q(i, j), q(i + 1, j));
            face = -1;
          }
          row[2 * j] = ccEdgePoint(topo, radial);
          row[2 * j + 1] = ccFacePoint(topo, face);
        }
      }
    }
  });
  child.regularLinks = parent.regularLinks == K ? 2 * K : 2 * parent.regularLinks + 1;
  child.outer = parent.outer;
  child.oppositePole = parent.oppositePole >= 0 ? ccVertexPoint(topo, parent.oppositePole) : -1;
  child.refinable = true;
  return child;
}

namespace {

// The parent corners whose quads C2PS splits (those at its poles); empty when none.
std::vector<uint8_t> poleCornerSplits(const RefinedLevel& parent, bool splitPoleQuads) {
  std::vector<uint8_t> split;
  if (splitPoleQuads && !parent.poles.empty()) {
    reserveFromPool(split, parent.mesh.faceVerts.size());
    split.assign(parent.mesh.faceVerts.size(), 0);
    for (const PolarConfig& pole : parent.poles)
      for (Index k = parent.topology.vertexFaceStart[pole.pole]; k < parent.topology.vertexFaceStart[pole.pole + 1]; ++k)
        split[parent.topology.vertexCorners[k]] = 1;
  }
  return split;
}

}  // namespace

// One Catmull-Clark step of the connectivity, derived from the parent's tables (refine_topology.h);
// with `splitPoleQuads` each quad at a pole's corner is split along its diagonal (pole - face point)
// into two triangles, doubling the polar valence. `links` holds the parent's corner links on entry
// and the child's on return (none without `childLinks`; the parent's still when the child is
// made with its faces only, `fullTopology` false, for completeGenericTopology).
RefinedLevel refineGenericTopology(const RefinedLevel& parent, bool splitPoleQuads, std::vector<Index>& links, bool childLinks,
                                   bool fullTopology) {
  std::vector<uint8_t> split = poleCornerSplits(parent, splitPoleQuads);
  RefinedConnectivity connectivity;
  ConnectivityOptions options;
  options.childLinks = childLinks && fullTopology;
  options.vertexRings = options.edges = fullTopology;
  refineCatmullClarkConnectivity(parent.mesh, parent.topology, links, split.empty() ? nullptr : &split, connectivity, options);
  RefinedLevel child;
  child.mesh = std::move(connectivity.mesh);
  child.topology = std::move(connectivity.topology);
  child.faceParent = std::move(connectivity.faceParent);
  if (options.vertexRings) {
    links.swap(connectivity.links);
    releaseToPool(connectivity.links);  // the parent's, no longer needed
  }
  releaseToPool(split);
  for (const PolarConfig& pole : parent.poles) child.poles.push_back(deriveChildConfig(pole, parent.mesh, parent.topology));
  return child;
}

void completeGenericTopology(const RefinedLevel& parent, bool splitPoleQuads, const std::vector<Index>& links, RefinedLevel& child) {
  std::vector<uint8_t> split = poleCornerSplits(parent, splitPoleQuads);
  // The builder completes a RefinedConnectivity: lend it the child's mesh, tables and parents.
  RefinedConnectivity connectivity;
  connectivity.mesh = std::move(child.mesh);
  connectivity.topology = std::move(child.topology);
  connectivity.faceParent = std::move(child.faceParent);
  completeChildTopology(parent.mesh, parent.topology, links, split.empty() ? nullptr : &split, connectivity);
  child.mesh = std::move(connectivity.mesh);
  child.topology = std::move(connectivity.topology);
  child.faceParent = std::move(connectivity.faceParent);
  releaseToPool(split);
}

// [SECTION] radial levels: RTS/BPS on meshes made only of polar regions

// Regions covering the whole mesh, or empty when some face lies outside every polar region.
std::vector<RadialRegion> findRadialRegions(const PolyMesh& mesh, const MeshTopology& topology, const std::vector<PolarConfig>& poles) {
  std::vector<RadialRegion> regions;
  size_t faces = 0;
  for (const PolarConfig& config : poles) {
    if (config.outer == PolarConfig::Outer::Mesh || config.regularLinks < config.linkCount - 1) return {};
    if (config.outer == PolarConfig::Outer::Pole && config.oppositePole < config.pole) continue;  // counted from the other end
    RadialRegion region;
    region.n = config.valence;
    region.links = config.linkCount;
    region.closed = config.outer == PolarConfig::Outer::Pole;
    region.vertexIds.push_back(config.pole);
    region.vertexIds.insert(region.vertexIds.end(), config.links.begin(), config.links.end());
    if (region.closed) region.vertexIds.push_back(config.oppositePole);
    const int n = region.n;
    auto q = [&](int r, int j) { return r == region.links + 1 ? region.vertexIds.back() : region.vertexIds[1 + size_t(r - 1) * n + ((j % n) + n) % n]; };
    for (int j = 0; j < n; ++j) region.faceIds.push_back(faceWith(mesh, topology, q(1, j), q(1, j + 1), config.pole));
    for (int r = 1; r < region.links; ++r)
      for (int j = 0; j < n; ++j) region.faceIds.push_back(faceWith(mesh, topology, q(r, j), q(r, j + 1), q(r + 1, j)));
    if (region.closed)
      for (int j = 0; j < n; ++j) region.faceIds.push_back(faceWith(mesh, topology, q(region.links, j), q(region.links, j + 1), config.oppositePole));
    if (std::find(region.faceIds.begin(), region.faceIds.end(), Index(-1)) != region.faceIds.end()) return {};
    faces += region.faceIds.size();
    regions.push_back(std::move(region));
  }
  if (regions.empty() || faces != size_t(mesh.faceCount())) return {};
  return regions;
}

// Builds the connectivity of the next radial level: every region keeps n and gets 2 links + 1
// (closed) or 2 links (boundary) rings; faces laid out row by row, parents at row / 2.
RefinedLevel refineRadialTopology(const std::vector<RadialRegion>& parentRegions, std::vector<RadialRegion>& childRegions,
                                  const std::string& source) {
  RefinedLevel child;
  PolyMesh& mesh = child.mesh;
  childRegions.clear();
  Index vertexBase = 0, faceBase = 0;
  for (const RadialRegion& parent : parentRegions) {
    RadialRegion region;
    region.n = parent.n;
    region.closed = parent.closed;
    region.links = parent.closed ? 2 * parent.links + 1 : 2 * parent.links;
    region.vertexBase = vertexBase;
    region.faceBase = faceBase;
    const int n = region.n;
    auto parentFace = [&](int row, int j) {
      int r = row / 2;
      return parent.faceIds.empty() ? parent.faceBase + Index(r) * n + j : parent.faceIds[size_t(r) * n + j];
    };
    for (int j = 0; j < n; ++j) {
      mesh.addFace({region.vertex(0, 0), region.vertex(1, j), region.vertex(1, j + 1)});
      child.faceParent.push_back(parentFace(0, j));
    }
    for (int r = 1; r < region.links; ++r)
      for (int j = 0; j < n; ++j) {
        mesh.addFace({region.vertex(r, j), region.vertex(r + 1, j), region.vertex(r + 1, j + 1), region.vertex(r, j + 1)});
        child.faceParent.push_back(parentFace(r, j));
      }
    if (region.closed)
      for (int j = 0; j < n; ++j) {
        mesh.addFace({region.vertex(region.links + 1, 0), region.vertex(region.links, j + 1), region.vertex(region.links, j)});
        child.faceParent.push_back(parentFace(region.links, j));
      }
    vertexBase += region.vertexCount();
    faceBase += region.faceCount();
    childRegions.push_back(region);
  }
  mesh.points.resize(vertexBase);
  child.topology = buildTopology(mesh, source);

  // Poles: A with columns as laid out; B sees the columns reversed (its fan is counter-clockwise).
  for (const RadialRegion& region : childRegions) {
    const int n = region.n;
    PolarConfig a;
    a.pole = region.vertex(0, 0);
    a.valence = n;
    a.linkCount = region.links;
    a.regularLinks = region.links;
    a.outer = region.closed ? PolarConfig::Outer::Pole : PolarConfig::Outer::Boundary;
    a.refinable = true;
    for (int r = 1; r <= region.links; ++r)
      for (int j = 0; j < n; ++j) a.links.push_back(region.vertex(r, j));
    if (region.closed) {
      PolarConfig b = a;
      b.pole = region.vertex(region.links + 1, 0);
      b.oppositePole = a.pole;
      a.oppositePole = b.pole;
      b.links.clear();
      for (int r = region.links; r >= 1; --r)
        for (int j = 0; j < n; ++j) b.links.push_back(region.vertex(r, n - j));
      child.poles.push_back(a);
      child.poles.push_back(b);
    } else {
      child.poles.push_back(a);
    }
  }
  return child;
}

namespace {

// The rows (A, rings, B) of a region as a PolarGrid seen from A, or from B (reversed columns).
PolarGrid regionGrid(const std::vector<Point>& rows, const RadialRegion& region, bool fromB) {
  const int n = region.n, K = region.links;
  PolarGrid grid(n, K);
  grid.pole = fromB ? rows.back() : rows.front();
  for (int i = 1; i <= K; ++i)
    for (int j = 0; j < n; ++j) {
      int row = fromB ? K + 1 - i : i;
      int col = fromB ? (n - j) % n : j;
      grid.q(i, j) = rows[1 + size_t(row - 1) * n + col];
    }
  return grid;
}

}  // namespace

// One radial step of a region's rows (A, links 1..K, B?) into the child's rows: rules (9)-(12) at
// each pole, the uniform radial cubic rules between, a boundary ring kept in place.
void refineRegionRadially(const std::vector<Point>& rows, const RadialRegion& parent, const SchemeTraits& rules,
                          bool uniformFirstStep, std::vector<Point>& childRows) {
  const int n = parent.n, K = parent.links;
  const int childLinks = parent.closed ? 2 * K + 1 : 2 * K;
  childRows.assign(size_t(childLinks) * n + (parent.closed ? 2 : 1), Point(0.0));
  auto childRow = [&](int r) { return &childRows[1 + size_t(r - 1) * n]; };
  // Uniform rules between the special rows: child links 3..2K-1 from parent links 1..K.
  refineOuterLinksRadially(&rows[1], n, K, childRow(3));
  // Pole A's rows 0..2.
  PolarGrid a = regionGrid(rows, parent, false);
  childRows[0] = rules.refinePole(a);
  rules.refineLink1(a, childRow(1));
  rules.refineLink2(a, childRow(2), uniformFirstStep);
  if (parent.closed) {  // pole B's rows, columns reversed back
    PolarGrid b = regionGrid(rows, parent, true);
    std::vector<Point> link(n);
    childRows.back() = rules.refinePole(b);
    rules.refineLink1(b, link.data());
    for (int j = 0; j < n; ++j) childRow(childLinks)[(n - j) % n] = link[j];
    rules.refineLink2(b, link.data(), uniformFirstStep);
    for (int j = 0; j < n; ++j) childRow(childLinks - 1)[(n - j) % n] = link[j];
  } else {  // the boundary ring stays: radially Catmull-Clark's boundary rule (mirrored phantom) fixes it
    std::copy(&rows[1 + size_t(K - 1) * n], &rows[1 + size_t(K) * n], childRow(childLinks));
  }
}

void inheritHoles(const RefinedLevel& parent, RefinedLevel& child) {
  child.faceHole.clear();
  if (parent.faceHole.empty()) return;
  child.faceHole.resize(child.faceParent.size());
  for (size_t f = 0; f < child.faceParent.size(); ++f) child.faceHole[f] = parent.faceHole[size_t(child.faceParent[f])];
}

void fillPoleData(RefinedLevel& level, Scheme scheme, const std::vector<PolarGrid>* schemeGrids) {
  const int gridLinks = 5;  // links kept in poleGrids: enough for ring 0 and the cap
  level.poleGrids.clear();
  level.poleTaylor.clear();
  if (!schemeTraits(scheme).polar()) return;
  for (size_t k = 0; k < level.poles.size(); ++k) {
    const PolarConfig& config = level.poles[k];
    level.poleGrids.push_back(gatherGrid(level.mesh.points, config, std::min(gridLinks, config.linkCount)));
    const PolarGrid& source = schemeGrids ? (*schemeGrids)[k] : level.poleGrids.back();
    level.poleTaylor.push_back(poleTaylorCoefficients(source, scheme));
  }
}

// [SECTION] Refinement

struct Refinement::Plan {
  bool radial = false;
  size_t inputVertices = 0;
  std::vector<Index> sourceVertex;  // non-manifold input: per level-0 vertex, the input's (manifold_split.h)
  std::vector<std::vector<RadialRegion>> regions;  // radial mode: per level
  std::string source;
  // The finest level made with its faces only (RefineOptions::fullFinestTopology): its parent's
  // corner links, kept for completeFinestTopology.
  bool finestTopologyMissing = false;
  std::vector<Index> finestParentLinks;
};

bool refinesRadially(const PolyMesh& base, Scheme scheme) {
  if (!schemeTraits(scheme).keepsValence) return false;
  MeshTopology topology;
  try {
    topology = buildTopology(base, "<mesh>");
  } catch (const std::exception&) {
    return false;  // not refinable at all; the refiner says why
  }
  return refinesRadially(PreparedBase{base, {}, topology, findPolarConfigs(base, topology)}, scheme);
}

bool refinesRadially(const PreparedBase& base, Scheme scheme) {
  if (!schemeTraits(scheme).keepsValence) return false;
  std::vector<PolarConfig> poles;
  for (const PolarConfig& config : base.configs)
    if (schemeRefinesPole(scheme, config)) poles.push_back(config);
  return !findRadialRegions(base.mesh, base.topology, poles).empty();
}

size_t estimateFaceCount(const PolyMesh& base, const RefineOptions& options, bool radial) {
  if (options.levels <= 0) return size_t(base.faceCount());
  // Radial refinement (RTS/BPS on caps and globes) keeps the valence and doubles the links: the
  // face count doubles a level (globe: 128, 256, 512, ... exactly).
  if (radial) return size_t(std::min(double(base.faceCount()) * std::pow(2.0, options.levels), 1e18));
  // Catmull-Clark: one quad per corner, then x4 per level; polar splits add < corners per level.
  double faces = double(base.faceVerts.size()) * std::pow(4.0, options.levels - 1);
  return size_t(std::min(faces * 1.25, 1e18));
}

Refinement::Refinement(const PolyMesh& input, const RefineOptions& options, const std::string& sourceName, size_t maxFaces)
    : options_(options), plan_(std::make_unique<Plan>()) {
  plan_->source = sourceName;
  // Non-manifold input: refined as its manifold split with OpenSubdiv's sharpening (manifold_split.h).
  ManifoldSplit split;
  MeshTopology baseTopology;
  const PolyMesh& base = refinableMesh(input, split, baseTopology, sourceName);
  plan_->inputVertices = size_t(input.vertexCount());
  plan_->sourceVertex = std::move(split.sourceVertex);
  if (options.levels < 0) throw InputError(sourceName, 0, "negative subdivision level " + std::to_string(options.levels));
  // Catmull-Clark growth unless RTS/BPS refine the whole mesh radially (checked below, once the
  // base topology is known): refuse at once what cannot fit either way.
  const bool mayBeRadial = schemeTraits(options.scheme).keepsValence;
  auto refuseOver = [&](size_t estimate) {
    if (estimate > maxFaces)
      throw InputError(sourceName, 0,
                       "level " + std::to_string(options.levels) + " would need about " + std::to_string(estimate) +
                           " faces, over the memory budget of " + std::to_string(maxFaces) + " faces");
  };
  refuseOver(estimateFaceCount(base, options, mayBeRadial));

  RefinedLevel level0;
  level0.mesh = base;
  level0.topology = std::move(baseTopology);
  for (PolarConfig& config : findPolarConfigs(base, level0.topology))
    if (schemeRefinesPole(options.scheme, config)) level0.poles.push_back(std::move(config));
  // Creases and corners: Catmull-Clark's rules wherever Catmull-Clark's connectivity refines (every
  // scheme but RTS/BPS's radial refinement of caps and globes, below; poles they touch are left to
  // Catmull-Clark by findPolarConfigs).
  bool creases = !base.tags.empty();
  if (creases) level0.sharpness = baseSharpness(base, level0.topology);
  level0.faceHole = baseHoles(base, level0.topology);
  levels_.push_back(std::move(level0));

  // RTS/BPS on caps and globes: radial refinement of the whole mesh.
  if (schemeTraits(options.scheme).keepsValence) {
    std::vector<RadialRegion> regions = findRadialRegions(levels_[0]);
    plan_->radial = !regions.empty();
    if (plan_->radial) plan_->regions.push_back(std::move(regions));
    if (plan_->radial) levels_[0].sharpness = {}, creases = false;  // the radial rules have no creases
  }
  if (!plan_->radial) refuseOver(estimateFaceCount(base, options));
  std::vector<Index> links;  // generic levels: the current finest level's corner links
  if (!plan_->radial && options.levels > 0) links = cornerLinks(levels_[0].mesh, levels_[0].topology);
  for (int m = 1; m <= options.levels; ++m) {
    if (plan_->radial) {
      std::vector<RadialRegion> childRegions;
      levels_.push_back(refineRadialTopology(plan_->regions.back(), childRegions, sourceName));
      plan_->regions.push_back(std::move(childRegions));
    } else {
      // Creases decay along the child's edges, found through its rings (childSharpness): kept then.
      // A faces-only finest level reads no links of its parent: those are made if it is completed.
      const bool fullFinest = options.fullFinestTopology || creases;
      const bool finest = m == options.levels, nextFacesOnly = m + 1 == options.levels && !fullFinest;
      levels_.push_back(refineGenericTopology(levels_.back(), schemeTraits(options.scheme).polar(), links,
                                              !finest && !nextFacesOnly, !finest || fullFinest));
      if (creases) {
        const RefinedLevel& parent = levels_[levels_.size() - 2];
        RefinedLevel& child = levels_.back();
        child.sharpness = childSharpness(parent.topology, parent.sharpness, child.topology);
        child.mesh.tags = sharpnessTags(child.topology, child.sharpness, base.tags);
      }
    }
    inheritHoles(levels_[levels_.size() - 2], levels_.back());
    // The refined mesh says which of its faces are holes (`refine` writes them as `t hole`).
    RefinedLevel& child = levels_.back();
    child.mesh.tags.holes.clear();
    for (size_t f = 0; f < child.faceHole.size(); ++f)
      if (child.faceHole[f]) child.mesh.tags.holes.push_back(Index(f));
  }
  if (!plan_->radial && options.levels > 0 && !options.fullFinestTopology && !creases) {
    plan_->finestTopologyMissing = true;
    plan_->finestParentLinks = std::move(links);
  }
  updatePositions(input.points);
}

bool Refinement::finestTopologyComplete() const { return !plan_->finestTopologyMissing; }

void Refinement::completeFinestTopology() {
  if (!plan_->finestTopologyMissing) return;
  const RefinedLevel& parent = levels_[levels_.size() - 2];
  if (plan_->finestParentLinks.empty()) plan_->finestParentLinks = cornerLinks(parent.mesh, parent.topology);
  completeGenericTopology(parent, schemeTraits(options_.scheme).polar(), plan_->finestParentLinks, levels_.back());
  releaseToPool(plan_->finestParentLinks);
  plan_->finestTopologyMissing = false;
}

// The big tables go to the pool for the next refinement (table_pool.h).
Refinement::~Refinement() {
  for (RefinedLevel& level : levels_) {
    releaseToPool(level.mesh.points);
    releaseToPool(level.mesh.faceStart);
    releaseToPool(level.mesh.faceVerts);
    releaseToPool(level.faceParent);
    MeshTopology& t = level.topology;
    for (std::vector<Index>* table : {&t.cornerEdge, &t.cornerFace, &t.edgeVerts, &t.edgeFaces, &t.vertexFaceStart,
                                      &t.vertexFaces, &t.vertexEdgeStart, &t.vertexEdges, &t.vertexCorners})
      releaseToPool(*table);
    releaseToPool(t.vertexOnBoundary);
    releaseToPool(t.vertexUsed);
  }
}
Refinement::Refinement(Refinement&&) noexcept = default;
Refinement& Refinement::operator=(Refinement&&) noexcept = default;

bool Refinement::radialOnly() const { return plan_->radial; }

bool Refinement::splitInput() const { return !plan_->sourceVertex.empty(); }

PolyMesh Refinement::takeOutputMesh() && {
  return splitInput() ? outputMesh() : std::move(levels_.back().mesh);
}

PolyMesh Refinement::outputMesh() const {
  if (plan_->sourceVertex.empty() || plan_->radial) return finest().mesh;
  // merged[v]: the output vertex of split vertex v at the current level.
  std::vector<Index> merged(plan_->sourceVertex), childMerged;
  Index mergedCount = Index(plan_->inputVertices);
  std::vector<std::pair<uint64_t, Index>> edgeKeys;
  for (int m = 0; m + 1 < levelCount(); ++m) {
    const MeshTopology& topo = levels_[size_t(m)].topology;
    // Output edges: split edges with the same merged ends are one.
    edgeKeys.resize(size_t(topo.edgeCount));
    for (Index e = 0; e < topo.edgeCount; ++e) {
      const uint64_t a = uint64_t(merged[size_t(topo.edgeVerts[2 * e])]), b = uint64_t(merged[size_t(topo.edgeVerts[2 * e + 1])]);
      edgeKeys[size_t(e)] = {std::min(a, b) << 32 | std::max(a, b), e};
    }
    std::sort(edgeKeys.begin(), edgeKeys.end());
    std::vector<Index> edgeId(size_t(topo.edgeCount));
    Index edges = 0;
    for (size_t i = 0; i < edgeKeys.size(); ++i) {
      if (i > 0 && edgeKeys[i].first != edgeKeys[i - 1].first) ++edges;
      edgeId[size_t(edgeKeys[i].second)] = edges;
    }
    if (!edgeKeys.empty()) ++edges;
    childMerged.assign(size_t(ccChildVertexCount(topo)), 0);
    for (Index f = 0; f < topo.faceCount; ++f) childMerged[size_t(ccFacePoint(topo, f))] = f;
    for (Index e = 0; e < topo.edgeCount; ++e) childMerged[size_t(ccEdgePoint(topo, e))] = topo.faceCount + edgeId[size_t(e)];
    for (Index v = 0; v < topo.vertexCount; ++v) childMerged[size_t(ccVertexPoint(topo, v))] = topo.faceCount + edges + merged[size_t(v)];
    mergedCount = topo.faceCount + edges + mergedCount;
    merged.swap(childMerged);
  }
  const PolyMesh& split = finest().mesh;
  PolyMesh out;
  out.points.assign(size_t(mergedCount), Point(0.0));
  for (size_t v = 0; v < split.points.size(); ++v) out.points[size_t(merged[v])] = split.points[v];
  out.faceStart = split.faceStart;
  out.faceVerts.resize(split.faceVerts.size());
  for (size_t c = 0; c < split.faceVerts.size(); ++c) out.faceVerts[c] = merged[size_t(split.faceVerts[c])];
  // Tags: the split's, on the merged ids (its sharpened copies say what OpenSubdiv sharpens too).
  out.tags = split.tags;
  for (CreaseEdge& crease : out.tags.creases) {
    const Index a = merged[size_t(crease.v0)], b = merged[size_t(crease.v1)];
    crease.v0 = std::min(a, b), crease.v1 = std::max(a, b);
  }
  std::sort(out.tags.creases.begin(), out.tags.creases.end(), [](const CreaseEdge& x, const CreaseEdge& y) {
    return x.v0 != y.v0 ? x.v0 < y.v0 : x.v1 != y.v1 ? x.v1 < y.v1 : x.sharpness > y.sharpness;
  });
  out.tags.creases.erase(std::unique(out.tags.creases.begin(), out.tags.creases.end(),
                                     [](const CreaseEdge& x, const CreaseEdge& y) { return x.v0 == y.v0 && x.v1 == y.v1; }),
                         out.tags.creases.end());
  for (CornerVertex& corner : out.tags.corners) corner.vertex = merged[size_t(corner.vertex)];
  std::sort(out.tags.corners.begin(), out.tags.corners.end(),
            [](const CornerVertex& x, const CornerVertex& y) { return x.vertex != y.vertex ? x.vertex < y.vertex : x.sharpness > y.sharpness; });
  out.tags.corners.erase(std::unique(out.tags.corners.begin(), out.tags.corners.end(),
                                     [](const CornerVertex& x, const CornerVertex& y) { return x.vertex == y.vertex; }),
                         out.tags.corners.end());
  return out;
}

void Refinement::updatePositions(const std::vector<Point>& basePoints) {
  if (basePoints.size() != plan_->inputVertices)
    throw std::invalid_argument("updatePositions: " + std::to_string(basePoints.size()) + " points for a mesh of " +
                                std::to_string(plan_->inputVertices));
  if (plan_->sourceVertex.empty()) {
    levels_[0].mesh.points = basePoints;
  } else {
    for (size_t v = 0; v < plan_->sourceVertex.size(); ++v) levels_[0].mesh.points[v] = basePoints[size_t(plan_->sourceVertex[v])];
  }
  const Scheme scheme = options_.scheme;
  auto fillPoleData = [&](RefinedLevel& level, const std::vector<PolarGrid>* schemeGrids) {
    polarview::fillPoleData(level, scheme, schemeGrids);
  };

  if (plan_->radial) {
    // Structured rows per region; level 0 gathers them from the input's ids.
    const SchemeTraits& rules = schemeTraits(scheme);
    std::vector<std::vector<Point>> rows;
    for (const RadialRegion& region : plan_->regions[0]) {
      rows.emplace_back();
      for (Index id : region.vertexIds) rows.back().push_back(levels_[0].mesh.points[size_t(id)]);
    }
    fillPoleData(levels_[0], nullptr);
    std::vector<Point> childRows;
    for (int m = 1; m < levelCount(); ++m) {
      RefinedLevel& level = levels_[m];
      for (size_t r = 0; r < rows.size(); ++r) {
        const RadialRegion& parent = plan_->regions[m - 1][r];
        refineRegionRadially(rows[r], parent, rules, options_.uniformFirstStep && m == 1, childRows);
        std::copy(childRows.begin(), childRows.end(), level.mesh.points.begin() + plan_->regions[m][r].vertexBase);
        rows[r].swap(childRows);
      }
      fillPoleData(level, nullptr);
    }
    return;
  }

  // Generic levels: Catmull-Clark points, then the polar overrides.
  const SchemeTraits& rules = schemeTraits(scheme);
  const bool radialPoles = rules.keepsValence;
  std::vector<PolarGrid> radialGrids;  // RTS/BPS: each pole's own radially refined configuration
  if (radialPoles)
    for (const PolarConfig& config : levels_[0].poles) radialGrids.push_back(gatherGrid(levels_[0].mesh.points, config, config.linkCount));
  fillPoleData(levels_[0], radialPoles ? &radialGrids : nullptr);

  std::vector<Point> link1, link2, refined, scratch;
  for (int m = 1; m < levelCount(); ++m) {
    const RefinedLevel& parent = levels_[m - 1];
    RefinedLevel& level = levels_[m];
    level.mesh.points.resize(ccChildVertexCount(parent.topology));
    computeCatmullClarkPoints(parent.topology, parent.mesh, parent.mesh.points.data(), level.mesh.points.data(), parent.sharpness);
    const bool uniformStep = options_.uniformFirstStep && m == 1;
    for (size_t k = 0; k < level.poles.size(); ++k) {
      const PolarConfig& child = level.poles[k];
      std::vector<Point>& points = level.mesh.points;
      if (!radialPoles) {
        // C2PS: rules (1)-(3) override the pole, the new 1-link and the new 2-link.
        PolarGrid grid = gatherGrid(parent.mesh.points, parent.poles[k], 2);
        const int n2 = child.valence;
        link1.resize(n2);
        link2.resize(n2);
        rules.refineLink1(grid, link1.data());
        rules.refineLink2(grid, link2.data(), uniformStep);
        points[child.pole] = rules.refinePole(grid);
        for (int j = 0; j < n2; ++j) {
          points[child.links[j]] = link1[j];
          points[child.links[size_t(n2) + j]] = link2[j];
        }
      } else if (radialPoles) {
        // The radially refined configuration, refined m times periodically, owns links 0..K_m-1.
        PolarGrid& grid = radialGrids[k];
        grid = rules.refineGrid(grid, uniformStep);
        points[child.pole] = grid.pole;
        const int owned = std::min(grid.links - 1, child.linkCount);
        for (int i = 1; i <= owned; ++i) {
          refinePeriodically(&grid.q(i, 0), grid.n, m, refined, scratch);
          for (int j = 0; j < child.valence; ++j) points[child.links[size_t(i - 1) * child.valence + j]] = refined[j];
        }
      }
    }
    fillPoleData(level, radialPoles ? &radialGrids : nullptr);
  }
}

}  // namespace polarview
