// BPS rules (weights from the authors' group's polar_subdiv.m; see bps.h for the provenance).
#include "core/subdiv/bps.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/mesh/constants.h"
#include "core/subdiv/polar_rules.h"

namespace polarview::bps {

namespace {

// n gamma_g = beta + cos + 1/2 cos2 + 1/8 cos3 (c^2 = 1/2 + 1/2 cos2, c^3 = 3/4 c + 1/4 cos3).
constexpr std::array<double, kMaxLinkFrequency + 1> kGammaModes{0.0, 1.0, 0.5, 0.125};

void checkGrid(const PolarGrid& grid, int minLinks, const char* what) {
  if (grid.n < 3 || grid.links < minLinks || grid.ring.size() != size_t(grid.n) * grid.links)
    throw std::invalid_argument(std::string("bps::") + what + ": needs valence >= 3 and links >= " +
                                std::to_string(minLinks));
}

void link1FromSums(const Point& pole, const LinkFourierSums& sums, int n, Point* out) {
  Point constant = (1.0 - kBeta) * pole + kBeta * sums.mean;
  for (int j = 0; j < n; ++j) out[j] = constant + sums.trigonometricPart(kGammaModes, unitCircle(j, n));
}

}  // namespace

double weightGamma(int g, int n) {
  double c = std::cos(kTwoPi * g / n);
  return (kBeta - 0.5 + 0.625 * c + c * c + 0.5 * c * c * c) / n;
}

Point refinePole(const PolarGrid& grid) {
  checkGrid(grid, 1, "refinePole");
  return (1.0 - kAlpha) * grid.pole + kAlpha * linkMean(&grid.q(1, 0), grid.n);
}

void refineLink1(const PolarGrid& grid, Point* out) {
  checkGrid(grid, 1, "refineLink1");
  link1FromSums(grid.pole, linkFourierSums(&grid.q(1, 0), grid.n, 3), grid.n, out);
}

void refineLink2(const PolarGrid& grid, Point* out) {
  checkGrid(grid, 2, "refineLink2");
  for (int j = 0; j < grid.n; ++j) out[j] = radialEvenRule(grid.pole, grid.q(1, j), grid.q(2, j));
}

PolarGrid refineGrid(const PolarGrid& grid) {
  checkGrid(grid, 2, "refineGrid");
  PolarGrid fine(grid.n, 2 * grid.links - 1);
  LinkFourierSums sums = linkFourierSums(&grid.q(1, 0), grid.n, 3);
  fine.pole = (1.0 - kAlpha) * grid.pole + kAlpha * sums.mean;
  link1FromSums(grid.pole, sums, grid.n, &fine.q(1, 0));
  refineLink2(grid, &fine.q(2, 0));
  refineOuterLinksRadially(grid.ring.data(), grid.n, grid.links, &fine.q(3, 0));
  return fine;
}

}  // namespace polarview::bps
