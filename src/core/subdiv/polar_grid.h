// PolarGrid: a polar configuration's points laid out by link and column (paper Section 3, Fig. 7).
// Link 0 is the polar vertex q00; link i >= 1 is the ring q_{i,0..n-1}; j is taken modulo n.
// Columns run in the direction in which the fan triangles (q00, q_{1j}, q_{1,j+1}) are
// counter-clockwise, so p1 x p2 is the outward normal.
#pragma once

#include <vector>

#include "core/mesh/poly_mesh.h"

namespace polarview {

struct PolarGrid {
  int n = 0;      // valence of the polar vertex
  int links = 0;  // number of rings of points around the pole (links 1..links)
  Point pole{};   // q00
  std::vector<Point> ring;  // ring[(i-1)*n + j] = q_{ij}, i = 1..links

  PolarGrid() = default;
  PolarGrid(int valence, int linkCount) : n(valence), links(linkCount), ring(size_t(valence) * linkCount) {}
  Point& q(int i, int j) { return ring[size_t(i - 1) * n + wrap(j)]; }
  const Point& q(int i, int j) const { return ring[size_t(i - 1) * n + wrap(j)]; }
  int wrap(int j) const { return ((j % n) + n) % n; }
};

}  // namespace polarview
