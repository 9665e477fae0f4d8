// Level of detail for drawing (see level_of_detail.h).
#include "pipeline/level_of_detail.h"

#include "core/mesh/constants.h"
#include "core/subdiv/parallel_for.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

#include <glm/geometric.hpp>

namespace polarview {

namespace {

constexpr size_t kMostFeatures = 4096;  // beyond: every k-th (only the nearest matters)

// A patch's size: the edges of its face (B-spline kinds: control points 5, 6, 9, 10 are the face's
// neighbourhood, their spacing the face's edge), or the extent of its position points (caps).
double patchSize(const Patch& patch) {
  if (patch.kind == PatchKind::Regular || patch.kind == PatchKind::Boundary || patch.kind == PatchKind::PolarRing) {
    const Point& a = patch.cp[5];
    const Point& b = patch.cp[6];
    const Point& c = patch.cp[10];
    const Point& d = patch.cp[9];
    return std::max({glm::distance(a, b), glm::distance(b, c), glm::distance(c, d), glm::distance(d, a)});
  }
  Point lo(0.0), hi(0.0);
  bool first = true;
  for (int k = 0; k < 16; ++k) {
    if (!isPositionPoint(patch.kind, k)) continue;
    lo = first ? patch.cp[k] : glm::min(lo, patch.cp[k]);
    hi = first ? patch.cp[k] : glm::max(hi, patch.cp[k]);
    first = false;
  }
  return glm::length(hi - lo);
}

Point patchCentre(const Patch& patch) {
  return patch.origin + (patch.kind == PatchKind::PoleCap ? patch.cp[0] : 0.25 * (patch.cp[5] + patch.cp[6] + patch.cp[9] + patch.cp[10]));
}

}  // namespace

DetailSizes detailSizes(const std::vector<Patch>& patches) {
  DetailSizes sizes;
  // Per patch its size and centre, split over the cores (C2PS 12: 246k patches, 440 bytes each);
  // the maxima and the features then in patch order, as one thread would find them.
  std::vector<double> size(patches.size());
  parallelRanges(Index(patches.size()), threadsFor(patches.size()), [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p) size[size_t(p)] = patchSize(patches[size_t(p)]);
  });
  int finest = 0;
  for (size_t p = 0; p < patches.size(); ++p) {
    const int level = patches[p].level;
    if (size_t(level) >= sizes.levelSize.size()) sizes.levelSize.resize(size_t(level) + 1, 0.0);
    if (std::isfinite(size[p])) sizes.levelSize[size_t(level)] = std::max(sizes.levelSize[size_t(level)], size[p]);
    finest = std::max(finest, level);
  }
  if (sizes.levelSize.empty()) return sizes;
  // One feature point per grid cell of four finest patches.
  const double cell = 4.0 * std::max(sizes.levelSize[size_t(finest)], 1e-300);
  std::vector<Point> centre(patches.size());
  parallelRanges(Index(patches.size()), threadsFor(patches.size()), [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p)
      if (patches[size_t(p)].level == finest) centre[size_t(p)] = patchCentre(patches[size_t(p)]);
  });
  std::unordered_set<uint64_t> occupied;
  for (size_t p = 0; p < patches.size(); ++p) {
    if (patches[p].level != finest || !std::isfinite(glm::dot(centre[p], centre[p]))) continue;
    uint64_t key = 1469598103934665603ull;
    for (int c = 0; c < 3; ++c) key = (key ^ uint64_t(int64_t(std::floor(centre[p][c] / cell)))) * 1099511628211ull;
    if (occupied.insert(key).second) sizes.features.push_back(centre[p]);
  }
  if (sizes.features.size() > kMostFeatures) {
    const size_t step = (sizes.features.size() + kMostFeatures - 1) / kMostFeatures;
    std::vector<Point> kept;
    for (size_t k = 0; k < sizes.features.size(); k += step) kept.push_back(sizes.features[k]);
    sizes.features = std::move(kept);
  }
  return sizes;
}

int levelToDraw(const DetailSizes& sizes, int level, const OrbitCamera& camera, double viewportHeight, double pixels) {
  if (sizes.levelSize.empty() || sizes.features.empty() || level <= 0) return level;
  // Pixels per world unit at depth z: H / (2 z tan(fov / 2)); orthographic: at the target's depth.
  const double perDepth = viewportHeight / (2.0 * std::tan(camera.fovDeg * kPi / 360.0));
  const Point eye = camera.eye(), forward = camera.forward();
  double pixelsPerUnit = 0.0;
  for (const Point& feature : sizes.features) {
    const double depth = camera.orthographic ? camera.distance : glm::dot(feature - eye, forward);
    if (!(depth > 0.0)) continue;  // behind the eye: not drawn
    pixelsPerUnit = std::max(pixelsPerUnit, perDepth / depth);
  }
  if (!std::isfinite(pixelsPerUnit)) return level;
  const int deepest = std::min(level, int(sizes.levelSize.size()) - 1);
  // The part of level m's set that differs from level L's, the cap or end caps closing it at a
  // feature, spans about two of its patches (a cap's diameter is twice its ring's width). A level
  // without patches in the set (every face of it refined further, e.g. level 0 of a mesh whose
  // n-gons make every vertex extraordinary) has no size to tell: its set is end caps throughout.
  for (int m = 0; m < deepest; ++m)
    if (sizes.levelSize[size_t(m)] > 0.0 && 2.0 * sizes.levelSize[size_t(m)] * pixelsPerUnit < pixels) return m;
  return level;
}

}  // namespace polarview
