// Eigencoefficients and Taylor expansion at the pole (Myles & Peters 2009, (26), (32)). See pole_taylor.h.
#include "core/spline/pole_taylor.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "core/subdiv/polar_rules.h"

namespace polarview {

TaylorCoefficients poleTaylorCoefficients(const PolarGrid& grid, Scheme scheme) {
  const SchemeTraits& traits = schemeTraits(scheme);
  if (traits.taylorOrder == 0)
    throw std::logic_error("poleTaylorCoefficients: " + std::string(traits.label) + " has no polar Taylor expansion");
  if (grid.n < 3 || grid.links < 1 || grid.ring.size() != size_t(grid.n) * grid.links)
    throw std::invalid_argument("poleTaylorCoefficients: needs valence >= 3 and a 1-link");

  LinkFourierSums sums = linkFourierSums(&grid.q(1, 0), grid.n, 2);
  TaylorCoefficients t;
  // Tangent directions: w1 = w2 = [0, 2, 0..] (Table 1), the same for all three schemes.
  t.p[1] = 2.0 * sums.cosSum[1];
  t.p[2] = 2.0 * sums.sinSum[1];
  if (traits.taylorOrder == 1) {
    // BPS's dominant block [[5/8, 3/8], [3/8, 5/8]] has left eigenvector [1/2, 1/2]; its 1/4
    // eigenvector is not radially quadratic, so only the tangent plane is meaningful.
    t.p[0] = 0.5 * grid.pole + 0.5 * sums.mean;
    t.order = 1;
    return t;
  }
  t.p[0] = (2.0 / 3.0) * grid.pole + (1.0 / 3.0) * sums.mean;  // w0 = 1/3 [2, 1, 0..]
  t.p[3] = sums.mean - grid.pole;                               // w3 = [-1, 1, 0..]
  t.p[4] = 3.0 * sums.cosSum[2];                                // w4 = w5 = [0, 3, 0..]
  t.p[5] = 3.0 * sums.sinSum[2];
  t.order = 2;
  return t;
}

TaylorJet evaluateTaylor(const TaylorCoefficients& t, double x, double y) {
  const auto& p = t.p;
  TaylorJet jet;
  jet.position = p[0] + x * p[1] + y * p[2];
  jet.x = p[1];
  jet.y = p[2];
  if (t.order >= 2) {
    jet.position += (x * x + y * y) * p[3] + (x * x - y * y) * p[4] + (2.0 * x * y) * p[5];
    jet.x += 2.0 * x * (p[3] + p[4]) + 2.0 * y * p[5];
    jet.y += 2.0 * y * (p[3] - p[4]) + 2.0 * x * p[5];
    jet.xx = 2.0 * (p[3] + p[4]);
    jet.yy = 2.0 * (p[3] - p[4]);
    jet.xy = 2.0 * p[5];
  }
  return jet;
}

PoleDifferential analyzePole(const TaylorCoefficients& t) {
  PoleDifferential d;
  d.limit = t.p[0];
  // Work on p1..p5 scaled by a power of two to about unit size: E G - F^2 holds fourth powers of
  // the coordinates, which overflow from about 1e77 (and underflow below 1e-77). Power-of-two
  // scaling is exact, so the normal is unchanged and K, H are rescaled exactly at the end.
  double size = 0.0;
  for (int k = 1; k < 6; ++k)
    for (int i = 0; i < 3; ++i) size = std::max(size, std::abs(t.p[k][i]));
  int exponent = 0;
  if (std::isfinite(size) && size > 0.0) std::frexp(size, &exponent);
  TaylorCoefficients unit = t;
  for (int k = 1; k < 6; ++k)
    for (int i = 0; i < 3; ++i) unit.p[k][i] = std::ldexp(t.p[k][i], -exponent);
  TaylorJet jet = evaluateTaylor(unit, 0.0, 0.0);
  Point cross = glm::cross(jet.x, jet.y);
  double crossLength = glm::length(cross);
  if (!(crossLength > 0.0)) return d;  // no tangent plane: normal and curvature undefined
  d.normal = cross / crossLength;
  if (t.order < 2) return d;

  // First and second fundamental forms (docs/rings-and-pole.md, Curvature at the pole), of the
  // scaled expansion.
  double E = glm::dot(jet.x, jet.x), F = glm::dot(jet.x, jet.y), G = glm::dot(jet.y, jet.y);
  double L = glm::dot(jet.xx, d.normal), M = glm::dot(jet.xy, d.normal), N = glm::dot(jet.yy, d.normal);
  // E G - F^2 = |x_x x x_y|^2 (Lagrange's identity), without the cancellation of the difference
  // (nearly parallel p1, p2 made it 0: K and H came out inf with the normal defined; found by
  // tests/fuzz).
  const double area2 = crossLength * crossLength;
  // Curvature scales as 1/length (H) and 1/length^2 (K); beyond a double it is left undefined.
  const double K = std::ldexp((L * N - M * M) / area2, -2 * exponent);
  const double H = std::ldexp((E * N - 2.0 * F * M + G * L) / (2.0 * area2), -exponent);
  if (!std::isfinite(K) || !std::isfinite(H)) return d;
  d.gaussian = K;
  d.mean = H;
  d.curvatureDefined = true;
  return d;
}

}  // namespace polarview
