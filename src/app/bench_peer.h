// The peer `bench` measures against in the same run: OpenSubdiv 3.5's uniform Catmull-Clark
// refinement (Far::TopologyRefiner + Far::PrimvarRefiner, its fast path), when libosd-dev is found.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/mesh/poly_mesh.h"
#include "core/subdiv/refiner.h"

namespace polarview::cli {

struct PeerTiming {
  std::string name;
  double topologyMs = 0, positionsMs = 0;  // medians
  size_t outVertices = 0, outFaces = 0;
  double peakRssMb = 0;  // the peer's own peak (VmHWM reset before it runs; 0 where that fails)
  // With `check`: OpenSubdiv's finest points (double weights, untimed) in the order of check's
  // finest level, and the largest coordinate difference from check's points (a non-manifold
  // input, refined split: the distance between the merged points and OpenSubdiv's as sets).
  bool checked = false;
  double maxDifference = 0;
};

// Median timings of the peer refining `mesh` uniformly `levels` times; nullopt without OpenSubdiv.
// `check` (a Catmull-Clark Refinement of `mesh` to `levels`, or null): compare its finest points
// with OpenSubdiv's, vertices matched level by level as tests/osd/osd_oracle_test.cpp does.
std::optional<PeerTiming> benchPeer(const PolyMesh& mesh, int levels, int reps, const Refinement* check = nullptr);

// The memory-bandwidth roof measured in the same run: STREAM's triad a[i] = b[i] + s c[i] over
// three arrays of `bytesPerArray` (doubles), on `threads` threads, best of `reps`; GB/s counting
// 24 bytes an element as STREAM does. [O(bytesPerArray * reps)]
double triadGigabytesPerSecond(size_t bytesPerArray, unsigned threads, int reps);

// Peak resident memory of this process (VmHWM), in MiB, and its reset (Linux clear_refs "5"):
// false where it cannot be reset. [O(1)]
double peakResidentMegabytes();
bool resetPeakResident();

}  // namespace polarview::cli
