#include "core/mesh/ngon_to_fan.h"

#include <algorithm>

namespace polarview {

namespace {

bool isHole(const PolyMesh& mesh, Index face) {
  return std::binary_search(mesh.tags.holes.begin(), mesh.tags.holes.end(), face);
}

bool becomesFan(const PolyMesh& mesh, Index face, int minSides) {
  return mesh.faceSize(face) >= minSides && !isHole(mesh, face);
}

}  // namespace

int countFanFaces(const PolyMesh& mesh, int minSides) {
  int count = 0;
  for (Index face = 0; face < mesh.faceCount(); ++face) count += becomesFan(mesh, face, minSides);
  return count;
}

FanConversion convertNgonsToFans(const PolyMesh& mesh, int minSides) {
  FanConversion out;
  out.mesh.points = mesh.points;
  out.mesh.tags = mesh.tags;
  out.mesh.tags.holes.clear();
  const bool hasLines = mesh.faceLine.size() == size_t(mesh.faceCount());
  auto keepLine = [&](Index face) {
    if (hasLines) out.mesh.faceLine.push_back(mesh.faceLine[size_t(face)]);
  };
  for (Index face = 0; face < mesh.faceCount(); ++face) {
    const Index* loop = mesh.face(face);
    const Index n = mesh.faceSize(face);
    if (!becomesFan(mesh, face, minSides)) {
      // Hole ids follow the new numbering (faces before this one may have become several).
      if (isHole(mesh, face)) out.mesh.tags.holes.push_back(out.mesh.faceCount());
      out.mesh.addFace(loop, size_t(n));
      keepLine(face);
      continue;
    }
    // The centroid of the corners (Blender's fan centre); the triangles keep the face's winding.
    Point centre(0.0);
    for (Index c = 0; c < n; ++c) centre += mesh.points[size_t(loop[c])];
    out.mesh.points.push_back(centre / double(n));
    const Index centreId = Index(out.mesh.points.size() - 1);
    for (Index c = 0; c < n; ++c) {
      out.mesh.addFace({loop[c], loop[(c + 1) % n], centreId});
      keepLine(face);
    }
    out.centres.push_back(centreId);
    out.faces.push_back(face);
  }
  return out;
}

}  // namespace polarview
