#include "app/bench_peer.h"

#include <algorithm>
#include <chrono>
#include <vector>

#ifdef POLARVIEW_HAVE_OSD
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#endif

namespace polarview::cli {

#ifdef POLARVIEW_HAVE_OSD
namespace {

// The vertex type OpenSubdiv's PrimvarRefiner interpolates.
struct OsdPoint {
  double x = 0, y = 0, z = 0;
  void Clear() { x = y = z = 0; }
  void AddWithWeight(const OsdPoint& p, float w) { x += w * p.x; y += w * p.y; z += w * p.z; }
};

double medianOf(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

std::optional<PeerTiming> benchPeer(const PolyMesh& mesh, int levels, int reps) {
  using namespace OpenSubdiv;
  std::vector<int> faceSizes(mesh.faceCount());
  for (Index f = 0; f < mesh.faceCount(); ++f) faceSizes[f] = mesh.faceSize(f);
  Far::TopologyDescriptor desc;
  desc.numVertices = mesh.vertexCount();
  desc.numFaces = mesh.faceCount();
  desc.numVertsPerFace = faceSizes.data();
  desc.vertIndicesPerFace = mesh.faceVerts.data();
  Sdc::Options sdc;  // OpenSubdiv's own tools: boundary edges only, uniform creases, Catmark triangles
  sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  sdc.SetCreasingMethod(Sdc::Options::CREASE_UNIFORM);
  sdc.SetTriangleSubdivision(Sdc::Options::TRI_SUB_CATMARK);

  PeerTiming timing;
  timing.name = "opensubdiv-3.5";
  std::vector<double> topo, pos;
  for (int rep = 0; rep < reps; ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    Far::TopologyRefiner* refiner = Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, sdc));
    if (!refiner) return std::nullopt;
    refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(levels));
    topo.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());

    std::vector<OsdPoint> points(refiner->GetNumVerticesTotal());
    for (Index v = 0; v < mesh.vertexCount(); ++v) points[v] = {mesh.points[v].x, mesh.points[v].y, mesh.points[v].z};
    t0 = std::chrono::steady_clock::now();
    Far::PrimvarRefiner primvar(*refiner);
    OsdPoint* src = points.data();
    for (int level = 1; level <= levels; ++level) {
      OsdPoint* dst = src + refiner->GetLevel(level - 1).GetNumVertices();
      primvar.Interpolate(level, src, dst);
      src = dst;
    }
    pos.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    timing.outVertices = refiner->GetLevel(levels).GetNumVertices();
    timing.outFaces = refiner->GetLevel(levels).GetNumFaces();
    delete refiner;
  }
  timing.topologyMs = medianOf(topo);
  timing.positionsMs = medianOf(pos);
  return timing;
}
#else
std::optional<PeerTiming> benchPeer(const PolyMesh&, int, int) { return std::nullopt; }
#endif

}  // namespace polarview::cli
