// The surface at a picked point (see point_readout.h).
#include "pipeline/point_readout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace polarview {
namespace {

const char* kindName(PatchKind kind) {
  switch (kind) {
    case PatchKind::Regular: return "regular B-spline";
    case PatchKind::Boundary: return "boundary B-spline";
    case PatchKind::PolarRing: return "polar ring";
    case PatchKind::PoleCap: return "pole cap (Taylor expansion (32))";
    case PatchKind::EndCap: return "end cap (Catmull-Clark extraordinary vertex)";
  }
  return "?";
}

// Whether `p` lies in the box of the patch's position-valued control points grown by `tolerance`
// (a B-spline or Bezier patch lies in its control points' hull; the cap's slots 10, 11 are data).
bool mayHold(const Patch& patch, const Point& p, double tolerance) {
  Point lo(INFINITY), hi(-INFINITY);
  for (int k = 0; k < 16; ++k) {
    if (!isPositionPoint(patch.kind, k)) continue;
    lo = glm::min(lo, patch.cp[k]);
    hi = glm::max(hi, patch.cp[k]);
  }
  lo += patch.origin, hi += patch.origin;
  if (patch.kind == PatchKind::PoleCap) {  // the cap bulges past its pole and boundary: grow by its size
    const double size = glm::length(hi - lo);
    lo -= Point(size), hi += Point(size);
  }
  return glm::all(glm::lessThanEqual(lo - Point(tolerance), p)) && glm::all(glm::lessThanEqual(p, hi + Point(tolerance)));
}

// The (u, v) of `patch` nearest `p`: the best of a 5 x 5 grid, then Newton steps on the squared
// distance (Gauss-Newton: the surface's second derivatives dropped), clamped to the unit square.
std::pair<double, double> nearestParameters(const Patch& patch, const Point& p) {
  double bestU = 0.5, bestV = 0.5, best = INFINITY;
  for (int a = 0; a <= 4; ++a)
    for (int b = 0; b <= 4; ++b) {
      const double d = glm::length(evaluatePatch(patch, a / 4.0, b / 4.0).position - p);
      if (d < best) best = d, bestU = a / 4.0, bestV = b / 4.0;
    }
  double u = bestU, v = bestV;
  for (int step = 0; step < 12; ++step) {
    const SurfacePoint s = evaluatePatch(patch, u, v);
    const Point r = s.position - p;
    const double a = glm::dot(s.du, s.du), b = glm::dot(s.du, s.dv), c = glm::dot(s.dv, s.dv);
    const double gu = glm::dot(s.du, r), gv = glm::dot(s.dv, r);
    const double det = a * c - b * b;
    if (!(std::abs(det) > 0.0)) break;
    const double du = (c * gu - b * gv) / det, dv = (a * gv - b * gu) / det;
    u = std::clamp(u - du, 0.0, 1.0);
    v = std::clamp(v - dv, 0.0, 1.0);
    if (std::abs(du) + std::abs(dv) < 1e-14) break;
  }
  return {u, v};
}

}  // namespace

std::string PointReadout::text() const {
  char buffer[800];
  std::snprintf(buffer, sizeof buffer,
                "position (%.12g, %.12g, %.12g)\nnormal (%.6f, %.6f, %.6f)\nK %.9g  H %.9g\nk1 %.9g  k2 %.9g\n"
                "%s patch %zu, level %d%s, (u, v) = (%.6f, %.6f)",
                point.position.x, point.position.y, point.position.z, point.normal.x, point.normal.y, point.normal.z,
                point.gaussian, point.mean, k1, k2, kindName(kind), patchIndex, level,
                ring >= 0 ? (", ring " + std::to_string(ring)).c_str() : "", u, v);
  return buffer;
}

std::optional<PointReadout> readSurfacePoint(const std::vector<Patch>& patches, const Point& picked, double tolerance) {
  std::optional<PointReadout> best;
  for (size_t k = 0; k < patches.size(); ++k) {
    const Patch& patch = patches[k];
    if (!mayHold(patch, picked, tolerance)) continue;
    const auto [u, v] = nearestParameters(patch, picked);
    const SurfacePoint s = evaluatePatch(patch, u, v);
    const double distance = glm::length(s.position - picked);
    if (distance > tolerance || (best && distance >= best->distance)) continue;
    PointReadout r;
    r.patchIndex = k;
    r.u = u, r.v = v;
    r.distance = distance;
    r.point = s;
    const double root = std::sqrt(std::max(s.mean * s.mean - s.gaussian, 0.0));
    r.k1 = s.mean + root;
    r.k2 = s.mean - root;
    r.kind = patch.kind;
    r.level = patch.level;
    r.ring = patch.ring;
    r.pole = patch.pole;
    best = r;
  }
  return best;
}

}  // namespace polarview
