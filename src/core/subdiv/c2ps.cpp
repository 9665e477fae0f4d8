// C2PS rules: Myles & Peters 2009, Section 3, (1)-(5), (29). See c2ps.h.
#include "core/subdiv/c2ps.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/mesh/constants.h"
#include "core/subdiv/polar_rules.h"

namespace polarview::c2ps {

namespace {

void checkGrid(const PolarGrid& grid, int minLinks, const char* what) {
  if (grid.n < 3 || grid.links < minLinks || grid.ring.size() != size_t(grid.n) * grid.links)
    throw std::invalid_argument(std::string("c2ps::") + what + ": needs valence >= 3 and links >= " +
                                std::to_string(minLinks));
}

// (2) at every new column k, from the 1-link's Fourier sums.
void link1FromSums(const Point& pole, const LinkFourierSums& sums, int n, Point* out) {
  Point constant = 0.5 * pole + 0.5 * sums.mean;  // 1/2 q00 + (1/n) sum_h 1/2 q1h
  for (int k = 0; k < 2 * n; ++k) out[k] = constant + sums.trigonometricPart(kWeightBModes, unitCircle(k, 2 * n));
}

// (3), or its Section-6 variant, from the periodically refined links 1 and 2.
void link2FromRefinedLinks(const Point& pole, const LinkFourierSums& sums, const Point* refined1,
                           const Point* refined2, int n, bool uniformFirstStep, Point* out) {
  if (uniformFirstStep) {
    for (int k = 0; k < 2 * n; ++k) out[k] = radialEvenRule(pole, refined1[k], refined2[k]);
    return;
  }
  for (int k = 0; k < 2 * n; ++k)
    out[k] = (11.0 / 12.0) * refined1[k] + (1.0 / 12.0) * refined2[k] +
             sums.trigonometricPart(kWeightDModes, unitCircle(k, 2 * n));
}

}  // namespace

double weightB(double g, int n) {
  double t = kTwoPi * g / n;
  return (0.5 + std::cos(t) + 0.5 * std::cos(2.0 * t)) / n;
}

double weightD(double g, int n) { return -std::cos(kTwoPi * g / n) / (6.0 * n); }

Point refinePole(const PolarGrid& grid) {
  checkGrid(grid, 1, "refinePole");
  return polarVertexRule(grid.pole, &grid.q(1, 0), grid.n);
}

void refineLink1(const PolarGrid& grid, Point* out) {
  checkGrid(grid, 1, "refineLink1");
  link1FromSums(grid.pole, linkFourierSums(&grid.q(1, 0), grid.n, 2), grid.n, out);
}

void refineLink2(const PolarGrid& grid, Point* out, bool uniformFirstStep) {
  checkGrid(grid, 2, "refineLink2");
  int n = grid.n;
  std::vector<Point> refined(size_t(4) * n);
  refinePeriodicLink(&grid.q(1, 0), n, refined.data());
  refinePeriodicLink(&grid.q(2, 0), n, refined.data() + 2 * n);
  link2FromRefinedLinks(grid.pole, linkFourierSums(&grid.q(1, 0), n, 1), refined.data(), refined.data() + 2 * n, n,
                        uniformFirstStep, out);
}

PolarGrid refineGrid(const PolarGrid& grid, bool uniformFirstStep) {
  checkGrid(grid, 2, "refineGrid");
  int n = grid.n, links = grid.links, width = 2 * n;
  PolarGrid fine(width, 2 * links - 1);

  // Every old link refined periodically by (5): the tensor-product rules act on these.
  std::vector<Point> refined(size_t(links) * width);
  for (int i = 1; i <= links; ++i) refinePeriodicLink(&grid.q(i, 0), n, refined.data() + size_t(i - 1) * width);

  // Links 0, 1, 2 by the polar rules (1)-(3).
  LinkFourierSums sums = linkFourierSums(&grid.q(1, 0), n, 2);
  fine.pole = 0.75 * grid.pole + 0.25 * sums.mean;
  link1FromSums(grid.pole, sums, n, &fine.q(1, 0));
  link2FromRefinedLinks(grid.pole, sums, refined.data(), refined.data() + width, n, uniformFirstStep, &fine.q(2, 0));

  // Links 3..2K-1 by uniform bi-3 subdivision (29): radial rules on the refined links.
  refineOuterLinksRadially(refined.data(), width, links, &fine.q(3, 0));
  return fine;
}

}  // namespace polarview::c2ps
