#include "pipeline/control_net.h"

#include <algorithm>

#include "core/mesh/manifold_split.h"

namespace polarview {

std::vector<NetSegment> controlNetSegments(const PolyMesh& mesh) {
  std::vector<NetSegment> segments;
  segments.reserve(mesh.faceVerts.size());
  for (Index f = 0; f < mesh.faceCount(); ++f) {
    const Index* loop = mesh.face(f);
    const Index k = mesh.faceSize(f);
    for (Index e = 0; e < k; ++e) {
      const Index a = loop[e], b = loop[(e + 1) % k];
      if (a != b) segments.push_back({std::min(a, b), std::max(a, b), 0.0f});
    }
  }
  auto byPair = [](const NetSegment& x, const NetSegment& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; };
  std::sort(segments.begin(), segments.end(), byPair);
  segments.erase(std::unique(segments.begin(), segments.end(), [](const NetSegment& x, const NetSegment& y) { return x.a == y.a && x.b == y.b; }),
                 segments.end());
  auto sharpen = [&](Index a, Index b, double sharpness) {
    const NetSegment key{std::min(a, b), std::max(a, b), 0.0f};
    const auto it = std::lower_bound(segments.begin(), segments.end(), key, byPair);
    if (it != segments.end() && it->a == key.a && it->b == key.b) it->sharpness = std::max(it->sharpness, float(sharpness));
  };
  for (const CreaseEdge& crease : mesh.tags.creases) sharpen(crease.v0, crease.v1, crease.sharpness);
  // Non-manifold edges: the split's infinitely sharp copies, named by their source vertices.
  const ManifoldSplit split = splitNonManifold(mesh);
  for (const CreaseEdge& crease : split.mesh.tags.creases)
    if (crease.sharpness >= kInfiniteSharpness)
      sharpen(split.sourceVertex[size_t(crease.v0)], split.sourceVertex[size_t(crease.v1)], crease.sharpness);
  return segments;
}

Point netSegmentColor(float sharpness) {
  if (!(sharpness > 0.0f)) return Point(0.1, 0.1, 0.1);
  const double t = std::min(double(sharpness) / 3.0, 1.0);
  return (1.0 - t) * Point(1.0, 0.6, 0.1) + t * Point(0.85, 0.05, 0.05);
}

}  // namespace polarview
