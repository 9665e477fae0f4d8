// A PolyMesh as OpenSubdiv 3.5 takes it (bench's peer and the oracle test): the Far topology
// descriptor with the mesh's crease and corner tags (sharpness as float, as Far takes it), and the
// Sdc options of its boundary rule and creasing method. Header-only: the oracle test includes it.
#pragma once

#include <algorithm>
#include <vector>

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include "core/mesh/poly_mesh.h"

namespace polarview {

// The largest distance from a point of either set to the nearest point of the other (bench's and
// the oracle test's check of a non-manifold mesh, whose split refinement numbers its points its own
// way). Points sorted by x; each searched within the distance found so far plus `window`, so
// `window` at least the expected distance keeps it near-linear. [O(n log n) for close sets]
inline double pointSetDistance(std::vector<Point> a, std::vector<Point> b, double window) {
  auto byX = [](const Point& p, const Point& q) { return p.x < q.x; };
  std::sort(a.begin(), a.end(), byX);
  std::sort(b.begin(), b.end(), byX);
  double worst = 0.0;
  for (int pass = 0; pass < 2; ++pass) {
    const std::vector<Point>& from = pass == 0 ? a : b;
    const std::vector<Point>& to = pass == 0 ? b : a;
    for (const Point& p : from) {
      double best = INFINITY;
      for (double reach = window;; reach *= 16.0) {
        const auto lo = std::lower_bound(to.begin(), to.end(), Point(p.x - reach, 0, 0), byX);
        for (auto it = lo; it != to.end() && it->x <= p.x + reach; ++it) {
          const Point d = *it - p;
          best = std::min(best, std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z));
        }
        if (best <= reach || reach > 1e300) break;
      }
      worst = std::max(worst, best);
    }
  }
  return worst;
}

// Owns the arrays `descriptor` points into: keep it alive while a refiner is created from it.
struct OsdMeshDescriptor {
  std::vector<int> faceSizes;
  std::vector<Index> creasePairs, cornerIds;
  std::vector<float> creaseWeights, cornerWeights;
  std::vector<Index> holeIds;
  OpenSubdiv::Far::TopologyDescriptor descriptor;
  OpenSubdiv::Sdc::Options options;

  explicit OsdMeshDescriptor(const PolyMesh& mesh) {
    using OpenSubdiv::Sdc::Options;
    faceSizes.resize(size_t(mesh.faceCount()));
    for (Index f = 0; f < mesh.faceCount(); ++f) faceSizes[size_t(f)] = mesh.faceSize(f);
    for (const CreaseEdge& c : mesh.tags.creases) {
      creasePairs.insert(creasePairs.end(), {c.v0, c.v1});
      creaseWeights.push_back(float(c.sharpness));
    }
    for (const CornerVertex& c : mesh.tags.corners) {
      cornerIds.push_back(c.vertex);
      cornerWeights.push_back(float(c.sharpness));
    }
    descriptor.numVertices = mesh.vertexCount();
    descriptor.numFaces = mesh.faceCount();
    descriptor.numVertsPerFace = faceSizes.data();
    descriptor.vertIndicesPerFace = mesh.faceVerts.data();
    descriptor.numCreases = int(creaseWeights.size());
    descriptor.creaseVertexIndexPairs = creasePairs.data();
    descriptor.creaseWeights = creaseWeights.data();
    descriptor.numCorners = int(cornerWeights.size());
    descriptor.cornerVertexIndices = cornerIds.data();
    descriptor.cornerWeights = cornerWeights.data();
    holeIds = mesh.tags.holes;
    descriptor.numHoles = int(holeIds.size());
    descriptor.holeIndices = holeIds.data();
    options.SetVtxBoundaryInterpolation(mesh.tags.boundary == BoundaryInterpolation::EdgeAndCorner ? Options::VTX_BOUNDARY_EDGE_AND_CORNER
                                        : mesh.tags.boundary == BoundaryInterpolation::None        ? Options::VTX_BOUNDARY_NONE
                                                                                                   : Options::VTX_BOUNDARY_EDGE_ONLY);
    options.SetCreasingMethod(mesh.tags.creaseMethod == CreaseMethod::Chaikin ? Options::CREASE_CHAIKIN
                                                                              : Options::CREASE_UNIFORM);
    options.SetTriangleSubdivision(mesh.tags.triangles == TriangleSubdivision::Smooth ? Options::TRI_SUB_SMOOTH
                                                                                      : Options::TRI_SUB_CATMARK);
  }
  OsdMeshDescriptor(const OsdMeshDescriptor&) = delete;  // `descriptor` points into this object
  OsdMeshDescriptor& operator=(const OsdMeshDescriptor&) = delete;

  // An unrefined Catmull-Clark refiner of the mesh (nullptr when Far refuses it; the caller owns it).
  OpenSubdiv::Far::TopologyRefiner* create() const {
    using Factory = OpenSubdiv::Far::TopologyRefinerFactory<OpenSubdiv::Far::TopologyDescriptor>;
    return Factory::Create(descriptor, Factory::Options(OpenSubdiv::Sdc::SCHEME_CATMARK, options));
  }
};

}  // namespace polarview
