#include "core/spline/ring_curvature.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/spline/patch.h"
#include "core/spline/spline_ring.h"
#include "core/subdiv/bps.h"
#include "core/subdiv/c2ps.h"
#include "core/subdiv/rts.h"

namespace polarview {
namespace {

constexpr int kRingLinks = 5;  // links 0..5: what spline ring (6) reads

PolarGrid innerLinks(const PolarGrid& grid) {
  if (grid.links <= kRingLinks) return grid;
  PolarGrid inner(grid.n, kRingLinks);
  inner.pole = grid.pole;
  std::copy(grid.ring.begin(), grid.ring.begin() + size_t(kRingLinks) * grid.n, inner.ring.begin());
  return inner;
}

constexpr int kSpokeSamples = 8;  // intervals per patch row along a spoke

// K along one spoke at `turn` (a fraction of a full turn) over a ring's patches: row 1 (links 4 to
// 3), then row 0 (links 3 to 2), outside in.
std::vector<double> kAlongSpoke(const std::vector<Patch>& patches, int n, double turn) {
  const double at = turn * n;
  const int j = std::min(int(at), n - 1);
  std::vector<double> k;
  for (int row = 1; row >= 0; --row)
    for (int a = kSpokeSamples; a >= (row == 1 ? 1 : 0); --a)
      k.push_back(evaluatePatch(patches[size_t(row * n + j)], double(a) / kSpokeSamples, at - j).gaussian);
  return k;
}

// Sign changes of the successive differences of `k`, steps under `flat` skipped.
int signChanges(const std::vector<double>& k, double flat) {
  int changes = 0, last = 0;
  for (size_t i = 1; i < k.size(); ++i) {
    const double step = k[i] - k[i - 1];
    if (std::abs(step) <= flat) continue;
    const int sign = step > 0 ? 1 : -1;
    changes += last != 0 && sign != last;
    last = sign;
  }
  return changes;
}

double largestAbsK(const std::vector<RingCurvature>& rings) {
  double largest = 0.0;
  for (const RingCurvature& r : rings) largest = std::max({largest, std::abs(r.minK), std::abs(r.maxK)});
  return largest;
}

}  // namespace

int spokeSignChanges(const std::vector<RingCurvature>& rings, double poleK) {
  if (rings.empty() || rings.front().kAlongSpokes.empty()) return 0;
  const double flat = 1e-9 * largestAbsK(rings);
  int changes = 0;
  for (size_t s = 0; s < rings.front().kAlongSpokes.size(); ++s) {
    std::vector<double> spoke;
    for (const RingCurvature& r : rings) spoke.insert(spoke.end(), r.kAlongSpokes[s].begin(), r.kAlongSpokes[s].end());
    if (!std::isnan(poleK)) spoke.push_back(poleK);
    changes += signChanges(spoke, flat);
  }
  return changes;
}

std::vector<RingCurvature> ringCurvatures(PolarGrid grid, Scheme scheme, bool uniformFirstStep, int rings, double poleK,
                                          double poleH, const Point& poleNormal, int samples, int angleSamples,
                                          int spokes) {
  if (grid.links < 2) throw std::invalid_argument("ringCurvatures: a pole needs links 0..2");
  samples = std::max(samples, 2);
  std::vector<RingCurvature> out;
  for (int m = 1; m <= rings; ++m) {
    const bool first = uniformFirstStep && m == 1;
    const SchemeTraits& traits = schemeTraits(scheme);
    if (!traits.polar()) throw std::invalid_argument("ringCurvatures: C2PS, RTS or BPS");
    grid = traits.refineGrid(grid, first);
    grid = innerLinks(grid);
    // Pole-relative from here on (the rules are affine: K and H do not move): rounding then scales
    // with the ring, not with the model's offset from the origin.
    const Point pole = grid.pole;
    grid.pole = Point(0.0);
    for (Point& p : grid.ring) p -= pole;
    if (grid.links < kRingLinks) continue;  // a 2-link input has its first ring at m = 2
    RingCurvature rc;
    rc.m = m;
    rc.valence = grid.n;
    rc.minK = rc.minH = std::numeric_limits<double>::infinity();
    rc.maxK = rc.maxH = -std::numeric_limits<double>::infinity();
    std::vector<Patch> patches = splineRing(grid, m);
    for (Patch& patch : patches) {
      // Relative to one of its own points: the derivatives are then differences of small numbers
      // (a deep ring is 2^-m of the model, far from the origin); K and H do not move.
      const Point origin = patch.cp[5];
      for (Point& p : patch.cp) p -= origin;
      for (int a = 0; a < samples; ++a)
        for (int b = 0; b < samples; ++b) {
          const SurfacePoint sp = evaluatePatch(patch, double(a) / (samples - 1), double(b) / (samples - 1));
          // The ring's normal points outwards; H takes the sign of the pole's normal.
          const double H = glm::dot(sp.normal, poleNormal) < 0.0 ? -sp.mean : sp.mean;
          rc.minK = std::min(rc.minK, sp.gaussian);
          rc.maxK = std::max(rc.maxK, sp.gaussian);
          rc.minH = std::min(rc.minH, H);
          rc.maxH = std::max(rc.maxH, H);
        }
    }
    // The middle circle: row 0's outer edge (u = 1, link 3), column j at v = angle n - j.
    for (int a = 0; a < angleSamples; ++a) {
      const double at = double(a) / angleSamples * grid.n;
      const int j = std::min(int(at), grid.n - 1);
      rc.kAlongAngle.push_back(evaluatePatch(patches[size_t(j)], 1.0, at - j).gaussian);
    }
    for (int s = 0; s < spokes; ++s) rc.kAlongSpokes.push_back(kAlongSpoke(patches, grid.n, double(s) / spokes));
    rc.maxAbsDeltaK = std::max(std::abs(rc.maxK - poleK), std::abs(rc.minK - poleK));
    rc.maxAbsDeltaH = std::max(std::abs(rc.maxH - poleH), std::abs(rc.minH - poleH));
    out.push_back(rc);
  }
  const double flat = 1e-9 * largestAbsK(out);
  for (RingCurvature& rc : out)
    for (const std::vector<double>& spoke : rc.kAlongSpokes) rc.spokeSignChanges += signChanges(spoke, flat);
  return out;
}

}  // namespace polarview
