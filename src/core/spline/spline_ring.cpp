#include "core/spline/spline_ring.h"

#include <algorithm>
#include <stdexcept>

namespace polarview {

std::vector<Patch> splineRing(const PolarGrid& grid, int m) {
  if (grid.links < 5) throw std::invalid_argument("splineRing: a spline ring needs links 1..5");
  const int n = grid.n;
  std::vector<Patch> ring(size_t(2) * n);
  for (int row = 0; row < 2; ++row) {
    for (int j = 0; j < n; ++j) {
      Patch& patch = ring[size_t(row) * n + j];
      // cp[4*jj + ii]: ii along u = links row+1 .. row+4, jj along v = columns j-1 .. j+2.
      for (int jj = 0; jj < 4; ++jj)
        for (int ii = 0; ii < 4; ++ii) patch.cp[4 * jj + ii] = grid.q(row + 1 + ii, j - 1 + jj);
      patch.kind = PatchKind::PolarRing;
      patch.level = uint8_t(std::clamp(m, 0, 255));
      patch.ring = m;
      patch.pole = 0;
      patch.face = -1;
    }
  }
  return ring;
}

}  // namespace polarview
