// Points found by position within a tolerance: the welding of the exports' seams and corners
// (tessellation.cpp, cad_topology.cpp). A uniform grid of cells kCellWidth tolerances wide, each
// listing its points (a chain through next_). A query looks at its own cell and, per axis, the
// neighbour it lies within the tolerance of: one cell for most points, at most 8 (cells one
// tolerance wide would need all 27 around it; that cost most of an export: docs/performance.md).
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "core/mesh/poly_mesh.h"

namespace polarview {

class PointGrid {
 public:
  static constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

  // Cells measured from `origin` (a point near the data keeps the cell indices small).
  PointGrid(const Point& origin, double tolerance) : origin_(origin), tolerance_(tolerance) {}

  // The nearest of `points` (the ids inserted index it) within the tolerance of `p`, or kNone.
  // [O(1) expected]
  uint32_t find(const Point& p, const std::vector<Point>& points) const;
  // Makes point `id` at `p` findable. Non-finite points, or points too far from the origin for the
  // cells' integer indices, are never found. [O(1) expected]
  void insert(const Point& p, uint32_t id);

 private:
  using Cell = std::array<int64_t, 3>;
  struct CellHash {
    size_t operator()(const Cell& c) const {
      return size_t(uint64_t(c[0]) * 0x9E3779B97F4A7C15ull ^ uint64_t(c[1]) * 0xC2B2AE3D27D4EB4Full ^
                    uint64_t(c[2]) * 0x165667B19E3779F9ull);
    }
  };
  static constexpr double kCellWidth = 4.0;  // in tolerances
  bool usable(const Point& p) const;
  Point scaled(const Point& p) const { return (p - origin_) / (kCellWidth * tolerance_); }  // in cells

  Point origin_;
  double tolerance_;
  std::unordered_map<Cell, uint32_t, CellHash> cells_;  // cell -> its last point
  std::vector<uint32_t> next_;                          // point -> the point before it in its cell
};

}  // namespace polarview
