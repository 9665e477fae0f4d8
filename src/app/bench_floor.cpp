// The memory-bound floor (bench_floor.h).
#include "app/bench_floor.h"

#include "app/bench_peer.h"
#include "core/subdiv/parallel_for.h"

namespace polarview::cli {

StreamBandwidth measureTriad(size_t doubles, int repeats) {
  StreamBandwidth out;
  out.threads = threadLimit();
  out.oneThreadGBs = triadGigabytesPerSecond(doubles * sizeof(double), 1, repeats);
  out.allThreadsGBs = out.threads > 1 ? triadGigabytesPerSecond(doubles * sizeof(double), out.threads, repeats) : out.oneThreadGBs;
  return out;
}

AdaptiveFloorBytes adaptiveFloorBytes(const AdaptiveRefinement& refinement, const PatchSet& set) {
  AdaptiveFloorBytes out;
  constexpr double kIndex = sizeof(Index), kPoint = sizeof(Point);
  double allPoints = 0.0;
  for (int m = 0; m < refinement.levelCount(); ++m) {
    const PolyMesh& mesh = refinement.level(m).mesh;
    allPoints += double(mesh.points.size());
    if (m == 0) continue;
    const PolyMesh& parent = refinement.level(m - 1).mesh;
    out.topology += kIndex * (double(mesh.faceVerts.size()) + double(mesh.faceCount()) + double(parent.faceVerts.size()));
    out.positions += kPoint * (double(mesh.points.size()) + double(parent.points.size()));
  }
  out.patches = double(sizeof(Patch)) * double(set.patches.size()) + kPoint * allPoints;
  return out;
}

}  // namespace polarview::cli
