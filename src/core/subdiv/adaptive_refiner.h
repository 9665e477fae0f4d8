// Feature-adaptive refinement (after OpenSubdiv's Far::TopologyRefiner::RefineAdaptive and
// Niessner et al. 2012): level m+1 refines only the faces whose patches are not yet regular, with
// the neighbourhood their rules need, so the cost grows with the patches, not as 4^L.
//
// Level m holds a part of the uniform refinement's level m (refiner.h), with
//  * neededFaces(m): the faces the uniform extraction would take patches from or refine (children
//    of faces refined because they were not regular; level 0: all). Their corners have the uniform
//    level's faces around them and their 4x4 stencils the uniform level's points;
//  * exactVertices(m): vertices whose position equals the uniform level's (round-off). Vertices at
//    the rim of the refined part were computed from incomplete neighbourhoods and are not exact.
// Step m -> m+1 (sparse, as OpenSubdiv's Vtr sparse refinement): R = needed faces that are not
// regular; the selected vertices are R's corners, and level m+1 holds the child faces of every
// level m face at its selected corners and nothing else: all four children of R's faces, and of
// each face around them the ones at R's corners, which hold exactly the points the next level's
// 4x4 stencils and rules read. Connectivity as the uniform refiner's steps (refine_topology.h):
// Catmull-Clark's quads, C2PS's split pole corners; the child's tables come from half-edge twins
// derived from level m's (buildTopologyFromTwins), its points from a sparse kernel over level m's
// tables (computeSparseCatmullClarkPoints). A face whose selected corners form several runs gets a
// face point per run (the child stays manifold; OpenSubdiv keeps one non-manifold point). Faces
// refined therefore equal OpenSubdiv's RefineAdaptive's (docs/performance.md). A child vertex is
// exact when the points its rule reads are exact and complete (Catmull-Clark vertex point: the
// vertex's faces are the uniform level's; edge point: both faces, or a real boundary; face point:
// its corners; C2PS's rules (1)-(3): links 0..2 of the pole). Poles keep the uniform level's index,
// orientation and first links: I wholly selected links give the child's links 1..2I+1.
// RTS/BPS's radial steps (caps and globes, and the tail's pole regions) copy the selection grown
// by three rings out as a mesh of their own and refine it radially (radial rows: exact when the
// parent rows of the cubic rules are).
//
// Precision: a level-20 ring is 1e-6 of the model and its points 1e-8 apart, so absolute doubles
// near 1 (rounding 1e-16) would leave the second differences curvature is made of (~1e-16) to
// round-off. Each step therefore refines every connected component of the faces it touches in a frame of its own,
// anchored at one of its parent vertices (its pole where it has one): level m+1's points are
// relative to RefinedLevel::frameOrigins[vertexFrame[v]], and the rules' differences keep double
// precision relative to the component's size at any depth. Patches carry the origin
// (Patch::origin). RTS/BPS's radial grids move into their pole's frame each level.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/subdiv/refiner.h"

namespace polarview {

class AdaptiveRefinement {
 public:
  // Refines `base` (already validated) `options.levels` times adaptively. Throws InputError when
  // the levels together would hold more than `maxFaces` faces (checked before each level is made).
  // A non-manifold `base` is refined as its manifold split (manifold_split.h): level 0 is the split
  // mesh; updatePositions still takes the input's points.
  AdaptiveRefinement(const PolyMesh& base, const RefineOptions& options, const std::string& sourceName = "<mesh>",
                     size_t maxFaces = size_t(1) << 26);
  // The same from `input`'s prepared base (its tables and polar configurations made before, by
  // a model's analysis): copied, not built again.
  AdaptiveRefinement(const PolyMesh& input, const PreparedBase& prepared, const RefineOptions& options,
                     const std::string& sourceName = "<mesh>", size_t maxFaces = size_t(1) << 26);
  ~AdaptiveRefinement();
  AdaptiveRefinement(AdaptiveRefinement&&) noexcept;
  AdaptiveRefinement& operator=(AdaptiveRefinement&&) noexcept;

  const RefineOptions& options() const { return options_; }
  int levelCount() const { return int(levels_.size()); }
  const RefinedLevel& level(int m) const { return levels_[m]; }
  const std::vector<uint8_t>& neededFaces(int m) const { return needed_[m]; }
  const std::vector<uint8_t>& exactVertices(int m) const { return exact_[m]; }
  // Faces of level m whose children keep their columns (radial steps): no level jump in parameter
  // along the rings across them.
  const std::vector<uint8_t>& radiallyRefinedFaces(int m) const { return radialRefined_[m]; }
  // True when RTS/BPS refine radially (caps and globes), as Refinement::radialOnly.
  bool radialOnly() const { return radial_; }
  // Whether level m (>= 1) equals level m-1 in its faces, tables and every flag a step reads (found
  // as it was made; always false without RefineOptions::copyFixedPointLevels): the hierarchy is at
  // a fixed point there, so every deeper level was made as a copy of it (its points its own), and
  // patch extraction reuses level m-1's classification and stencils. [O(1)]
  bool repeatsParentLevel(int m) const { return m >= 1 && m < levelCount() && repeats_[size_t(m)] != 0; }
  // Faces of all levels and of the copied-out parts (what the budget counts). [O(1)]
  size_t totalFaces() const { return totalFaces_; }

  // Recomputes every level's points from new base points (same count as the base, else
  // std::invalid_argument); topology untouched. [O(faces of all levels)]
  void updatePositions(const std::vector<Point>& basePoints);

  // Level m does not depend on how deep the refinement goes, so a viewer stepping the level keeps
  // one refinement: extend() makes `levels` more levels from the finest (topology and points of
  // the new levels only; the same InputError as the constructor when they would exceed
  // `maxFaces`, the refinement then unchanged), truncate() drops the levels beyond `levels`.
  // Either way the result equals a refinement made to that level at once. [O(new faces)], [O(1)]
  void extend(int levels, size_t maxFaces = size_t(1) << 26);
  void truncate(int levels);

 private:
  struct Step;  // what makes level m+1 from level m
  // Per level: what a further step starts from (whether the poles' regions refine radially apart,
  // which vertices see all their uniform faces, RTS/BPS's own radial grids of mixed meshes).
  struct LevelState;
  // Level 0 from the refinable mesh, its tables and polar configurations; then `options_.levels`
  // levels and the input's points.
  void start(const PolyMesh& input, const PolyMesh& base, MeshTopology topology, std::vector<Index> sourceVertex,
             const std::vector<PolarConfig>& configs, size_t maxFaces);
  void addLevels(int count, size_t maxFaces);
  // Level m (>= 1) reads as level m-1 in everything a sparse step reads. [O(level m)]
  bool stepInputsEqualParent(int m) const;
  // Level m+1 and step m as copies of level m and step m-1 (repeatsParentLevel(m)). [O(level m), copies]
  void copyFixedPointStep(int m, int target, size_t maxFaces);
  // Throws InputError when `newFaces` more would exceed maxFaces (a step of level m towards `target`).
  void checkBudget(size_t newFaces, int target, int m, size_t maxFaces) const;
  void appendTail(const RefinedLevel& level, const std::vector<uint8_t>& polar, int m, Step& step, RefinedLevel& child,
                  std::vector<uint8_t>& childExact, std::vector<uint8_t>& childComplete) const;
  void computePoints(size_t firstStep);
  RefineOptions options_;
  std::string sourceName_;
  size_t inputVertices_ = 0;
  std::vector<Index> sourceVertex_;  // non-manifold input: per level-0 vertex, the input's (manifold_split.h)
  bool radial_ = false;
  std::vector<RefinedLevel> levels_;
  std::vector<std::vector<uint8_t>> needed_, exact_;
  std::vector<std::vector<uint8_t>> radialRefined_;  // per level: faces refined radially into the next
  std::vector<Step> steps_;
  std::vector<LevelState> states_;
  std::vector<size_t> totalFacesAt_;  // totalFaces() of the refinement ending at each level
  std::vector<uint8_t> repeats_;      // per level: repeatsParentLevel(m)
  size_t totalFaces_ = 0;
};

// Faces adaptive refinements of 0..options.levels levels would hold in all (what AdaptiveRefinement's
// budget counts), one entry per level: levels up to `measured` are refined (7: two levels past the
// start of the RTS/BPS tail), deeper ones extrapolated as faces(m) = a + b 2^m through the last two
// measured levels (C2PS's poles double their valence each level; Catmull-Clark's extraordinary
// vertices and radial rings add the same each level; at most 1e18). A measured level whose total
// would exceed `maxFaces` (the caller's budget) is not made: it and the deeper ones read
// maxFaces + 1 ("more than the budget"; sums of estimates stay over it), so the estimate itself
// never holds more than maxFaces faces. [O(faces of the measured levels, at most maxFaces)]
std::vector<size_t> estimateAdaptiveFaceCounts(const PolyMesh& base, const RefineOptions& options, size_t maxFaces, int measured = 7);
// The same from `input`'s prepared base (AdaptiveRefinement's second constructor).
std::vector<size_t> estimateAdaptiveFaceCounts(const PolyMesh& input, const PreparedBase& prepared, const RefineOptions& options,
                                               size_t maxFaces, int measured = 7);

}  // namespace polarview
