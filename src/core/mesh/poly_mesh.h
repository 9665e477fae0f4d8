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

// Subdivision tags: what an OBJ file's `t` tags carry, in OpenSubdiv's conventions (its
// regression shapes and Far::TopologyRefinerFactory): crease edges and corner vertices with a
// sharpness, hole faces, and the Sdc::Options they select.

// Sdc::Options::VtxBoundaryInterpolation; `t interpolateboundary 1/0/0 N` with N = 0, 1, 2.
enum class BoundaryInterpolation { None, EdgeAndCorner, EdgeOnly };
// Sdc::Options::CreasingMethod; `t creasemethod 0/0/1 normal|chaikin`.
enum class CreaseMethod { Uniform, Chaikin };
// Sdc::Options::TriangleSubdivision; `t smoothtriangles 0/0/1 catmark|smooth`.
enum class TriangleSubdivision { Catmark, Smooth };

// OpenSubdiv's sharpness at and above which a feature is infinitely sharp (Sdc::Crease::SHARPNESS_INFINITE).
constexpr double kInfiniteSharpness = 10.0;

// An edge (v0 < v1, 0-based vertex ids) with a sharpness > 0.
struct CreaseEdge {
  Index v0, v1;
  double sharpness;
  bool operator==(const CreaseEdge& o) const { return v0 == o.v0 && v1 == o.v1 && sharpness == o.sharpness; }
};

// A vertex (0-based) with a sharpness > 0.
struct CornerVertex {
  Index vertex;
  double sharpness;
  bool operator==(const CornerVertex& o) const { return vertex == o.vertex && sharpness == o.sharpness; }
};

// What the tags say, already validated and merged: each edge, corner and hole at most once (a
// later tag overrides an earlier one, as in OpenSubdiv), sorted, sharpness 0 left out. The
// defaults are OpenSubdiv's tools' (and polarview's Catmull-Clark's) options.
struct SubdivTags {
  std::vector<CreaseEdge> creases;    // sorted by (v0, v1)
  std::vector<CornerVertex> corners;  // sorted by vertex
  std::vector<Index> holes;           // 0-based face ids, sorted
  BoundaryInterpolation boundary = BoundaryInterpolation::EdgeOnly;
  CreaseMethod creaseMethod = CreaseMethod::Uniform;
  TriangleSubdivision triangles = TriangleSubdivision::Catmark;

  bool hasSharpFeatures() const { return !creases.empty() || !corners.empty(); }
  // Whether the options are the defaults above.
  bool defaultOptions() const {
    return boundary == BoundaryInterpolation::EdgeOnly && creaseMethod == CreaseMethod::Uniform &&
           triangles == TriangleSubdivision::Catmark;
  }
  bool empty() const { return !hasSharpFeatures() && holes.empty() && defaultOptions(); }
};

struct PolyMesh {
  std::vector<Point> points;       // vertex positions
  std::vector<Index> faceStart{0}; // faceCount()+1 offsets into faceVerts
  std::vector<Index> faceVerts;    // counter-clockwise vertex loops, 0-based
  // Optional: 1-based OBJ line of each face (empty when the mesh was not read from a file).
  // 64-bit: a file may have more than 2^31 lines.
  std::vector<int64_t> faceLine;
  // Creases, corners, holes and options from the file's `t` tags (above); indices refer
  // to this mesh, so a mesh with other vertices or faces (a refined one) starts without them.
  SubdivTags tags;

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
