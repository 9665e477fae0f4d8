// The memory-bound floor (bench_floor.h).
#include "app/bench_floor.h"

#include <algorithm>
#include <chrono>
#include <memory>

#include "core/subdiv/parallel_for.h"
#include "pipeline/stopwatch.h"

namespace polarview::cli {

namespace {

// The best triad time over `repeats` with `threads` threads, each on its contiguous part (its own
// first touch, so its pages sit where it runs).
double bestTriadSeconds(size_t n, int repeats, unsigned threads) {
  std::unique_ptr<double[]> a(new double[n]), b(new double[n]), c(new double[n]);
  const Index count = Index(n);
  parallelRanges(count, threads, [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i) a[size_t(i)] = 0.0, b[size_t(i)] = 1.0, c[size_t(i)] = 2.0;
  });
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    parallelRanges(count, threads, [&](Index begin, Index end) {
      double* __restrict out = a.get();
      const double* __restrict x = b.get();
      const double* __restrict y = c.get();
      for (Index i = begin; i < end; ++i) out[i] = x[i] + 3.0 * y[i];
    });
    best = std::min(best, millisecondsSince(start) * 1e-3);
  }
  volatile double sink = a[n / 2];  // the stores are used
  (void)sink;
  return best;
}

}  // namespace

StreamBandwidth measureTriad(size_t doubles, int repeats) {
  StreamBandwidth out;
  const double bytes = 24.0 * double(doubles);
  out.threads = std::max(1u, std::min(8u, std::thread::hardware_concurrency()));
  out.oneThreadGBs = bytes / bestTriadSeconds(doubles, repeats, 1) * 1e-9;
  out.allThreadsGBs = out.threads > 1 ? bytes / bestTriadSeconds(doubles, repeats, out.threads) * 1e-9 : out.oneThreadGBs;
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
