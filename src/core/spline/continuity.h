// Continuity of a patch set's limit surface across its seams, measured with evaluatePatch
// (docs/commands.md, continuity): where two patch sides meet, how far apart the two patches' points
// are, the angle between their normals, and the jumps of K and H. C2PS is curvature continuous
// (Myles & Peters 2009, Section 4); Catmull-Clark's end caps are only G0 across their edges
// (patch_extraction.h, EndCap).
//
// Seams are found geometrically, not from the refinement's topology: each side is sampled at
// interior parameters, the sides passing near a sample are looked up in a hierarchical spatial hash
// of the sides' polylines and the sample is projected onto their boundary curves (Gauss-Newton on
// the cubic); the nearest within the tolerance is the partner.
// So T-junctions (a coarse side against 2^d finer sides), polar rings against rings of twice the
// columns, rings against pole caps and caps against caps are all found the same way.
#pragma once

#include <cstddef>
#include <vector>

#include "core/spline/patch_extraction.h"

namespace polarview {

// What meets at a seam, from the kinds of the two patches (seamKindOf).
enum class SeamKind : unsigned char {
  Regular,      // Regular / Boundary with Regular / Boundary
  RingRing,     // polar ring patches: consecutive rings, or neighbouring columns of one ring
  RingCap,      // ring L against a pole cap's boundary (u = 1 of the cap)
  CapCap,       // neighbouring cap sectors (the radial sides v = 0 / v = 1, u in (0,1])
  EndCap,       // an EndCap on at least one side
  RegularRing,  // the Catmull-Clark region against a polar ring
  RegularCap,   // the Catmull-Clark region against a pole cap
};
constexpr size_t kSeamKindCount = 7;
// "regular", "ring-ring", "ring-cap", "cap-cap", "end-cap", "regular-ring", "regular-cap". [O(1)]
const char* seamKindName(SeamKind kind);
// The kind of the seam between patches of kinds a and b (symmetric). [O(1)]
SeamKind seamKindOf(PatchKind a, PatchKind b);

struct ContinuityOptions {
  int samplesPerSide = 8;   // interior parameters (k + 1/2) / K of each side that look for a partner
  int curvatureGrid = 4;    // G x G interior parameters per patch for the model's largest |K|, |H|
};

// The worst values over the samples of every seam of one kind. Gaps relative to the bounding-box
// diagonal; angles in radians; jumps of K and H relative to the model's largest |K| and |H|.
struct SeamStats {
  SeamKind kind = SeamKind::Regular;
  size_t count = 0;        // side pairs that meet
  size_t tJunctions = 0;   // of them, pairs where one side meets more than one side
  size_t samples = 0;      // points compared
  double maxPositionGap = 0.0;
  double maxNormalAngle = 0.0;
  double maxGaussianJump = 0.0;
  double maxMeanJump = 0.0;
  double maxCurvatureJump() const { return maxGaussianJump > maxMeanJump ? maxGaussianJump : maxMeanJump; }
};

struct ContinuityReport {
  std::vector<SeamStats> seams;  // one per kind present, in SeamKind order
  size_t boundarySides = 0;      // sides no sample of which met another patch (the mesh boundary)
  double maxAbsGaussian = 0.0;   // over the curvature grid of every patch
  double maxAbsMean = 0.0;
  double boxDiagonal = 0.0;      // of the points the curvature grid sampled
  // The stats of one kind, or null where no seam of that kind was found. [O(kinds)]
  const SeamStats* find(SeamKind kind) const;
};

// Measures every seam of `set` (sides rules above; a PoleCap's side 3 is the pole point and is not
// a side; caps are compared at u in (0,1], never at the pole itself). A sample meets a side within
// 1e-6 of its own side's length (and 1e-12 of the diagonal); normals are oriented per seam by the
// sign of their mean dot product (H flips with them). [O(patches x samples x log)]
ContinuityReport measureContinuity(const PatchSet& set, const ContinuityOptions& options = {});

}  // namespace polarview
