// Feature-adaptive patch extraction: the limit surface of a Refinement as bicubic patches
// (docs/patches.md, Extraction; docs/rings-and-pole.md, Spline rings; Myles & Peters 2009, Section 5.1,
// (6)-(8)).
//
// At each level m a patch is emitted for every face whose 4x4 neighbourhood is regular and whose
// parent face was not (so each piece of surface is covered once, by the coarsest patch that
// represents it exactly):
//  * Regular: a quad whose 4 corners are interior valence-4 vertices with only quads around them.
//  * Boundary: the same with some corners on the boundary, each such corner of valence 3 with two
//    quads; the missing control points are mirrored (phantom = 2 * boundary point - interior point),
//    so the boundary curve is the cubic B-spline of the boundary polygon, Catmull-Clark's
//    VTX_BOUNDARY_EDGE_ONLY limit. A valence-2 corner is NOT regular here: under EDGE_ONLY it is a
//    smooth boundary vertex with limit 2/3 v + 1/6 (a + b), which a mirrored corner patch (it
//    interpolates v) would miss; OpenSubdiv too treats it as regular only when it is sharp. Such
//    faces are refined to the last level and end as EndCaps (which do reproduce that limit).
//  * PolarRing: a regular (or boundary) patch whose whole stencil lies in links 1..5 of one polar
//    configuration of that level: paper (6), ring = m, pole = index in RefinedLevel::poles.
// At the finest level L:
//  * PoleCap: every pole of finest().poles with Taylor data (RefinedLevel::poleTaylor) and at least
//    3 links gets one cap per column j (patch.h layout): p0..p5 of poleTaylor, boundary points
//    b_j = (q1j + 4 q2j + q3j) / 6 (the inner boundary of ring L), first and second radial
//    derivative points e_j = (q3j - q1j) / 2 and f_j = q1j - 2 q2j + q3j (ring L's there, so the
//    cap is C2 with the ring), sector j of sectorCount n.
//    They replace the faces between links 0-1 and 1-2.
//  * EndCap: every other face not covered. Built in Bezier form and converted to the B-spline
//    control points of patch.h (Bezier -> B-spline per direction: d0 = 6b0 - 7b1 + 2b2,
//    d1 = 2b1 - b2, d2 = 2b2 - b1, d3 = 6b3 - 7b2 + 2b1, the inverse of the map in docs/patches.md,
//    B-spline basis and Bezier form):
//      - corners: Catmull-Clark limit points (interior valence k: k/(k+5) v + 4/(k(k+5)) sum e +
//        1/(k(k+5)) sum f; boundary: 2/3 v + 1/6 (a + b));
//      - each boundary curve: the cubic Hermite curve of the limit points and limit tangents of its
//        two end vertices along that edge (interior: the Catmull-Clark tangent mask
//        sum_j A_k cos(2 pi (j-i)/k) e_j + (cos(2 pi (j-i)/k) + cos(2 pi (j+1-i)/k)) f_j, scaled so
//        k = 4 gives the B-spline derivative; boundary edge: (b - a)/2; interior edge at a boundary
//        vertex: (f_{i-1} + 4 e_i + f_i)/6 - limit). It depends only on the edge, so both faces
//        compute the same curve; at regular end vertices it IS the neighbouring B-spline patch's
//        boundary curve, on the boundary it is the EDGE_ONLY limit curve;
//      - interior Bezier points: Loop-Schaefer's (k v + 2 e_a + 2 e_b + d)/(k+5) per corner (k = 4
//        at boundary vertices).
//    Continuity: G0 (watertight up to round-off) everywhere; the normal is continuous at the
//    extraordinary vertex itself (all its tangents lie in one plane) and only approximately along
//    the end caps' edges. A non-quad face (only possible at level 0, or at a pole left without a
//    cap) is split into k quads (corner, edge midpoint, centre, edge midpoint) whose outer edges
//    are the halves of the edge curves (still watertight) and whose spokes are straight.
// Level jumps (Patch::edgeLevelDelta): for every side of a face-based quad patch, the level
// difference to the patches across it, from the mesh adjacency and RefinedLevel::faceParent: a side
// facing a face of its level that was refined further is a coarse side (+d, d = the largest jump
// reported by the fine patches along it); a side facing a face covered by a coarser patch Q (an
// ancestor of that face became Q) is a fine side (-d). Pole caps meet ring L at the same level (0).
#pragma once

#include <array>
#include <memory>
#include <utility>
#include <vector>

#include "core/spline/patch.h"
#include "core/subdiv/adaptive_refiner.h"
#include "core/subdiv/refiner.h"

namespace polarview {

struct PatchSet {
  std::vector<Patch> patches;          // flat, in extraction order (level by level, then caps)
  std::array<size_t, 5> kindCounts{};  // indexed by PatchKind

  // Number of patches of one kind. [O(1)]
  size_t count(PatchKind kind) const { return kindCounts[size_t(kind)]; }
};

// How each patch of a PatchSet was made (filled by extractPatches on request): for B-spline
// patches the 16 stencil vertex ids at the patch's level (-1: mirrored phantom) and which sides
// are on the boundary (bit s: side s); caps are remade from their face or pole.
struct PatchSources {
  std::vector<std::array<Index, 16>> stencil;
  std::vector<uint8_t> sidesMissing;
};

// Extracts the patches of every level of `refinement` (rules above), with Patch::edgeLevelDelta
// filled (all 0 for RTS/BPS radial levels, whose levels keep the columns). The finest level needs
// all its tables (std::logic_error otherwise: RefineOptions::fullFinestTopology,
// Refinement::completeFinestTopology). [O(faces of all levels)]
PatchSet extractPatches(const Refinement& refinement);
// The same patches from a feature-adaptive refinement: only its needed faces give patches, end caps
// and level jumps (adaptive_refiner.h), so the set equals extractPatches of the uniform refinement
// of the same levels (face ids differ). Throws std::logic_error if a patch would read a vertex that
// is not exact. [O(faces of all levels)]
// `sources` (optional) receives how each patch was made, for refreshPatches.
PatchSet extractPatches(const AdaptiveRefinement& refinement, PatchSources* sources = nullptr);

// Live edits: after refinement.updatePositions (topology untouched), recomputes the control points
// of `set` (made by extractPatches with these `sources`) from the new points; kinds, levels and
// level jumps stay. Equal to a fresh extractPatches. [O(patches); no classification, no search]
void refreshPatches(const AdaptiveRefinement& refinement, const PatchSources& sources, PatchSet& set);

// Patch sets of one AdaptiveRefinement at any of its levels, each level's patches extracted once
// (level m's regular patches do not depend on the finest level; the finest adds its caps): a viewer
// stepping the level on one refinement (AdaptiveRefinement::extend) assembles instead of
// re-extracting, and uploads only what is not shared with the set it showed (sharedPrefix).
class LevelPatchCache {
 public:
  LevelPatchCache();
  ~LevelPatchCache();
  LevelPatchCache(LevelPatchCache&&) noexcept;
  LevelPatchCache& operator=(LevelPatchCache&&) noexcept;

  // The patch set of `refinement` cut at level `finest` (0..levelCount()-1, else
  // std::invalid_argument): equal, patch for patch and with its sources, to extractPatches of a
  // refinement made to that level. [O(patches of the set + faces of new levels)]
  // `storage`: a vector whose memory the set may take (a viewer's previous set: large fresh
  // allocations cost page faults, about a third of an assembly at C2PS level 12).
  PatchSet patchSet(const AdaptiveRefinement& refinement, int finest, PatchSources* sources = nullptr,
                    std::vector<Patch> storage = {});
  // Extracts what patchSet(refinement, finest) needs without assembling it (a viewer makes the next
  // level ahead, in the background). [O(faces of new levels)]
  void prepare(const AdaptiveRefinement& refinement, int finest);
  // The patch set of level `finest` once prepared: its regular patches (of all levels) and its
  // caps; {0, 0} when not prepared. [O(levels)]
  std::pair<size_t, size_t> preparedCounts(int finest) const;
  // Whether no level has been extracted yet (a new refinement, or after forget()). [O(1)]
  bool empty() const;
  // How many patches the sets of levels a and b begin with in common (the regular patches of
  // levels 0..min(a, b); level jumps may differ). [O(levels)]
  size_t sharedPrefix(int a, int b) const;
  // Drops what levels >= fromLevel gave (their points or topology changed). [O(1)]
  void forget(int fromLevel = 0);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Tessellation segments of a T-junction edge (edgeLevelDelta d != 0) of a patch of `level`, for a
// per-view density exponent k (2^k segments per level-0 parameter unit); shaders/patch.tesc is its
// mirror. Coarse side (d > 0): 2^clamp(k - level, d, 6); fine side (d < 0): 2^clamp(k - level, 0,
// 6 + d). For every k the coarse side then has 2^d times the segments of each fine side, so with
// equal spacing the fine sides' vertices are exactly the coarse side's (the shared curve is the
// same curve, refined by knot insertion), and no side exceeds GL's 64. Jumps over 6 levels and a
// coarse side facing pieces of mixed levels can still crack (none seen on the test meshes). [O(1)]
int transitionEdgeSegments(int level, int delta, int densityExponent);

}  // namespace polarview
