// Crease edges and corners from lists (sharp_features.h).
#include "core/mesh/sharp_features.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

#include "core/mesh/input_error.h"

namespace polarview {

namespace {

uint64_t edgeKey(Index a, Index b) { return (uint64_t(uint32_t(std::min(a, b))) << 32) | uint32_t(std::max(a, b)); }

void checkSharpness(double sharpness, const std::string& what, const std::string& source) {
  if (!std::isfinite(sharpness) || sharpness < 0)
    throw InputError(source, 0, what + ": sharpness " + std::to_string(sharpness) + " (it must be finite and >= 0)");
}

}  // namespace

void setSharpFeatures(PolyMesh& mesh, const std::vector<CreaseEdge>& creases, const std::vector<CornerVertex>& corners,
                      const std::string& source) {
  std::unordered_set<uint64_t> faceEdges;
  if (!creases.empty())
    for (Index f = 0; f < mesh.faceCount(); ++f)
      for (Index i = 0, k = mesh.faceSize(f); i < k; ++i) faceEdges.insert(edgeKey(mesh.face(f)[i], mesh.face(f)[(i + 1) % k]));
  auto inRange = [&](Index v) { return v >= 0 && v < mesh.vertexCount(); };
  for (size_t e = 0; e < creases.size(); ++e) {
    const CreaseEdge& c = creases[e];
    const std::string what = "crease " + std::to_string(e) + " (" + std::to_string(c.v0) + ", " + std::to_string(c.v1) + ")";
    if (!inRange(c.v0) || !inRange(c.v1))
      throw InputError(source, 0, what + ": vertex id out of range (" + std::to_string(mesh.vertexCount()) + " vertices, 0-based)");
    if (!faceEdges.count(edgeKey(c.v0, c.v1))) throw InputError(source, 0, what + ": not an edge of any face");
    checkSharpness(c.sharpness, what, source);
  }
  for (size_t k = 0; k < corners.size(); ++k) {
    const std::string what = "corner " + std::to_string(k) + " (vertex " + std::to_string(corners[k].vertex) + ")";
    if (!inRange(corners[k].vertex))
      throw InputError(source, 0, what + ": vertex id out of range (" + std::to_string(mesh.vertexCount()) + " vertices, 0-based)");
    checkSharpness(corners[k].sharpness, what, source);
  }
  // The last entry of each edge and vertex, in id order; sharpness 0 is no feature.
  std::vector<CreaseEdge> edges;
  for (const CreaseEdge& c : creases) edges.push_back({std::min(c.v0, c.v1), std::max(c.v0, c.v1), c.sharpness});
  std::stable_sort(edges.begin(), edges.end(), [](const CreaseEdge& a, const CreaseEdge& b) {
    return std::make_pair(a.v0, a.v1) < std::make_pair(b.v0, b.v1);
  });
  std::vector<CornerVertex> vertices = corners;
  std::stable_sort(vertices.begin(), vertices.end(), [](const CornerVertex& a, const CornerVertex& b) { return a.vertex < b.vertex; });
  mesh.tags.creases.clear();
  for (size_t i = 0; i < edges.size(); ++i)
    if ((i + 1 == edges.size() || edges[i + 1].v0 != edges[i].v0 || edges[i + 1].v1 != edges[i].v1) && edges[i].sharpness > 0)
      mesh.tags.creases.push_back(edges[i]);
  mesh.tags.corners.clear();
  for (size_t i = 0; i < vertices.size(); ++i)
    if ((i + 1 == vertices.size() || vertices[i + 1].vertex != vertices[i].vertex) && vertices[i].sharpness > 0)
      mesh.tags.corners.push_back(vertices[i]);
}

}  // namespace polarview
