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

#include "core/subdiv/parallel_for.h"

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

// Points per side (ends included) for its polyline in the hash and the projection's first guess.
constexpr int kDenseSamples = 9;
// A patch evaluation in threadsFor's units of work (parallel_for.h: ~32,768 units pay for a thread).
constexpr size_t kWorkPerEvaluation = 64;
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
  std::array<Point, kDenseSamples> dense{};  // at t = k / (kDenseSamples - 1)
  double length = 0.0;  // of the polyline through the dense points
  double slack = 0.0;   // how far the curve may stray from that polyline (with the match tolerance)
};

// The tolerance within which a sample of a side of this length meets another side.
double matchTolerance(double sideLength, double diagonal) {
  return std::max(kMatchRelativeToSide * sideLength, kMatchRelativeToDiagonal * diagonal);
}

double distanceToSegment(const Point& p, const Point& a, const Point& b) {
  const Point ab = b - a;
  const double squared = glm::dot(ab, ab);
  const double t = squared > 0.0 ? std::clamp(glm::dot(p - a, ab) / squared, 0.0, 1.0) : 0.0;
  return glm::distance(p, a + t * ab);
}

// The sides that can meet another: all four of a face-based patch, sides 0-2 of a PoleCap (side 3
// is the pole point), each with its dense points; the slack is twice the largest distance of a
// segment's parameter midpoint from the segment (a cubic strays from its chord about that much).
// Split over the threads by patches, joined in patch order.
std::vector<Side> collectSides(const PatchSet& set, double diagonal) {
  const Index count = Index(set.patches.size());
  const unsigned parts = threadsFor(size_t(count) * 4 * (2 * kDenseSamples) * kWorkPerEvaluation);
  std::vector<std::vector<Side>> collected(parts);
  runParts(parts, [&](unsigned part) {
    std::vector<Side>& sides = collected[part];
    for (uint32_t i = uint32_t(partBound(count, parts, part)); i < uint32_t(partBound(count, parts, part + 1)); ++i) {
      const Patch& patch = set.patches[i];
      for (int s = 0; s < 4; ++s) {
        if (patch.kind == PatchKind::PoleCap && s == 3) continue;
        Side side{i, s};
        constexpr double kStep = 1.0 / (kDenseSamples - 1);
        double stray = 0.0;
        for (int k = 0; k < kDenseSamples; ++k) {
          side.dense[k] = sideCurve(patch, s, k * kStep).position;
          if (k == 0) continue;
          side.length += glm::distance(side.dense[k], side.dense[k - 1]);
          const Point middle = sideCurve(patch, s, (k - 0.5) * kStep).position;
          stray = std::max(stray, distanceToSegment(middle, side.dense[k - 1], side.dense[k]));
        }
        side.slack = 2.0 * stray + matchTolerance(side.length, diagonal);
        sides.push_back(side);
      }
    }
  });
  std::vector<Side> sides;
  sides.reserve(set.patches.size() * 4);
  for (const std::vector<Side>& part : collected) sides.insert(sides.end(), part.begin(), part.end());
  return sides;
}

// A hierarchical grid of the sides' segments: each segment (with its side's slack) is listed in the
// cells of the one level whose cell size (a power of two) exceeds its extent, so it sits in at most
// 8 cells, and a cell lists only segments of about its size. Caps' radial sides all meet at the
// pole: a uniform grid would list thousands of them in the pole's cell.
class SegmentHash {
 public:
  SegmentHash(const std::vector<Side>& sides, double coordinateScale) {
    // Cells no finer than the coordinates' resolution, so cell indices stay within 2^53.
    const int finest = std::ilogb(std::max(coordinateScale, std::numeric_limits<double>::min())) - 50;
    for (uint32_t i = 0; i < sides.size(); ++i)
      for (uint32_t k = 0; k + 1 < kDenseSamples; ++k) {
        const Point lo = glm::min(sides[i].dense[k], sides[i].dense[k + 1]) - Point(sides[i].slack);
        const Point hi = glm::max(sides[i].dense[k], sides[i].dense[k + 1]) + Point(sides[i].slack);
        const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, std::numeric_limits<double>::min()});
        const int level = std::max(std::ilogb(extent) + 1, finest);
        levels_.push_back(level);
        const glm::i64vec3 a = cellOf(lo, level), b = cellOf(hi, level);
        for (int64_t x = a.x; x <= b.x; ++x)
          for (int64_t y = a.y; y <= b.y; ++y)
            for (int64_t z = a.z; z <= b.z; ++z) cells_[{level, {x, y, z}}].push_back(i * kDenseSamples + k);
      }
    std::sort(levels_.begin(), levels_.end());
    levels_.erase(std::unique(levels_.begin(), levels_.end()), levels_.end());
  }
  // Calls visit(side, segment) for every segment listed in a cell holding p. [O(levels + hits)]
  template <class Visit>
  void forEachNear(const Point& p, Visit&& visit) const {
    for (int level : levels_) {
      const auto it = cells_.find({level, cellOf(p, level)});
      if (it == cells_.end()) continue;
      for (uint32_t entry : it->second) visit(entry / kDenseSamples, entry % kDenseSamples);
    }
  }

 private:
  struct Cell {
    int level;
    glm::i64vec3 index;
    bool operator==(const Cell& o) const { return level == o.level && index == o.index; }
  };
  struct CellHash {
    size_t operator()(const Cell& c) const {
      uint64_t h = uint64_t(c.level) * 0x9E3779B97F4A7C15ull;
      for (int64_t v : {c.index.x, c.index.y, c.index.z}) h = (h ^ uint64_t(v)) * 0xBF58476D1CE4E5B9ull;
      return size_t(h ^ (h >> 31));
    }
  };
  static glm::i64vec3 cellOf(const Point& p, int level) {
    return glm::i64vec3(std::floor(std::ldexp(p.x, -level)), std::floor(std::ldexp(p.y, -level)),
                        std::floor(std::ldexp(p.z, -level)));
  }
  std::vector<int> levels_;
  std::unordered_map<Cell, std::vector<uint32_t>, CellHash> cells_;
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
  // The gap by std::hypot: on a 1e-150 model a round-off gap (1e-166) squared leaves double's range.
  const Point gap = pa.position - pb.position;
  return {std::hypot(gap.x, gap.y, gap.z), glm::dot(pa.normal, pb.normal),
          glm::length(glm::cross(pa.normal, pb.normal)), std::abs(pa.gaussian - pb.gaussian),
          std::abs(pa.mean - pb.mean), std::abs(pa.mean + pb.mean)};
}

// The model's largest |K| and |H| over a grid of interior parameters of every patch, and the box of
// those points (maxima and minima: the same on any number of threads).
void sampleCurvature(const PatchSet& set, int grid, ContinuityReport& report, Point& lo, Point& hi) {
  struct Extremes {
    double gaussian = 0.0, mean = 0.0;
    Point lo{std::numeric_limits<double>::max()}, hi{-std::numeric_limits<double>::max()};
  };
  const Index count = Index(set.patches.size());
  const unsigned parts = threadsFor(size_t(count) * size_t(grid * grid) * kWorkPerEvaluation);
  std::vector<Extremes> extremes(parts);
  runParts(parts, [&](unsigned k) {
    Extremes& out = extremes[k];
    for (Index n = partBound(count, parts, k); n < partBound(count, parts, k + 1); ++n)
      for (int i = 0; i < grid; ++i)
        for (int j = 0; j < grid; ++j) {
          const SurfacePoint p = evaluatePatch(set.patches[size_t(n)], (i + 0.5) / grid, (j + 0.5) / grid);
          if (std::isfinite(p.gaussian)) out.gaussian = std::max(out.gaussian, std::abs(p.gaussian));
          if (std::isfinite(p.mean)) out.mean = std::max(out.mean, std::abs(p.mean));
          out.lo = glm::min(out.lo, p.position);
          out.hi = glm::max(out.hi, p.position);
        }
  });
  lo = Point(std::numeric_limits<double>::max());
  hi = Point(-std::numeric_limits<double>::max());
  for (const Extremes& e : extremes) {
    report.maxAbsGaussian = std::max(report.maxAbsGaussian, e.gaussian);
    report.maxAbsMean = std::max(report.maxAbsMean, e.mean);
    lo = glm::min(lo, e.lo);
    hi = glm::max(hi, e.hi);
  }
}

// Every seam's samples: each side's interior samples looking for the side through them.
struct SeamSearch {
  std::vector<SeamRecord> seams;
  std::vector<std::vector<uint32_t>> partners;  // per side, the distinct sides it meets
};

// A sample of side `a` that found side `b` through it, and the two patches' comparison there.
struct SeamHit {
  uint32_t a, b;
  SeamSample sample;
};

// The hits of side ia's samples, appended to `hits` in sample order. Reads only. [O(samples x near sides)]
void searchSide(const PatchSet& set, const std::vector<Side>& sides, const SegmentHash& hash, double diagonal,
                int samplesPerSide, uint32_t ia, std::vector<uint32_t>& candidates, std::vector<SeamHit>& hits) {
  const Side& a = sides[ia];
  const Patch& patchA = set.patches[a.patch];
  const double tolerance = matchTolerance(a.length, diagonal);
  for (int k = 0; k < samplesPerSide; ++k) {
    const double t = (k + 0.5) / samplesPerSide;
    const glm::dvec2 uvA = sideParameter(a.s, t);
    const SurfacePoint pa = evaluatePatch(patchA, uvA.x, uvA.y);
    // The sides of other patches whose polylines pass within their slack of this point ...
    candidates.clear();
    hash.forEachNear(pa.position, [&](uint32_t ib, uint32_t segment) {
      const Side& b = sides[ib];
      if (b.patch != a.patch && distanceToSegment(pa.position, b.dense[segment], b.dense[segment + 1]) <= b.slack + tolerance)
        candidates.push_back(ib);
    });
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    // ... and of them the nearest whose curve passes within the tolerance.
    uint32_t best = UINT32_MAX;
    double bestDistance = tolerance, bestT = 0.0;
    for (uint32_t ib : candidates) {
      const double tb = projectOnSide(set, sides[ib], pa.position);
      const double distance = glm::distance(sideCurve(set.patches[sides[ib].patch], sides[ib].s, tb).position, pa.position);
      if (distance <= bestDistance) best = ib, bestDistance = distance, bestT = tb;
    }
    if (best == UINT32_MAX) continue;
    const glm::dvec2 uvB = sideParameter(sides[best].s, bestT);
    const SurfacePoint pb = evaluatePatch(set.patches[sides[best].patch], uvB.x, uvB.y);
    hits.push_back({ia, best, compare(pa, pb)});
  }
}

// The sides are searched in blocks, each split over the threads, its hits filed in side order: the
// same seams, samples and order as one thread's.
SeamSearch findSeams(const PatchSet& set, const std::vector<Side>& sides, const SegmentHash& hash, double diagonal,
                     int samplesPerSide) {
  SeamSearch search;
  search.partners.resize(sides.size());
  std::unordered_map<uint64_t, size_t> seamIndex;
  constexpr uint32_t kBlock = 8192;  // sides a block: bounds the hits kept at once
  const uint32_t sideCount = uint32_t(sides.size());
  for (uint32_t first = 0; first < sideCount; first += kBlock) {
    const Index count = Index(std::min(kBlock, sideCount - first));
    const unsigned parts = threadsFor(size_t(count) * size_t(samplesPerSide) * 4 * kWorkPerEvaluation);
    std::vector<std::vector<SeamHit>> hits(parts);
    runParts(parts, [&](unsigned k) {
      std::vector<uint32_t> candidates;
      for (Index i = partBound(count, parts, k); i < partBound(count, parts, k + 1); ++i)
        searchSide(set, sides, hash, diagonal, samplesPerSide, first + uint32_t(i), candidates, hits[k]);
    });
    // File each sample under the unordered pair of sides.
    for (const std::vector<SeamHit>& part : hits)
      for (const SeamHit& hit : part) {
        const uint32_t lo = std::min(hit.a, hit.b), hi = std::max(hit.a, hit.b);
        const auto [it, added] = seamIndex.emplace(uint64_t(lo) << 32 | hi, search.seams.size());
        if (added) {
          search.seams.push_back({lo, hi, {}});
          search.partners[lo].push_back(hi);
          search.partners[hi].push_back(lo);
        }
        search.seams[it->second].samples.push_back(hit.sample);
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
  const std::vector<Side> sides = collectSides(set, report.boxDiagonal);
  const Point far = glm::max(glm::abs(lo), glm::abs(hi));
  const SegmentHash hash(sides, std::max({far.x, far.y, far.z, report.boxDiagonal}));
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
