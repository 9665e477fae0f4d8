// The single refinement steps the uniform Refinement (refiner.h) and the feature-adaptive one
// (adaptive_refiner.h) are built from: one Catmull-Clark/C2PS step of a level's connectivity, one
// radial step of RTS/BPS regions, and the lookups they share. Internal to core/subdiv.
#pragma once

#include <string>
#include <vector>

#include "core/subdiv/polar_grid.h"
#include "core/subdiv/refined_level.h"
#include "core/subdiv/scheme.h"

namespace polarview {


// Copies a configuration's points (pole and links 1..linkCount) into a PolarGrid. [O(n links)]
PolarGrid gatherGrid(const std::vector<Point>& points, const PolarConfig& config, int linkCount);
// Repeats periodic refinement (5) `times` times: n points -> n 2^times points.
void refinePeriodically(const Point* link, int n, int times, std::vector<Point>& out, std::vector<Point>& scratch);

// child.faceHole from the parent's (children of holes are holes), by child.faceParent. [O(faces)]
void inheritHoles(const RefinedLevel& parent, RefinedLevel& child);

// Fills level.poleGrids (links 0..min(5, K) of each pole) and level.poleTaylor (expansion (32) of
// the scheme, from `schemeGrids` where RTS/BPS keep their own radially refined grids, else from
// poleGrids); both empty for Catmull-Clark. [O(poles n)]
void fillPoleData(RefinedLevel& level, Scheme scheme, const std::vector<PolarGrid>* schemeGrids);

// The configuration one Catmull-Clark/C2PS step makes of `parent` (column j -> 2j, links K -> 2K),
// in the full child numbering of catmull_clark.h (ccVertexPoint ...) of `mesh`, `topo`. [O(n K)]
PolarConfig deriveChildConfig(const PolarConfig& parent, const PolyMesh& mesh, const MeshTopology& topo);
// One Catmull-Clark step of the connectivity, derived from the parent's tables (refine_topology.h);
// with `splitPoleQuads` each quad at a pole's corner is split along its diagonal (pole - face point)
// into two triangles, doubling the polar valence; the child's poles are derived from the parent's
// (column j -> 2j, links K -> 2K). `links` holds the parent's corner links on entry and on return
// the child's (`childLinks`: the next step is a full one), none (no `childLinks`), or, for
// completeGenericTopology, still the parent's when the child is made without `fullTopology`: its
// faces, face parents, counts and vertex flags only (OpenSubdiv's minimal last level). [O(corners)]
RefinedLevel refineGenericTopology(const RefinedLevel& parent, bool splitPoleQuads, std::vector<Index>& links, bool childLinks,
                                   bool fullTopology = true);
// The tables a refineGenericTopology(parent, splitPoleQuads, links, false, false) left out of
// `child` (`links`: the parent's, cornerLinks(parent) when the parent was made without them); its
// points stay. [O(corners)]
void completeGenericTopology(const RefinedLevel& parent, bool splitPoleQuads, const std::vector<Index>& links, RefinedLevel& child);

// A polar region refined radially: pole A, `links` rings of n points, then pole B (closed) or
// nothing (the last ring is a boundary). Rows: 0 = A, 1..links = rings, links+1 = B.
struct RadialRegion {
  int n = 0, links = 0;
  bool closed = false;
  Index vertexBase = 0, faceBase = 0;  // first vertex / face of the region at this level
  std::vector<Index> vertexIds;        // level 0 only: mesh ids by row (A, rings, B)
  std::vector<Index> faceIds;          // level 0 only: mesh face ids by row and column

  int rowCount() const { return links + (closed ? 2 : 1); }
  Index vertexCount() const { return Index(n) * links + (closed ? 2 : 1); }
  Index faceCount() const { return Index(n) * (closed ? links + 1 : links); }
  // Vertex id of row r, column j at a level >= 1 (laid out row by row).
  Index vertex(int r, int j) const {
    if (r == 0) return vertexBase;
    if (r == links + 1) return vertexBase + 1 + Index(n) * links;
    return vertexBase + 1 + Index(r - 1) * n + ((j % n) + n) % n;
  }
};

// Regions covering the whole mesh (each of `poles` that ends at a boundary or at another pole),
// or empty when some face lies outside every polar region. [O(mesh)]
std::vector<RadialRegion> findRadialRegions(const PolyMesh& mesh, const MeshTopology& topology,
                                            const std::vector<PolarConfig>& poles);
// The same for a level and the poles its scheme treats. [O(mesh)]
inline std::vector<RadialRegion> findRadialRegions(const RefinedLevel& level) {
  return findRadialRegions(level.mesh, level.topology, level.poles);
}
// The connectivity of the next radial level: every region keeps n and gets 2 links + 1 (closed) or
// 2 links (boundary) rings; faces laid out row by row, parents at row / 2. [O(output)]
RefinedLevel refineRadialTopology(const std::vector<RadialRegion>& parentRegions, std::vector<RadialRegion>& childRegions,
                                  const std::string& source);
// One radial step of a region's rows (A, links 1..K, B?) into the child's rows: rules (9)-(12) at
// each pole, the uniform radial cubic rules between, a boundary ring kept in place. [O(n K)]
void refineRegionRadially(const std::vector<Point>& rows, const RadialRegion& parent, const SchemeTraits& rules,
                          bool uniformFirstStep, std::vector<Point>& childRows);

}  // namespace polarview
