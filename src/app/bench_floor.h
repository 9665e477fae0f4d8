// The memory-bound floor `bench --adaptive` prints beside its timings (docs/performance.md, "The
// floor"): the bytes each stage must at least move, and the machine's stream bandwidth measured in
// the same run by a triad, so each stage's time reads as a fraction of what the memory allows.
#pragma once

#include <cstddef>

#include "core/spline/patch_extraction.h"
#include "core/subdiv/adaptive_refiner.h"

namespace polarview::cli {

// STREAM's triad a[i] = b[i] + s c[i] over three arrays of `doubles` each (far beyond the caches at
// the default 2^23: 192 MB), best of `repeats`; 24 bytes an element, as STREAM counts it
// (bench_peer.h triadGigabytesPerSecond, which the uniform bench prints too).
struct StreamBandwidth {
  double oneThreadGBs = 0.0;   // one thread (the stages run on one)
  double allThreadsGBs = 0.0;  // every hardware thread, each on its part of the arrays
  unsigned threads = 1;
};
StreamBandwidth measureTriad(size_t doubles = size_t(1) << 23, int repeats = 5);

// The fewest bytes each stage of the feature-adaptive path must read and write (lower bounds: what
// any implementation has to touch once, nothing it may keep in cache counted twice):
//  * topology: write each level >= 1's face-vertex lists and face parents (4-byte indices), read
//    each parent level's face-vertex lists once;
//  * positions: write each level >= 1's points (24 bytes each), read each parent level's points once;
//  * patches: write the patches (sizeof(Patch) each), read every level's points once.
struct AdaptiveFloorBytes {
  double topology = 0.0, positions = 0.0, patches = 0.0;
};
AdaptiveFloorBytes adaptiveFloorBytes(const AdaptiveRefinement& refinement, const PatchSet& set);

}  // namespace polarview::cli
