// The peer `bench` measures against in the same run: OpenSubdiv 3.5's uniform Catmull-Clark
// refinement (Far::TopologyRefiner + Far::PrimvarRefiner, its fast path), when libosd-dev is found.
#pragma once

#include <optional>
#include <string>

#include "core/mesh/poly_mesh.h"

namespace polarview::cli {

struct PeerTiming {
  std::string name;
  double topologyMs = 0, positionsMs = 0;  // medians
  size_t outVertices = 0, outFaces = 0;
};

// Median timings of the peer refining `mesh` uniformly `levels` times; nullopt without OpenSubdiv.
std::optional<PeerTiming> benchPeer(const PolyMesh& mesh, int levels, int reps);

}  // namespace polarview::cli
