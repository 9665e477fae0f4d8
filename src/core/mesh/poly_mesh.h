// PolyMesh: the flat polygon mesh every stage of polarview reads and writes.
// Faces are stored CSR-style (faceStart / faceVerts) so refinement never allocates per face.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace polarview {

using Index = int32_t;
using Point = glm::dvec3;

struct PolyMesh {
  std::vector<Point> points;       // vertex positions
  std::vector<Index> faceStart{0}; // faceCount()+1 offsets into faceVerts
  std::vector<Index> faceVerts;    // counter-clockwise vertex loops, 0-based
  // Optional: 1-based OBJ line of each face (empty when the mesh was not read from a file).
  std::vector<int> faceLine;

  Index vertexCount() const { return static_cast<Index>(points.size()); }
  Index faceCount() const { return static_cast<Index>(faceStart.size()) - 1; }
  Index faceSize(Index f) const { return faceStart[f + 1] - faceStart[f]; }
  const Index* face(Index f) const { return faceVerts.data() + faceStart[f]; }

  // Appends a face given by its vertex loop. [O(k)]
  void addFace(std::initializer_list<Index> loop) { addFace(loop.begin(), loop.size()); }
  void addFace(const Index* loop, size_t k) {
    faceVerts.insert(faceVerts.end(), loop, loop + k);
    faceStart.push_back(static_cast<Index>(faceVerts.size()));
  }
};

}  // namespace polarview
