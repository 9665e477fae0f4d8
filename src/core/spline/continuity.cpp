#include "core/spline/continuity.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/ext/vector_int3_sized.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

namespace polarview {

namespace {

constexpr const char* kSeamKindNames[kSeamKindCount] = {"regular",  "ring-ring",    "ring-cap",   "cap-cap",
                                                        "end-cap",  "regular-ring", "regular-cap"};

// seamKindOf as a table over (PatchKind, PatchKind) in PatchKind order: Regular, Boundary,
// PolarRing, PoleCap, EndCap.
using SK = SeamKind;
constexpr SeamKind kSeamKindTable[5][5] = {
    {SK::Regular, SK::Regular, SK::RegularRing, SK::RegularCap, SK::EndCap},
    {SK::Regular, SK::Regular, SK::RegularRing, SK::RegularCap, SK::EndCap},
    {SK::RegularRing, SK::RegularRing, SK::RingRing, SK::RingCap, SK::EndCap},
    {SK::RegularCap, SK::RegularCap, SK::RingCap, SK::CapCap, SK::EndCap},
    {SK::EndCap, SK::EndCap, SK::EndCap, SK::EndCap, SK::EndCap},
};

// Dense points per side for its box and the projection's first guess.
constexpr int kDenseSamples = 9;
// A sample meets a side within this fraction of its own side's length ...
constexpr double kMatchRelativeToSide = 1e-6;
// ... and never closer than this fraction of the diagonal (round-off of far-off coordinates).
constexpr double kMatchRelativeToDiagonal = 1e-12;

// Side s of the parameter square at t in [0,1], from corner s to corner s+1 (patch.h, EDGES).
glm::dvec2 sideParameter(int s, double t) {
  switch (s) {
    case 0: return {t, 0.0};
    case 1: return {1.0, t};
    case 2: return {1.0 - t, 1.0};
    default: return {0.0, 1.0 - t};
  }
}

// A point of a side's boundary curve with its first derivative along t.
struct CurvePoint {
  Point position, tangent;
};
CurvePoint sideCurve(const Patch& patch, int s, double t) {
  const glm::dvec2 uv = sideParameter(s, t);
  const SurfacePoint p = evaluatePatch(patch, uv.x, uv.y);
  const Point tangent = s == 0 ? p.du : s == 1 ? p.dv : s == 2 ? -p.du : -p.dv;
  return {p.position, tangent};
}

struct Side {
  uint32_t patch = 0;
  int s = 0;
  std::array<Point, kDenseSamples> dense{};
  Point boxMin{0.0}, boxMax{0.0};
  double length = 0.0;  // of the polyline through the dense points
};

// The sides that can meet another: all four of a face-based patch, sides 0-2 of a PoleCap (side 3
// is the pole point), each with its dense points, a box inflated to hold the curve between them.
std::vector<Side> collectSides(const PatchSet& set) {
  std::vector<Side> sides;
  sides.reserve(set.patches.size() * 4);
  for (uint32_t i = 0; i < set.patches.size(); ++i) {
    const Patch& patch = set.patches[i];
    for (int s = 0; s < 4; ++s) {
      if (patch.kind == PatchKind::PoleCap && s == 3) continue;
      Side side{i, s};
      side.boxMin = Point(std::numeric_limits<double>::max());
      side.boxMax = Point(-std::numeric_limits<double>::max());
      for (int k = 0; k < kDenseSamples; ++k) {
        side.dense[k] = sideCurve(patch, s, double(k) / (kDenseSamples - 1)).position;
        side.boxMin = glm::min(side.boxMin, side.dense[k]);
        side.boxMax = glm::max(side.boxMax, side.dense[k]);
        if (k > 0) side.length += glm::distance(side.dense[k], side.dense[k - 1]);
      }
      const double slack = 0.25 * side.length;  // a cubic's bulge between dense points is far less
      side.boxMin -= Point(slack);
      side.boxMax += Point(slack);
      sides.push_back(side);
    }
  }
  return sides;
}

// A uniform grid of cells, each listing the sides whose (inflated) boxes overlap it.
class SideHash {
 public:
  SideHash(const std::vector<Side>& sides, Point lo, Point hi) : lo_(lo) {
    double meanLength = 0.0;
    for (const Side& side : sides) meanLength += side.length;
    meanLength /= double(std::max<size_t>(sides.size(), 1));
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-300});
    cell_ = std::max(meanLength, extent / double(1 << 20));
    for (uint32_t i = 0; i < sides.size(); ++i) {
      const glm::i64vec3 a = cellOf(sides[i].boxMin), b = cellOf(sides[i].boxMax);
      for (int64_t x = a.x; x <= b.x; ++x)
        for (int64_t y = a.y; y <= b.y; ++y)
          for (int64_t z = a.z; z <= b.z; ++z) cells_[key({x, y, z})].push_back(i);
    }
  }
  // The sides listed in the cell of p. [O(1)]
  const std::vector<uint32_t>& near(const Point& p) const {
    static const std::vector<uint32_t> kNone;
    const auto it = cells_.find(key(cellOf(p)));
    return it == cells_.end() ? kNone : it->second;
  }

 private:
  glm::i64vec3 cellOf(const Point& p) const {
    const Point c = glm::floor((p - lo_) / cell_);
    return glm::clamp(glm::i64vec3(c), glm::i64vec3(0), glm::i64vec3((1 << 21) - 1));
  }
  static uint64_t key(const glm::i64vec3& c) { return uint64_t(c.x) | uint64_t(c.y) << 21 | uint64_t(c.z) << 42; }
  Point lo_;
  double cell_ = 1.0;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

// The parameter t of the point of side's curve nearest to p: the best dense point, then
// Gauss-Newton on (c(t) - p) . c'(t) = 0, clamped to [0,1].
double projectOnSide(const PatchSet& set, const Side& side, const Point& p) {
  int best = 0;
  for (int k = 1; k < kDenseSamples; ++k)
    if (glm::distance(side.dense[k], p) < glm::distance(side.dense[best], p)) best = k;
  double t = double(best) / (kDenseSamples - 1);
  const Patch& patch = set.patches[side.patch];
  for (int iteration = 0; iteration < 40; ++iteration) {
    const CurvePoint c = sideCurve(patch, side.s, t);
    const double speed = glm::dot(c.tangent, c.tangent);
    if (!(speed > 0.0)) break;
    const double step = glm::dot(c.position - p, c.tangent) / speed;
    const double next = std::clamp(t - step, 0.0, 1.0);
    if (std::abs(next - t) < 1e-15) break;
    t = next;
  }
  return t;
}

// One compared point of a seam: the two patches' differences there.
struct SeamSample {
  double gap, dot, cross, gaussianJump, meanJumpSame, meanJumpFlipped;
};

struct SeamRecord {
  uint32_t a = 0, b = 0;  // side indices, a < b
  std::vector<SeamSample> samples;
};

SeamSample compare(const SurfacePoint& pa, const SurfacePoint& pb) {
  return {glm::distance(pa.position, pb.position), glm::dot(pa.normal, pb.normal),
          glm::length(glm::cross(pa.normal, pb.normal)), std::abs(pa.gaussian - pb.gaussian),
          std::abs(pa.mean - pb.mean), std::abs(pa.mean + pb.mean)};
}

// The model's largest |K| and |H| over a grid of interior parameters of every patch, and the box of
// those points.
void sampleCurvature(const PatchSet& set, int grid, ContinuityReport& report, Point& lo, Point& hi) {
  lo = Point(std::numeric_limits<double>::max());
  hi = Point(-std::numeric_limits<double>::max());
  for (const Patch& patch : set.patches)
    for (int i = 0; i < grid; ++i)
      for (int j = 0; j < grid; ++j) {
        const SurfacePoint p = evaluatePatch(patch, (i + 0.5) / grid, (j + 0.5) / grid);
        if (std::isfinite(p.gaussian)) report.maxAbsGaussian = std::max(report.maxAbsGaussian, std::abs(p.gaussian));
        if (std::isfinite(p.mean)) report.maxAbsMean = std::max(report.maxAbsMean, std::abs(p.mean));
        lo = glm::min(lo, p.position);
        hi = glm::max(hi, p.position);
      }
}

// Every seam's samples: each side's interior samples looking for the side through them.
struct SeamSearch {
  std::vector<SeamRecord> seams;
  std::vector<std::vector<uint32_t>> partners;  // per side, the distinct sides it meets
};

SeamSearch findSeams(const PatchSet& set, const std::vector<Side>& sides, const SideHash& hash, double diagonal,
                     int samplesPerSide) {
  SeamSearch search;
  search.partners.resize(sides.size());
  std::unordered_map<uint64_t, size_t> seamIndex;
  for (uint32_t ia = 0; ia < sides.size(); ++ia) {
    const Side& a = sides[ia];
    const Patch& patchA = set.patches[a.patch];
    const double tolerance = std::max(kMatchRelativeToSide * a.length, kMatchRelativeToDiagonal * diagonal);
    for (int k = 0; k < samplesPerSide; ++k) {
      const double t = (k + 0.5) / samplesPerSide;
      const glm::dvec2 uvA = sideParameter(a.s, t);
      const SurfacePoint pa = evaluatePatch(patchA, uvA.x, uvA.y);
      // The nearest side of another patch through this point.
      uint32_t best = UINT32_MAX;
      double bestDistance = tolerance, bestT = 0.0;
      for (uint32_t ib : hash.near(pa.position)) {
        const Side& b = sides[ib];
        if (b.patch == a.patch) continue;
        if (glm::any(glm::lessThan(pa.position, b.boxMin)) || glm::any(glm::greaterThan(pa.position, b.boxMax))) continue;
        const double tb = projectOnSide(set, b, pa.position);
        const double distance = glm::distance(sideCurve(set.patches[b.patch], b.s, tb).position, pa.position);
        if (distance <= bestDistance) best = ib, bestDistance = distance, bestT = tb;
      }
      if (best == UINT32_MAX) continue;
      const glm::dvec2 uvB = sideParameter(sides[best].s, bestT);
      const SurfacePoint pb = evaluatePatch(set.patches[sides[best].patch], uvB.x, uvB.y);
      // File the sample under the unordered pair of sides.
      const uint32_t lo = std::min(ia, best), hi = std::max(ia, best);
      const auto [it, added] = seamIndex.emplace(uint64_t(lo) << 32 | hi, search.seams.size());
      if (added) {
        search.seams.push_back({lo, hi, {}});
        search.partners[lo].push_back(hi);
        search.partners[hi].push_back(lo);
      }
      search.seams[it->second].samples.push_back(compare(pa, pb));
    }
  }
  return search;
}

// Folds one seam into its kind's stats: normals oriented by the sign of the mean dot product.
void addSeam(const SeamRecord& seam, bool tJunction, const ContinuityReport& report, SeamStats& stats) {
  double dotSum = 0.0;
  for (const SeamSample& s : seam.samples) dotSum += s.dot;
  const bool flipped = dotSum < 0.0;
  const double kScale = report.maxAbsGaussian > 0.0 ? report.maxAbsGaussian : 1.0;
  const double hScale = report.maxAbsMean > 0.0 ? report.maxAbsMean : 1.0;
  ++stats.count;
  stats.tJunctions += tJunction;
  stats.samples += seam.samples.size();
  for (const SeamSample& s : seam.samples) {
    stats.maxPositionGap = std::max(stats.maxPositionGap, s.gap / report.boxDiagonal);
    stats.maxNormalAngle = std::max(stats.maxNormalAngle, std::atan2(s.cross, flipped ? -s.dot : s.dot));
    stats.maxGaussianJump = std::max(stats.maxGaussianJump, s.gaussianJump / kScale);
    stats.maxMeanJump = std::max(stats.maxMeanJump, (flipped ? s.meanJumpFlipped : s.meanJumpSame) / hScale);
  }
}

}  // namespace

const char* seamKindName(SeamKind kind) { return kSeamKindNames[size_t(kind)]; }

SeamKind seamKindOf(PatchKind a, PatchKind b) { return kSeamKindTable[size_t(a)][size_t(b)]; }

const SeamStats* ContinuityReport::find(SeamKind kind) const {
  for (const SeamStats& s : seams)
    if (s.kind == kind) return &s;
  return nullptr;
}

ContinuityReport measureContinuity(const PatchSet& set, const ContinuityOptions& options) {
  ContinuityReport report;
  if (set.patches.empty()) return report;
  Point lo, hi;
  sampleCurvature(set, std::max(options.curvatureGrid, 1), report, lo, hi);
  report.boxDiagonal = std::max(glm::distance(lo, hi), std::numeric_limits<double>::min());

  // Sides, their hash, and the seams found through it.
  const std::vector<Side> sides = collectSides(set);
  Point sideLo(std::numeric_limits<double>::max()), sideHi(-std::numeric_limits<double>::max());
  for (const Side& side : sides) sideLo = glm::min(sideLo, side.boxMin), sideHi = glm::max(sideHi, side.boxMax);
  const SideHash hash(sides, sideLo, sideHi);
  const SeamSearch search = findSeams(set, sides, hash, report.boxDiagonal, std::max(options.samplesPerSide, 1));

  // Per kind: a T-junction is a seam one of whose sides meets more than one side.
  std::array<SeamStats, kSeamKindCount> byKind{};
  for (size_t k = 0; k < kSeamKindCount; ++k) byKind[k].kind = SeamKind(k);
  for (const SeamRecord& seam : search.seams) {
    const SeamKind kind = seamKindOf(set.patches[sides[seam.a].patch].kind, set.patches[sides[seam.b].patch].kind);
    const bool tJunction = search.partners[seam.a].size() > 1 || search.partners[seam.b].size() > 1;
    addSeam(seam, tJunction, report, byKind[size_t(kind)]);
  }
  for (const SeamStats& stats : byKind)
    if (stats.count > 0) report.seams.push_back(stats);
  for (const std::vector<uint32_t>& p : search.partners) report.boundarySides += p.empty();
  return report;
}

}  // namespace polarview
