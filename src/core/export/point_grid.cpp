// Points found by position (see point_grid.h).
#include "core/export/point_grid.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace polarview {

namespace {

std::array<int64_t, 3> cellOf(const Point& scaled) {
  return {int64_t(std::floor(scaled.x)), int64_t(std::floor(scaled.y)), int64_t(std::floor(scaled.z))};
}

}  // namespace

bool PointGrid::usable(const Point& p) const {
  const Point q = scaled(p);
  return tolerance_ > 0.0 && std::abs(q.x) < 1e18 && std::abs(q.y) < 1e18 && std::abs(q.z) < 1e18;  // NaN: false
}

uint32_t PointGrid::find(const Point& p, const std::vector<Point>& points) const {
  if (!usable(p)) return kNone;
  const Point q = scaled(p);
  const Cell centre = cellOf(q);
  // Per axis, the cells that may hold a point within the tolerance: [low, high] of {-1, 0, 1}.
  std::array<int, 3> low{}, high{};
  for (int a = 0; a < 3; ++a) {
    const double inside = q[a] - std::floor(q[a]);  // in cells
    low[size_t(a)] = inside * kCellWidth <= 1.0 ? -1 : 0;
    high[size_t(a)] = (1.0 - inside) * kCellWidth <= 1.0 ? 1 : 0;
  }
  uint32_t best = kNone;
  double bestDistance = tolerance_;
  for (int dz = low[2]; dz <= high[2]; ++dz)
    for (int dy = low[1]; dy <= high[1]; ++dy)
      for (int dx = low[0]; dx <= high[0]; ++dx) {
        const auto it = cells_.find({centre[0] + dx, centre[1] + dy, centre[2] + dz});
        if (it == cells_.end()) continue;
        for (uint32_t id = it->second; id != kNone; id = next_[id]) {
          const double distance = glm::length(points[id] - p);
          if (distance <= bestDistance) best = id, bestDistance = distance;
        }
      }
  return best;
}

void PointGrid::insert(const Point& p, uint32_t id) {
  if (!usable(p)) return;
  if (next_.size() <= id) next_.resize(size_t(id) + 1, kNone);
  uint32_t& head = cells_.try_emplace(cellOf(scaled(p)), kNone).first->second;
  next_[id] = head;
  head = id;
}

}  // namespace polarview
