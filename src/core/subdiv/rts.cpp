// RTS rules: Myles & Peters 2009, Section 5.2, Definition 1, (9)-(12). See rts.h.
#include "core/subdiv/rts.h"

#include <stdexcept>
#include <string>

#include "core/subdiv/polar_rules.h"

namespace polarview::rts {

namespace {

void checkGrid(const PolarGrid& grid, int minLinks, const char* what) {
  if (grid.n < 3 || grid.links < minLinks || grid.ring.size() != size_t(grid.n) * grid.links)
    throw std::invalid_argument(std::string("rts::") + what + ": needs valence >= 3 and links >= " +
                                std::to_string(minLinks));
}

// (10) at every column j (angle j/n: no half shift, no periodic refinement).
void link1FromSums(const Point& pole, const LinkFourierSums& sums, int n, Point* out) {
  Point constant = 0.5 * pole + 0.5 * sums.mean;
  for (int j = 0; j < n; ++j) out[j] = constant + sums.trigonometricPart(kWeightBModes, unitCircle(j, n));
}

// (11), or the Section-6 first step (the 2-link rule of BPS).
void link2FromSums(const PolarGrid& grid, const LinkFourierSums& sums, bool uniformFirstStep, Point* out) {
  int n = grid.n;
  const Point* link1 = &grid.q(1, 0);
  const Point* link2 = &grid.q(2, 0);
  if (uniformFirstStep) {
    for (int j = 0; j < n; ++j) out[j] = radialEvenRule(grid.pole, link1[j], link2[j]);
    return;
  }
  for (int j = 0; j < n; ++j)
    out[j] = (11.0 / 12.0) * link1[j] + (1.0 / 12.0) * link2[j] +
             sums.trigonometricPart(kWeightDModes, unitCircle(j, n));
}

}  // namespace

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
  link2FromSums(grid, linkFourierSums(&grid.q(1, 0), grid.n, 1), uniformFirstStep, out);
}

PolarGrid refineGrid(const PolarGrid& grid, bool uniformFirstStep) {
  checkGrid(grid, 2, "refineGrid");
  PolarGrid fine(grid.n, 2 * grid.links - 1);
  LinkFourierSums sums = linkFourierSums(&grid.q(1, 0), grid.n, 2);
  fine.pole = 0.75 * grid.pole + 0.25 * sums.mean;                        // (9)
  link1FromSums(grid.pole, sums, grid.n, &fine.q(1, 0));                   // (10)
  link2FromSums(grid, sums, uniformFirstStep, &fine.q(2, 0));              // (11)
  refineOuterLinksRadially(grid.ring.data(), grid.n, grid.links, &fine.q(3, 0));  // (12)
  return fine;
}

}  // namespace polarview::rts
