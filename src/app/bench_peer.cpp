#include "app/bench_peer.h"

#include "core/subdiv/parallel_for.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <fstream>
#include <string>
#include <vector>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#ifdef POLARVIEW_HAVE_OSD
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/stencilTable.h>

#include "app/osd_descriptor.h"
#endif

namespace polarview::cli {

#ifdef POLARVIEW_HAVE_OSD
namespace {

// The vertex type OpenSubdiv's PrimvarRefiner interpolates (float weights: its fast path; double
// weights for the equality check).
template <class Weight>
struct OsdPoint {
  double x = 0, y = 0, z = 0;
  void Clear() { x = y = z = 0; }
  void AddWithWeight(const OsdPoint& p, Weight w) { x += w * p.x; y += w * p.y; z += w * p.z; }
};

// Interpolates `points` (level 0 filled, all levels' room) through every level; returns the finest.
template <class Weight, class Refiner>
const OsdPoint<Weight>* interpolateLevels(const OpenSubdiv::Far::TopologyRefiner& refiner, int levels,
                                          std::vector<OsdPoint<Weight>>& points) {
  Refiner primvar(refiner);
  OsdPoint<Weight>* src = points.data();
  for (int level = 1; level <= levels; ++level) {
    OsdPoint<Weight>* dst = src + refiner.GetLevel(level - 1).GetNumVertices();
    primvar.Interpolate(level, src, dst);
    src = dst;
  }
  return src;
}

double medianOf(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

// OpenSubdiv's vertex of each of check's finest vertices (-1: none): face and vertex points
// through their parents, edge points through the parent edge's ends (the libraries number edges
// differently), child faces through the parent face and the corner, rotated to start alike.
std::vector<int> finestVertexMap(const Refinement& check, const OpenSubdiv::Far::TopologyRefiner& refiner) {
  const PolyMesh& base = check.level(0).mesh;
  std::vector<int> map(base.points.size()), faceMap(size_t(base.faceCount())), shift(faceMap.size(), 0);
  for (size_t v = 0; v < map.size(); ++v) map[v] = int(v);
  for (size_t f = 0; f < faceMap.size(); ++f) faceMap[f] = int(f);
  for (int m = 1; m < check.levelCount(); ++m) {
    const PolyMesh& parent = check.level(m - 1).mesh;
    const MeshTopology& topo = check.level(m - 1).topology;
    const OpenSubdiv::Far::TopologyLevel& osd = refiner.GetLevel(m - 1);
    const OpenSubdiv::Far::TopologyLevel& osdChild = refiner.GetLevel(m);
    std::vector<int> child(size_t(ccChildVertexCount(topo)), -1);
    for (Index f = 0; f < topo.faceCount; ++f) child[ccFacePoint(topo, f)] = osd.GetFaceChildVertex(faceMap[f]);
    for (Index e = 0; e < topo.edgeCount; ++e) {
      const int osdEdge = osd.FindEdge(map[topo.edgeVerts[2 * e]], map[topo.edgeVerts[2 * e + 1]]);
      child[ccEdgePoint(topo, e)] = osdEdge < 0 ? -1 : osd.GetEdgeChildVertex(osdEdge);
    }
    for (Index v = 0; v < topo.vertexCount; ++v) child[ccVertexPoint(topo, v)] = osd.GetVertexChildVertex(map[v]);
    const PolyMesh& childMesh = check.level(m).mesh;
    std::vector<int> childFaceMap(size_t(childMesh.faceCount()), -1), childShift(childFaceMap.size(), 0);
    for (Index c = 0; c < childMesh.faceCount(); ++c) {  // child face c: parent corner c
      const Index f = topo.cornerFace[c], n = parent.faceSize(f);
      const int osdFace = osd.GetFaceChildFaces(faceMap[f])[(shift[f] + (c - parent.faceStart[f])) % n];
      const auto verts = osdChild.GetFaceVertices(osdFace);
      const int first = child[childMesh.face(c)[0]];
      childFaceMap[c] = osdFace;
      childShift[c] = int(std::find(verts.begin(), verts.end(), first) - verts.begin());
    }
    map.swap(child);
    faceMap.swap(childFaceMap);
    shift.swap(childShift);
  }
  return map;
}

std::optional<PeerTiming> benchPeer(const PolyMesh& mesh, int levels, int reps, const Refinement* check) {
  using namespace OpenSubdiv;
  // The mesh as Far takes it, with its tags (built once, outside the timed region).
  const OsdMeshDescriptor described(mesh);

  PeerTiming timing;
  timing.name = "opensubdiv-3.5";
  const bool peakReset = resetPeakResident();
  std::vector<double> topo, pos;
  for (int rep = 0; rep < reps; ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    Far::TopologyRefiner* refiner = described.create();
    if (!refiner) return std::nullopt;
    refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(levels));
    topo.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());

    std::vector<OsdPoint<float>> points(refiner->GetNumVerticesTotal());
    for (Index v = 0; v < mesh.vertexCount(); ++v) points[v] = {mesh.points[v].x, mesh.points[v].y, mesh.points[v].z};
    t0 = std::chrono::steady_clock::now();
    interpolateLevels<float, Far::PrimvarRefiner>(*refiner, levels, points);
    pos.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    timing.outVertices = refiner->GetLevel(levels).GetNumVertices();
    timing.outFaces = refiner->GetLevel(levels).GetNumFaces();
    if (check && rep + 1 == reps && check->splitInput()) {
      // A non-manifold mesh: ours is refined split (manifold_split.h); the merged points against
      // OpenSubdiv's as point sets.
      std::vector<OsdPoint<double>> exact(refiner->GetNumVerticesTotal());
      for (Index v = 0; v < mesh.vertexCount(); ++v) exact[v] = {mesh.points[v].x, mesh.points[v].y, mesh.points[v].z};
      const OsdPoint<double>* finest = interpolateLevels<double, Far::PrimvarRefinerReal<double>>(*refiner, levels, exact);
      std::vector<Point> theirs(timing.outVertices);
      for (size_t v = 0; v < theirs.size(); ++v) theirs[v] = Point(finest[v].x, finest[v].y, finest[v].z);
      const PolyMesh ours = check->outputMesh();
      timing.checked = ours.faceCount() == Index(timing.outFaces);
      timing.maxDifference = timing.checked ? pointSetDistance(ours.points, theirs, 1e-9) : INFINITY;
    } else if (check && rep + 1 == reps && check->finest().mesh.points.size() == timing.outVertices) {
      std::vector<OsdPoint<double>> exact(refiner->GetNumVerticesTotal());
      for (Index v = 0; v < mesh.vertexCount(); ++v) exact[v] = {mesh.points[v].x, mesh.points[v].y, mesh.points[v].z};
      const OsdPoint<double>* finest = interpolateLevels<double, Far::PrimvarRefinerReal<double>>(*refiner, levels, exact);
      const std::vector<int> map = finestVertexMap(*check, *refiner);
      const std::vector<Point>& ours = check->finest().mesh.points;
      timing.checked = true;
      for (size_t v = 0; v < ours.size(); ++v) {
        if (map[v] < 0) {  // an edge OpenSubdiv does not have: not the same mesh
          timing.maxDifference = std::numeric_limits<double>::infinity();
          break;
        }
        const OsdPoint<double>& q = finest[map[v]];
        timing.maxDifference = std::max({timing.maxDifference, std::abs(ours[v].x - q.x), std::abs(ours[v].y - q.y),
                                         std::abs(ours[v].z - q.z)});
      }
    }
    delete refiner;
  }
  if (peakReset) timing.peakRssMb = peakResidentMegabytes();
  timing.topologyMs = medianOf(topo);
  timing.positionsMs = medianOf(pos);
  return timing;
}

struct AdaptivePeer::Impl {
  const PolyMesh& mesh;
  int levels;
  OsdMeshDescriptor described;
  std::vector<double> topo, patches, pos;
  AdaptivePeerTiming last;  // counts of the latest repetition
  Impl(const PolyMesh& m, int l) : mesh(m), levels(l), described(m) {}
};

AdaptivePeer::AdaptivePeer(const PolyMesh& mesh, int levels) {
  if (levels > kMaxLevels)
    unavailable_ = "OpenSubdiv isolates at most " + std::to_string(kMaxLevels) + " levels";
  else
    impl_ = std::make_unique<Impl>(mesh, levels);
}

AdaptivePeer::~AdaptivePeer() = default;

bool AdaptivePeer::run() {
  using namespace OpenSubdiv;
  if (!impl_) return false;
  Impl& p = *impl_;
  const bool first = p.topo.empty();
#ifdef __GLIBC__
  // The bench's own path ran before and freed its memory, which malloc may still hold: handed back
  // first, so that the peak measured from here is the peer's, over what the process holds live.
  if (first) malloc_trim(0);
#endif
  const bool peakReset = first && resetPeakResident();

  auto t0 = std::chrono::steady_clock::now();
  std::unique_ptr<Far::TopologyRefiner> refiner(p.described.create());
  if (!refiner) {
    unavailable_ = "OpenSubdiv refused the mesh";
    impl_.reset();
    return false;
  }
  Far::TopologyRefiner::AdaptiveOptions adaptive(p.levels);
  adaptive.useInfSharpPatch = true;
  adaptive.useSingleCreasePatch = false;
  adaptive.considerFVarChannels = false;
  refiner->RefineAdaptive(adaptive);
  p.topo.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());

  Far::PatchTableFactory::Options options(unsigned(p.levels));
  options.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_BSPLINE_BASIS);
  options.useInfSharpPatch = true;
  options.useSingleCreasePatch = false;
  options.generateFVarTables = false;
  options.generateVaryingTables = false;  // our path makes no varying data either
  t0 = std::chrono::steady_clock::now();
  std::unique_ptr<Far::PatchTable> table(Far::PatchTableFactory::Create(*refiner, options));
  p.patches.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());

  // Every refined vertex, then the end caps' local points (the tutorials' layout), allocated and
  // touched before the clock starts, as benchPeer's.
  const int refined = refiner->GetNumVerticesTotal(), local = table->GetNumLocalPoints();
  std::vector<OsdPoint<float>> points(size_t(refined + local));
  for (Index v = 0; v < p.mesh.vertexCount(); ++v) {
    const Point& q = p.mesh.points[v];
    points[v] = {q.x, q.y, q.z};
  }
  t0 = std::chrono::steady_clock::now();
  interpolateLevels<float, Far::PrimvarRefiner>(*refiner, refiner->GetMaxLevel(), points);
  // The templated accessor: the plain one downcasts to StencilTable inside OpenSubdiv's header, which
  // UBSan reports (the object is a StencilTableReal<float>).
  if (local > 0) table->GetLocalPointStencilTable<float>()->UpdateValues(points.data(), points.data() + refined);
  p.pos.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());

  AdaptivePeerTiming& t = p.last;
  t.patches = size_t(table->GetNumPatchesTotal());
  t.totalFaces = size_t(refiner->GetNumFacesTotal());
  t.totalVertices = size_t(refined);
  t.localPoints = size_t(local);
  t.levelFaces.clear();
  for (int level = 0; level <= refiner->GetMaxLevel(); ++level)
    t.levelFaces.push_back(size_t(refiner->GetLevel(level).GetNumFaces()));
  volatile double sink = points.back().x;  // the points are used
  (void)sink;
  if (peakReset) t.peakRssMb = peakResidentMegabytes();
  return true;
}

AdaptivePeerTiming AdaptivePeer::result() const {
  AdaptivePeerTiming t;
  if (!impl_ || impl_->topo.empty()) return t;
  t = impl_->last;
  t.name = "opensubdiv-3.5";
  t.topologyMs = medianOf(impl_->topo);
  t.patchesMs = medianOf(impl_->patches);
  t.positionsMs = medianOf(impl_->pos);
  return t;
}
#else
std::optional<PeerTiming> benchPeer(const PolyMesh&, int, int, const Refinement*) { return std::nullopt; }

struct AdaptivePeer::Impl {};
AdaptivePeer::AdaptivePeer(const PolyMesh&, int) : unavailable_("built without OpenSubdiv") {}
AdaptivePeer::~AdaptivePeer() = default;
bool AdaptivePeer::run() { return false; }
AdaptivePeerTiming AdaptivePeer::result() const { return {}; }
#endif

std::optional<AdaptivePeerTiming> benchAdaptivePeer(const PolyMesh& mesh, int levels, int reps) {
  AdaptivePeer peer(mesh, levels);
  for (int rep = 0; rep < std::max(reps, 1); ++rep)
    if (!peer.run()) return std::nullopt;
  return peer.result();
}

double triadGigabytesPerSecond(size_t bytesPerArray, unsigned threads, int reps) {
  const Index n = Index(bytesPerArray / sizeof(double));
  std::vector<double> a(n), b(n, 1.0), c(n, 2.0);  // touched here: the loop times no page faults
  double best = 1e300;
  for (int rep = 0; rep < reps; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    parallelRanges(n, threads, [&](Index begin, Index end) {
      for (Index i = begin; i < end; ++i) a[i] = b[i] + 3.0 * c[i];
    });
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  volatile double sink = a[size_t(n) / 2];  // the stores are used
  (void)sink;
  return 3.0 * double(n) * sizeof(double) / best / 1e9;
}

double peakResidentMegabytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0.0;
}

bool resetPeakResident() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  return bool(clear);
}

}  // namespace polarview::cli
