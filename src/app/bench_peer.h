// The peer `bench` measures against in the same run: OpenSubdiv 3.5's uniform Catmull-Clark
// refinement (Far::TopologyRefiner + Far::PrimvarRefiner, its fast path), when libosd-dev is found.
#pragma once

#include <memory>
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

// bench --adaptive --vs-opensubdiv: OpenSubdiv 3.5's own feature-adaptive path on the same mesh
// (tags and Sdc options as benchPeer's), timed in three parts, medians over the repetitions run:
//  * topologyMs: Far::TopologyRefinerFactory::Create + RefineAdaptive(AdaptiveOptions(levels)),
//    useInfSharpPatch on, useSingleCreasePatch and considerFVarChannels off;
//  * patchesMs: Far::PatchTableFactory::Create (ENDCAP_BSPLINE_BASIS, useInfSharpPatch on, no
//    face-varying or varying tables), its local point stencil table included;
//  * positionsMs: Far::PrimvarRefiner::Interpolate for every refined level (double xyz, float
//    weights: benchPeer's fast path), then the end caps' local points through the patch table's
//    GetLocalPointStencilTable()->UpdateValues: all the points the patches read.
struct AdaptivePeerTiming {
  std::string name;
  double topologyMs = 0, patchesMs = 0, positionsMs = 0;  // medians
  size_t patches = 0;      // PatchTable::GetNumPatchesTotal()
  size_t totalFaces = 0;   // TopologyRefiner::GetNumFacesTotal(): every level's (sparse) faces
  size_t totalVertices = 0, localPoints = 0;
  std::vector<size_t> levelFaces;  // faces of levels 0..GetMaxLevel() (fewer than levels + 1 when no feature is left)
  double peakRssMb = 0;  // VmHWM reset before its first repetition and read after it (0 where that fails)
};

// One repetition at a time, so the bench can alternate it with its own path (a noisy machine
// drifts; alternating spreads the drift over both). The mesh's descriptor is made once, untimed.
class AdaptivePeer {
 public:
  static constexpr int kMaxLevels = 15;  // AdaptiveOptions::isolationLevel has 4 bits
  AdaptivePeer(const PolyMesh& mesh, int levels);
  ~AdaptivePeer();
  AdaptivePeer(const AdaptivePeer&) = delete;
  AdaptivePeer& operator=(const AdaptivePeer&) = delete;
  // Why there is no peer ("": there is one): built without OpenSubdiv, Far refused the mesh (after
  // run()), or more levels than OpenSubdiv isolates (kMaxLevels).
  const std::string& unavailable() const { return unavailable_; }
  // Runs one timed repetition; false (and unavailable() says why) when Far refuses the mesh.
  bool run();
  // Medians of the repetitions run so far (at least one).
  AdaptivePeerTiming result() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string unavailable_;
};

// `reps` repetitions of AdaptivePeer in a row; nullopt without a peer.
std::optional<AdaptivePeerTiming> benchAdaptivePeer(const PolyMesh& mesh, int levels, int reps);

// The memory-bandwidth roof measured in the same run: STREAM's triad a[i] = b[i] + s c[i] over
// three arrays of `bytesPerArray` (doubles), on `threads` threads, best of `reps`; GB/s counting
// 24 bytes an element as STREAM does. [O(bytesPerArray * reps)]
double triadGigabytesPerSecond(size_t bytesPerArray, unsigned threads, int reps);

// Peak resident memory of this process (VmHWM), in MiB, and its reset (Linux clear_refs "5"):
// false where it cannot be reset. [O(1)]
double peakResidentMegabytes();
bool resetPeakResident();

}  // namespace polarview::cli
