// `polarview bench`: refinement and patches timed, with memory, against OpenSubdiv where it
// computes the same (bench_peer.h); docs/commands.md (bench) and docs/performance.md read it.
#include "app/bench_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "app/bench_floor.h"
#include "app/bench_peer.h"
#include "app/cli_options.h"
#include "app/json_writer.h"
#include "core/mesh/obj_io.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/adaptive_refiner.h"
#include "core/subdiv/parallel_for.h"
#include "core/subdiv/refiner.h"
#include "core/subdiv/table_pool.h"
#include "pipeline/level_limits.h"
#include "pipeline/model.h"
#include "pipeline/stopwatch.h"
#include "pipeline/surface_build.h"
#include "pipeline/surface_key.h"

namespace polarview::cli {

namespace {

// bench's options.
struct BenchArgs : SurfaceArgs {
  int reps = 5;
  bool json = false;
  bool adaptive = false, edit = false;  // --adaptive [--edit]
  bool vsOpenSubdiv = false;            // --vs-opensubdiv
};

OptionTable benchTable(BenchArgs& o) {
  return {inputRow(o.input),
          schemeRow(o),
          levelsRow(o, {"--levels", "--level"}),
          intOption({"--reps"}, "N", "repetitions; medians are reported (1..1000, default 5)", &o.reps, 1, 1000),
          uniformFirstStepRow(o),
          memoryBudgetRow(o), threadsRow(),
          flagOption({"--adaptive"}, "the feature-adaptive path of view, render and export", &o.adaptive),
          flagOption({"--edit"}, "with --adaptive: time one moved vertex's update", &o.edit),
          flagOption({"--vs-opensubdiv"}, "OpenSubdiv 3.5 in the same run (uniform: its points checked against ours; "
                     "--adaptive: its RefineAdaptive + PatchTableFactory timed beside ours, patches counted)", &o.vsOpenSubdiv),
          jsonRow(&o.json)};
}

// Bytes the positions pass must move at least, all levels: each level's parent points read once,
// child points written once, and the index tables the point rules stream (catmull_clark.cpp:
// faces, edges' ends and faces, vertex rings). Gathers of neighbours are not counted again.
double positionsTrafficBytes(const Refinement& refinement) {
  double bytes = 0;
  for (int m = 1; m < refinement.levelCount(); ++m) {
    const RefinedLevel& parent = refinement.level(m - 1);
    const MeshTopology& t = parent.topology;
    const size_t indices = parent.mesh.faceStart.size() + parent.mesh.faceVerts.size() + t.edgeVerts.size() +
                           t.edgeFaces.size() + t.vertexEdgeStart.size() + t.vertexEdges.size() + t.vertexFaceStart.size() +
                           t.vertexFaces.size();
    bytes += double(indices) * sizeof(Index) + 2.0 * double(t.vertexCount) * sizeof(uint8_t);
    bytes += double(parent.mesh.points.size() + refinement.level(m).mesh.points.size()) * sizeof(Point);
  }
  return bytes;
}

// Bytes of one level's arrays: points, faces, face parents and every topology table it holds.
double levelBytes(const RefinedLevel& level) {
  const MeshTopology& t = level.topology;
  double bytes = double(level.mesh.points.size()) * sizeof(Point) + double(t.vertexOnBoundary.size() + t.vertexUsed.size());
  for (const std::vector<Index>* table : {&level.mesh.faceStart, &level.mesh.faceVerts, &level.faceParent, &t.cornerEdge,
                                          &t.cornerFace, &t.edgeVerts, &t.edgeFaces, &t.vertexFaceStart, &t.vertexFaces,
                                          &t.vertexEdgeStart, &t.vertexEdges, &t.vertexCorners})
    bytes += double(table->size()) * sizeof(Index);
  return bytes;
}

// The arrays a refinement holds (every level: a library user reads any of them), as built.
double refinementBytes(const Refinement& refinement) {
  double bytes = 0;
  for (int m = 0; m < refinement.levelCount(); ++m) bytes += levelBytes(refinement.level(m));
  return bytes;
}

// bench --adaptive: the feature-adaptive path of view, render and export (adaptive_refiner.h).
// topology_ms = construction - positions; positions_ms = updatePositions; patches_ms = extraction;
// --edit adds edit_ms: one base vertex moved, then the points of every level and the patches'
// control points recomputed on the kept hierarchy (updatePositions + refreshPatches).
// The viewer's level steps on one kept refinement and LevelPatchCache (levels >= 1):
// level_up_ms = level L-1 shown, extend(1) + the patch set of L; level_down_ms = back to L-1;
// level_up_again_ms = to L once more (all of it cached).
// The viewer's own step (surface_build.h): level L-1 shown, level L's whole surface made ahead
// while idle (made_ahead_ms: prepareLevel, refinement, patches and curvature samples), then the step
// (level_up_made_ahead_ms: buildSurface handing it out; the GPU upload is not in it).
// --vs-opensubdiv: OpenSubdiv's RefineAdaptive + PatchTableFactory beside it (AdaptivePeer), its
// numbers in "peer", the ratios and patches_agree at the top level (docs/performance.md).

// What the adaptive bench measured, repetition by repetition, and the peer's timing.
struct AdaptiveBench {
  std::vector<double> build, positions, patches, edits, levelUp, levelDown, levelUpAgain, madeAhead, levelUpMadeAhead;
  std::string viewerStepRefusal;  // why the viewer's step is not timed (the viewer would refuse it)
  size_t patchCount = 0, totalFaces = 0, finestFaces = 0, polesRefined = 0;
  std::vector<size_t> levelFaces;
  double peakRssMb = 0.0;
  double topologyMs = 0, positionsMs = 0, patchesMs = 0;
  bool compared = false, peerFailed = false;
  std::string comparison;
  AdaptivePeerTiming theirs;
  AdaptiveFloorBytes floorBytes;  // bench_floor.h
  StreamBandwidth bandwidth;
};

// A stage's floor: its bytes at the machine's all-thread triad bandwidth, in ms.
double floorMs(double bytes, const StreamBandwidth& bandwidth) { return bytes / (bandwidth.allThreadsGBs * 1e6); }

// One repetition of our path: the refinement, its patches and --edit's update.
void timeAdaptiveRefinement(const BenchArgs& o, const PolyMesh& mesh, int rep, size_t budgetFaces, AdaptiveBench& b) {
  auto t0 = std::chrono::steady_clock::now();
  AdaptiveRefinement refinement(mesh, {o.scheme, o.levels, o.uniformFirstStep}, o.input, budgetFaces);
  b.build.push_back(millisecondsSince(t0));
  t0 = std::chrono::steady_clock::now();
  refinement.updatePositions(mesh.points);
  b.positions.push_back(millisecondsSince(t0));
  t0 = std::chrono::steady_clock::now();
  PatchSources sources;
  PatchSet set = extractPatches(refinement, &sources);
  b.patches.push_back(millisecondsSince(t0));
  b.patchCount = set.patches.size();
  if (rep == 0) b.floorBytes = adaptiveFloorBytes(refinement, set);
  // The path's own peak: before the level steps keep more refinements and surfaces alive.
  if (rep == 0) b.peakRssMb = peakResidentMegabytes();
  b.totalFaces = refinement.totalFaces();
  b.finestFaces = size_t(refinement.level(refinement.levelCount() - 1).mesh.faceCount());
  b.polesRefined = refinement.level(0).poles.size();
  b.levelFaces.clear();
  for (int m = 0; m < refinement.levelCount(); ++m) b.levelFaces.push_back(size_t(refinement.level(m).mesh.faceCount()));
  if (!o.edit) return;
  // Drag vertex 0 by 1% of the first edge's length, as the viewer does per frame.
  std::vector<Point> moved = mesh.points;
  moved[0] += 0.01 * (mesh.points[size_t(mesh.faceVerts[1])] - mesh.points[size_t(mesh.faceVerts[0])]);
  t0 = std::chrono::steady_clock::now();
  refinement.updatePositions(moved);
  refreshPatches(refinement, sources, set);
  b.edits.push_back(millisecondsSince(t0));
}

// The level steps on one kept refinement and LevelPatchCache (levels >= 1).
void timeLevelSteps(const BenchArgs& o, const PolyMesh& mesh, size_t budgetFaces, AdaptiveBench& b) {
  AdaptiveRefinement stepped(mesh, RefineOptions{o.scheme, o.levels - 1, o.uniformFirstStep}, o.input, budgetFaces);
  LevelPatchCache cache;
  PatchSources stepSources;
  cache.patchSet(stepped, o.levels - 1, &stepSources);  // what the view showed
  auto t0 = std::chrono::steady_clock::now();
  stepped.extend(1, budgetFaces);
  cache.patchSet(stepped, o.levels, &stepSources);
  b.levelUp.push_back(millisecondsSince(t0));
  t0 = std::chrono::steady_clock::now();
  cache.patchSet(stepped, o.levels - 1, &stepSources);
  b.levelDown.push_back(millisecondsSince(t0));
  t0 = std::chrono::steady_clock::now();
  cache.patchSet(stepped, o.levels, &stepSources);
  b.levelUpAgain.push_back(millisecondsSince(t0));
}

// The viewer's own step (surface_build.h): level L made ahead while L-1 is shown, then the step.
// The viewer offers fewer levels than the bench refines (its level cap, its bytes a face): where it
// would refuse these, the bench says so instead of timing them.
void timeViewerStep(const BenchArgs& o, const Model& model, const std::string& scheme, size_t viewFaceBudget,
                    AdaptiveBench& b) {
  if (!b.viewerStepRefusal.empty()) return;
  const SurfaceKey shownKey{model.generation, *parseSchemeChoice(scheme), o.levels - 1, model.points};
  SurfaceKey nextKey = shownKey;
  nextKey.level = o.levels;
  b.viewerStepRefusal = checkFaceBudget(model, nextKey, viewFaceBudget);
  if (!b.viewerStepRefusal.empty()) return;
  const std::shared_ptr<const BuiltSurface> shown = buildSurface(model, shownKey, viewFaceBudget);
  auto t0 = std::chrono::steady_clock::now();
  if (!prepareLevel(*shown->hierarchy, model, nextKey, viewFaceBudget)) {
    b.viewerStepRefusal = "level " + std::to_string(o.levels) + " could not be made ahead (memory)";
    return;
  }
  b.madeAhead.push_back(millisecondsSince(t0));
  t0 = std::chrono::steady_clock::now();
  const std::shared_ptr<const BuiltSurface> next = buildSurface(model, nextKey, viewFaceBudget, shown->hierarchy);
  b.levelUpMadeAhead.push_back(millisecondsSince(t0));
}

// --vs-opensubdiv: the peer's result where it computed the same surface; no OpenSubdiv (or it
// refused the mesh) fails the command, as the uniform bench's peer; too many levels only says so.
void compareWithAdaptivePeer(const BenchArgs& o, std::optional<AdaptivePeer>& peer, bool peerWanted, AdaptiveBench& b) {
  if (peer && !peer->unavailable().empty() && (peerWanted || o.levels <= AdaptivePeer::kMaxLevels)) {
    b.comparison = "no peer: " + peer->unavailable();
    b.peerFailed = o.levels <= AdaptivePeer::kMaxLevels;
  } else if (peer && peerWanted) {
    b.theirs = peer->result();
    b.compared = true;
    b.comparison = "same surface: Catmull-Clark, OpenSubdiv's RefineAdaptive + PatchTableFactory (B-spline end caps)";
  }
}

// Ours against OpenSubdiv's: topology, positions and patches together.
double adaptiveSpeedup(const AdaptiveBench& b) {
  const AdaptivePeerTiming& t = b.theirs;
  return (t.topologyMs + t.positionsMs + t.patchesMs) / std::max(b.topologyMs + b.positionsMs + b.patchesMs, 1e-9);
}

std::string adaptiveBenchJson(const BenchArgs& o, const std::string& scheme, const Model& model, const AdaptiveBench& b) {
  const AdaptivePeerTiming& theirs = b.theirs;
  JsonWriter w(o.input);
  w.beginObject().field("file", o.input).field("scheme", scheme).field("levels", o.levels).field("adaptive", true);
  w.field("reps", o.reps).field("topology_ms", b.topologyMs).field("positions_ms", b.positionsMs);
  w.field("patches_ms", b.patchesMs).field("patches", b.patchCount).field("total_faces", b.totalFaces);
  w.field("finest_faces", b.finestFaces);
  if (o.edit) w.field("edit_ms", median(b.edits));
  if (o.levels >= 1)
    w.field("level_up_ms", median(b.levelUp)).field("level_down_ms", median(b.levelDown)).field("level_up_again_ms", median(b.levelUpAgain));
  if (o.levels >= 1 && b.viewerStepRefusal.empty())
    w.field("made_ahead_ms", median(b.madeAhead)).field("level_up_made_ahead_ms", median(b.levelUpMadeAhead));
  else if (o.levels >= 1)
    w.key("made_ahead_ms").null().key("level_up_made_ahead_ms").null().field("viewer_step", b.viewerStepRefusal);
  w.field("peak_rss_mb", b.peakRssMb);
  // The first repetition (cold: fresh memory) against the medians (warm).
  w.key("cold").beginObject().field("topology_ms", std::max(0.0, b.build[0] - b.positions[0]));
  w.field("positions_ms", b.positions[0]).field("patches_ms", b.patches[0]);
  w.field("cold_over_warm", (b.build[0] + b.patches[0]) / std::max(b.topologyMs + b.positionsMs + b.patchesMs, 1e-9)).endObject();
  // Memory a refined face and a patch cost at the peak (the whole process's peak over either count),
  // and the deepest level of this scheme a view's memory budget (640 MB) admits on the model.
  w.field("peak_bytes_per_face", b.peakRssMb * 1048576.0 / double(std::max<size_t>(b.totalFaces, 1)));
  w.field("peak_bytes_per_patch", b.peakRssMb * 1048576.0 / double(std::max<size_t>(b.patchCount, 1)));
  w.field("view_deepest_level", deepestLevel(model, *parseSchemeChoice(scheme), kDefaultFaceBudget));
  w.key("level_faces").beginArray();
  for (size_t faces : b.levelFaces) w.value(faces);
  w.endArray();
  // The memory-bound floor (bench_floor.h): bytes, floor time at the all-thread triad bandwidth, and
  // the fraction of the floor each stage reaches (floor time / measured time).
  w.key("floor").beginObject().field("triad_gbs_one_thread", b.bandwidth.oneThreadGBs);
  w.field("triad_gbs_all_threads", b.bandwidth.allThreadsGBs).field("threads", size_t(b.bandwidth.threads));
  const std::pair<const char*, std::pair<double, double>> stages[] = {{"topology", {b.floorBytes.topology, b.topologyMs}},
                                                                       {"positions", {b.floorBytes.positions, b.positionsMs}},
                                                                       {"patches", {b.floorBytes.patches, b.patchesMs}}};
  for (const auto& [name, bytesAndMs] : stages) {
    const double ms = floorMs(bytesAndMs.first, b.bandwidth);
    w.key(name).beginObject().field("bytes", bytesAndMs.first).field("floor_ms", ms);
    w.field("fraction", ms / std::max(bytesAndMs.second, 1e-9)).endObject();
  }
  w.endObject();
  if (o.vsOpenSubdiv) {
    if (b.compared) {
      w.key("peer").beginObject().field("name", theirs.name);
      w.field("what",
              "Far::TopologyRefiner::RefineAdaptive (useInfSharpPatch) + Far::PatchTableFactory (ENDCAP_BSPLINE_BASIS) + "
              "Far::PrimvarRefiner and the local point stencils");
      w.field("topology_ms", theirs.topologyMs).field("positions_ms", theirs.positionsMs);
      w.field("patches_ms", theirs.patchesMs).field("patches", theirs.patches).field("total_faces", theirs.totalFaces);
      w.field("total_vertices", theirs.totalVertices).field("local_points", theirs.localPoints);
      w.key("level_faces").beginArray();
      for (size_t faces : theirs.levelFaces) w.value(faces);
      w.endArray();
      if (theirs.peakRssMb > 0) w.field("peak_rss_mb", theirs.peakRssMb);
      w.endObject();
    }
    w.field("compared", b.compared).field("comparison", b.comparison);
    if (b.compared) {
      w.field("topology_speedup", theirs.topologyMs / std::max(b.topologyMs, 1e-9))
          .field("patches_speedup", theirs.patchesMs / std::max(b.patchesMs, 1e-9));
      w.field("positions_speedup", theirs.positionsMs / std::max(b.positionsMs, 1e-9))
          .field("speedup", adaptiveSpeedup(b))
          .field("faces_ratio", double(b.totalFaces) / double(std::max<size_t>(theirs.totalFaces, 1)));
      w.field("patches_agree", theirs.patches == b.patchCount);
    }
  }
  w.endObject();
  return w.str();
}

void printAdaptiveBench(const BenchArgs& o, const std::string& scheme, const AdaptiveBench& b) {
  const AdaptivePeerTiming& theirs = b.theirs;
  std::printf("%s %s level %d (adaptive): topology %.3f ms, positions %.3f ms, patches %.3f ms; %zu patches, %zu faces in "
              "all levels; peak RSS %.1f MB\n",
              o.input.c_str(), scheme.c_str(), o.levels, b.topologyMs, b.positionsMs, b.patchesMs, b.patchCount, b.totalFaces,
              b.peakRssMb);
  const auto fraction = [&](double bytes, double ms) { return 100.0 * floorMs(bytes, b.bandwidth) / std::max(ms, 1e-9); };
  std::printf("memory-bound floor (triad %.1f GB/s on 1 thread, %.1f GB/s on %u): topology %.2f MB %.1f%%, positions %.2f MB "
              "%.1f%%, patches %.2f MB %.1f%% of the floor's speed\n",
              b.bandwidth.oneThreadGBs, b.bandwidth.allThreadsGBs, b.bandwidth.threads, b.floorBytes.topology / 1e6,
              fraction(b.floorBytes.topology, b.topologyMs), b.floorBytes.positions / 1e6,
              fraction(b.floorBytes.positions, b.positionsMs), b.floorBytes.patches / 1e6,
              fraction(b.floorBytes.patches, b.patchesMs));
  std::printf("cold (the first repetition, fresh memory): topology %.3f ms, positions %.3f ms, patches %.3f ms; %.2fx the "
              "warm median\n",
              std::max(0.0, b.build[0] - b.positions[0]), b.positions[0], b.patches[0],
              (b.build[0] + b.patches[0]) / std::max(b.topologyMs + b.positionsMs + b.patchesMs, 1e-9));
  if (o.edit) std::printf("edit (one base vertex moved -> new patches): %.3f ms\n", median(b.edits));
  if (o.levels >= 1)
    std::printf("level steps on the kept hierarchy: %d -> %d %.3f ms, back %.3f ms, again %.3f ms\n", o.levels - 1,
                o.levels, median(b.levelUp), median(b.levelDown), median(b.levelUpAgain));
  if (o.levels >= 1 && b.viewerStepRefusal.empty())
    std::printf("the viewer's step: level %d made ahead while idle %.3f ms, then the step %.3f ms (upload not counted)\n",
                o.levels, median(b.madeAhead), median(b.levelUpMadeAhead));
  else if (o.levels >= 1)
    std::printf("the viewer's step: not timed (%s)\n", b.viewerStepRefusal.c_str());
  if (b.compared)
    std::printf("%s adaptive: topology %.3f ms, positions %.3f ms, patches %.3f ms; %zu patches (%s), %zu faces in all "
                "levels (ours %.2fx); speed-up %.2fx (topology), %.2fx (positions), %.2fx (patches), %.2fx (all)\n",
                theirs.name.c_str(), theirs.topologyMs, theirs.positionsMs, theirs.patchesMs, theirs.patches,
                theirs.patches == b.patchCount ? "agree" : ("DIFFER: ours " + std::to_string(b.patchCount)).c_str(),
                theirs.totalFaces, double(b.totalFaces) / double(std::max<size_t>(theirs.totalFaces, 1)),
                theirs.topologyMs / std::max(b.topologyMs, 1e-9), theirs.positionsMs / std::max(b.positionsMs, 1e-9),
                theirs.patchesMs / std::max(b.patchesMs, 1e-9), adaptiveSpeedup(b));
  else if (o.vsOpenSubdiv)
    std::printf("vs OpenSubdiv adaptive: not compared (%s)\n", b.comparison.c_str());
}

int runAdaptiveBench(const BenchArgs& o, const PolyMesh& mesh) {
  const size_t budgetFaces = size_t(double(memoryBudgetBytes(o)) / double(kBytesPerUniformFace));
  const size_t viewFaceBudget = size_t(double(memoryBudgetBytes(o)) / kBytesPerAdaptiveFace);
  const std::string scheme = cliSchemeName(o.scheme, o.uniformFirstStep);
  const Model model = makeModel(std::make_shared<const PolyMesh>(mesh), o.input, 1);
  AdaptiveBench b;
  // --vs-opensubdiv: OpenSubdiv's own feature-adaptive path (bench_peer.h), alternated with ours
  // repetition by repetition (ours first on even repetitions, the peer first on odd ones) so that a
  // noisy machine's drift falls on both. It computes Catmull-Clark only: run where this run's
  // surface is the same (cc, or a polar scheme that refines no pole of this mesh), known after
  // our first repetition.
  std::optional<AdaptivePeer> peer;
  if (o.vsOpenSubdiv) peer.emplace(mesh, o.levels);
  bool peerWanted = false;
  auto runPeer = [&] {
    if (peer && peerWanted && peer->unavailable().empty()) peer->run();
  };
  for (int rep = 0; rep < o.reps; ++rep) {
    if (rep % 2 == 1) runPeer();
    timeAdaptiveRefinement(o, mesh, rep, budgetFaces, b);
    if (o.levels >= 1) {
      timeLevelSteps(o, mesh, budgetFaces, b);
      timeViewerStep(o, model, scheme, viewFaceBudget, b);
    }
    if (rep == 0 && peer) {
      if (schemeTraits(o.scheme).polar() && b.polesRefined > 0)
        b.comparison = "different surfaces: " + scheme + " refines " + std::to_string(b.polesRefined) + " pole" +
                       (b.polesRefined == 1 ? "" : "s") + " by its own rules, OpenSubdiv computes Catmull-Clark only";
      else
        peerWanted = true;
    }
    if (rep % 2 == 0) runPeer();
  }
  b.positionsMs = median(b.positions), b.topologyMs = std::max(0.0, median(b.build) - b.positionsMs);
  b.patchesMs = median(b.patches);
  b.bandwidth = measureTriad();  // in the same run as the timings
  compareWithAdaptivePeer(o, peer, peerWanted, b);
  const std::string json = adaptiveBenchJson(o, scheme, model, b);  // also for text: it refuses a non-finite number
  if (o.json) std::cout << json << "\n";
  else printAdaptiveBench(o, scheme, b);
  if (b.peerFailed) {
    std::fprintf(stderr, "polarview: bench --adaptive --vs-opensubdiv: %s\n", b.comparison.c_str());
    return 2;
  }
  return 0;
}

// What the uniform bench measured (medians over the repetitions) and what it compares against.
struct UniformBench {
  std::vector<double> build, positions, patches;
  size_t outVertices = 0, outFaces = 0, patchCount = 0, polesRefined = 0;
  double trafficBytes = 0, outputBytes = 0, finestBytes = 0, refinePeakRssMb = 0, peakRssMb = 0;
  double topologyMs = 0, positionsMs = 0, coldTopologyMs = 0, triadGbs = 0, positionsGbs = 0;
  std::optional<PeerTiming> peer;
  bool compared = false;
  std::string comparison, peerWhat = "OpenSubdiv Catmull-Clark (a different surface: not compared)";
  double topologySpeedup = 0, positionsSpeedup = 0, speedup = 0;
  bool checked = false, equal = false;  // --vs-opensubdiv: the finest points against the peer's
  double maxDifference = 0;
};

// The repetitions: topology as `refine` builds it (and OpenSubdiv's RefineUniform), no vertex rings
// at the finest level; the patches need them, so patches_ms includes making them. `kept` gets the
// last repetition's refinement (for --vs-opensubdiv's check).
void timeUniformRefinement(const BenchArgs& o, const PolyMesh& mesh, UniformBench& b, std::optional<Refinement>& kept) {
  RefineOptions options{o.scheme, o.levels, o.uniformFirstStep};
  options.fullFinestTopology = false;
  for (int rep = 0; rep < o.reps; ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    Refinement refinement(mesh, options, o.input);
    b.build.push_back(millisecondsSince(t0));
    t0 = std::chrono::steady_clock::now();
    refinement.updatePositions(mesh.points);
    b.positions.push_back(millisecondsSince(t0));
    if (rep == 0) {  // the refinement as `refine` has it: its own peak and its arrays
      b.refinePeakRssMb = peakResidentMegabytes();
      b.outputBytes = refinementBytes(refinement);
      b.finestBytes = levelBytes(refinement.finest());
    }
    t0 = std::chrono::steady_clock::now();
    refinement.completeFinestTopology();
    PatchSet set = extractPatches(refinement);
    b.patches.push_back(millisecondsSince(t0));
    b.outVertices = refinement.finest().mesh.points.size();
    b.outFaces = size_t(refinement.finest().mesh.faceCount());
    b.patchCount = set.patches.size();
    b.polesRefined = refinement.level(0).poles.size();
    b.trafficBytes = positionsTrafficBytes(refinement);
    if (o.vsOpenSubdiv && rep + 1 == o.reps) kept.emplace(std::move(refinement));
  }
}

// The peer computes Catmull-Clark only: timings compare only where this run computed the same
// surface (cc, or a scheme that refines no pole of this mesh), checked by equal face counts.
void compareWithPeer(const BenchArgs& o, const std::string& scheme, UniformBench& b) {
  if (!b.peer) {
    b.comparison = "no peer: built without OpenSubdiv (or it refused the mesh)";
  } else if (schemeTraits(o.scheme).polar() && b.polesRefined > 0) {
    b.comparison = "different surfaces: " + scheme + " refines " + std::to_string(b.polesRefined) + " pole" +
                   (b.polesRefined == 1 ? "" : "s") + " by its own rules, OpenSubdiv computes Catmull-Clark only";
  } else if (b.peer->outFaces != b.outFaces) {
    b.comparison = "not compared: Catmull-Clark both, but the face counts differ (" + std::to_string(b.outFaces) + " vs " +
                   std::to_string(b.peer->outFaces) + ")";
    b.peerWhat = "OpenSubdiv Catmull-Clark (face counts differ: not compared)";
  } else {
    b.compared = true;
    b.comparison = "same surface: Catmull-Clark, equal face counts";
    b.peerWhat = "OpenSubdiv Catmull-Clark (the same surface: compared)";
  }
  if (b.compared) {
    b.topologySpeedup = b.peer->topologyMs / std::max(b.topologyMs, 1e-9);
    b.positionsSpeedup = b.peer->positionsMs / std::max(b.positionsMs, 1e-9);
    b.speedup = (b.peer->topologyMs + b.peer->positionsMs) / std::max(b.topologyMs + b.positionsMs, 1e-9);
  }
}

// --vs-opensubdiv: the finest points must equal OpenSubdiv's (double weights) to round-off,
// relative to the mesh's size.
void checkPeerPoints(const BenchArgs& o, const PolyMesh& mesh, UniformBench& b) {
  b.checked = o.vsOpenSubdiv && b.compared && b.peer->checked;
  double size = 1.0;
  if (b.checked) {
    Point lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const Point& p : mesh.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    size = std::max(size, glm::length(hi - lo));
  }
  b.maxDifference = b.checked ? b.peer->maxDifference : 0.0;
  b.equal = b.checked && b.maxDifference <= 1e-12 * size;
}

std::string uniformBenchJson(const BenchArgs& o, const std::string& scheme, const UniformBench& b) {
  JsonWriter w(o.input);
  w.beginObject().field("file", o.input).field("scheme", scheme).field("levels", o.levels);
  w.field("reps", o.reps).field("topology_ms", b.topologyMs).field("positions_ms", b.positionsMs);
  w.field("cold_topology_ms", b.coldTopologyMs).field("cold_over_warm", b.coldTopologyMs / std::max(b.topologyMs, 1e-9));
  w.field("patches_ms", median(b.patches)).field("out_vertices", b.outVertices).field("out_faces", b.outFaces);
  // Memory (docs/performance.md): the refinement's peak against the arrays it holds, all levels.
  w.field("patches", b.patchCount).field("peak_rss_mb", b.refinePeakRssMb).field("peak_rss_with_patches_mb", b.peakRssMb);
  w.field("output_mb", b.outputBytes / (1 << 20))
      .field("peak_over_output", b.refinePeakRssMb * (1 << 20) / std::max(b.outputBytes, 1.0));
  w.field("output_bytes_per_vertex", b.outputBytes / double(std::max<size_t>(b.outVertices, 1)));
  w.field("finest_mb", b.finestBytes / (1 << 20));
  w.field("positions_gbs", b.positionsGbs).field("triad_gbs", b.triadGbs).field("positions_over_triad", b.positionsGbs / b.triadGbs);
  if (b.peer) {
    w.key("peer").beginObject().field("what", b.peerWhat).field("name", b.peer->name).field("topology_ms", b.peer->topologyMs);
    w.field("positions_ms", b.peer->positionsMs).field("out_vertices", b.peer->outVertices).field("out_faces", b.peer->outFaces);
    if (b.peer->peakRssMb > 0 && !o.vsOpenSubdiv) w.field("peak_rss_mb", b.peer->peakRssMb);  // (the check keeps ours alive)
    w.endObject();
  }
  w.field("compared", b.compared).field("comparison", b.comparison);
  if (b.compared)
    w.field("topology_speedup", b.topologySpeedup).field("positions_speedup", b.positionsSpeedup).field("speedup", b.speedup);
  if (o.vsOpenSubdiv) {
    w.key("vs_opensubdiv").beginObject().field("checked", b.checked);
    if (b.checked) w.field("equal", b.equal).field("max_difference", b.maxDifference);
    else w.field("why", b.compared ? "no points from the peer" : b.comparison);
    w.endObject();
  }
  w.endObject();
  return w.str();
}

void printUniformBench(const BenchArgs& o, const std::string& scheme, const UniformBench& b) {
  std::printf("%s %s level %d: topology %.3f ms (cold %.3f ms), positions %.3f ms, patches %.3f ms; %zu vertices, %zu faces, "
              "%zu patches; peak RSS %.1f MB refining (arrays held: %.1f MB, all levels), %.1f MB with the patches\n",
              o.input.c_str(), scheme.c_str(), o.levels, b.topologyMs, b.coldTopologyMs, b.positionsMs, median(b.patches),
              b.outVertices, b.outFaces, b.patchCount, b.refinePeakRssMb, b.outputBytes / (1 << 20), b.peakRssMb);
  std::printf("positions %.2f GB/s, triad %.2f GB/s (%.0f%%)\n", b.positionsGbs, b.triadGbs, 100.0 * b.positionsGbs / b.triadGbs);
  if (b.peer)
    std::printf("%s — %s: topology %.3f ms, positions %.3f ms; %zu vertices, %zu faces\n", b.peer->name.c_str(),
                b.peerWhat.c_str(), b.peer->topologyMs, b.peer->positionsMs, b.peer->outVertices, b.peer->outFaces);
  if (b.compared)
    std::printf("%s: speed-up %.2fx (topology), %.2fx (positions), %.2fx (both)\n", b.comparison.c_str(), b.topologySpeedup,
                b.positionsSpeedup, b.speedup);
  else std::printf("%s\n", b.comparison.c_str());
  if (b.checked) std::printf("vs OpenSubdiv: %s (max difference %.3g)\n", b.equal ? "equal" : "DIFFERENT", b.maxDifference);
  else if (o.vsOpenSubdiv) std::printf("vs OpenSubdiv: not checked (%s)\n", b.compared ? "no points from the peer" : b.comparison.c_str());
}

int runBench(BenchArgs& o) {
  checkFirstStep(o);
  if (o.edit && !o.adaptive) throw UsageError{"--edit needs --adaptive"};
  PolyMesh mesh = loadInput(o.input);
  if (o.adaptive) return runAdaptiveBench(o, mesh);
  checkMemoryBudget(mesh, o);
  UniformBench b;
  std::optional<Refinement> kept;  // --vs-opensubdiv: the last repetition's, for the check
  timeUniformRefinement(o, mesh, b, kept);
  b.peakRssMb = peakResidentMegabytes();  // before the peer and the triad allocate
  clearTablePool();  // the peer and the triad start from the memory the process had before
  // The constructor builds topology and computes positions once: topology = build - positions.
  // Repetitions after the first reuse the previous refinement's tables (table_pool.h), as the
  // viewer does when levels change; the first repetition, on fresh memory, is reported apart.
  b.positionsMs = median(b.positions), b.topologyMs = std::max(0.0, median(b.build) - b.positionsMs);
  b.coldTopologyMs = std::max(0.0, b.build.front() - b.positions.front());
  // The check compares Catmull-Clark points only (a polar scheme's poles are not OpenSubdiv's).
  const bool sameRules = !schemeTraits(o.scheme).polar() || b.polesRefined == 0;
  b.peer = benchPeer(mesh, o.levels, o.reps, kept && sameRules ? &*kept : nullptr);
  kept.reset();
  // The roof for positions_gbs, on as many threads as the point rules use on large meshes.
  b.triadGbs = triadGigabytesPerSecond(size_t(128) << 20, threadsFor(size_t(1) << 30), 5);
  b.positionsGbs = b.trafficBytes / (std::max(b.positionsMs, 1e-9) * 1e6);
  const std::string scheme = cliSchemeName(o.scheme, o.uniformFirstStep);
  compareWithPeer(o, scheme, b);
  checkPeerPoints(o, mesh, b);
  const std::string json = uniformBenchJson(o, scheme, b);  // also when printing text: it refuses a non-finite number
  if (o.json) std::cout << json << "\n";
  else printUniformBench(o, scheme, b);
  if (o.vsOpenSubdiv && !b.peer) {
    std::fprintf(stderr, "polarview: bench --vs-opensubdiv: %s\n", b.comparison.c_str());
    return 2;
  }
  return b.checked && !b.equal ? 1 : 0;
}

}  // namespace

CommandParser benchCommand() { return makeCommandParser(benchTable, runBench); }

}  // namespace polarview::cli
