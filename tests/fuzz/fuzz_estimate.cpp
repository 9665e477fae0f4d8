// libFuzzer target over the level limit's face estimate (tests/fuzz/README.md): small OBJ inputs ->
// estimateAdaptiveFaceCounts (adaptive_refiner.h) for each of the viewer's six schemes at the
// viewer's deepest level (refineOptionsFor(scheme, kMaxLevel), as estimatedLevelFaces in
// level_limits.h asks for it), under a small face budget and with 1..7 measured levels (a
// check of level L measures L), both picked by a hash of the input.
//
// Expected: polarview::InputError (a mesh no refinement takes). A finding: any other exception, a
// crash, ASan/UBSan report, a hang (-timeout), an allocation past the budget's needs (-rss_limit_mb,
// -malloc_limit_mb), or a broken guarantee of the header:
//  * one entry per level 0..kMaxLevel, level 0's the base faces, at most 1e18;
//  * the totals never fall, except to budget + 1 ("more than the budget") after a base mesh that is
//    over the budget by itself; once over the budget they stay over;
//  * a measured level is within the budget or reads budget + 1;
//  * the truth, for one scheme per input: AdaptiveRefinement to the deepest measured level within
//    the budget is made under that budget with at least the faces estimated; to the next level,
//    where the estimate says "over", it is refused (InputError) under it.
#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh/input_error.h"
#include "core/subdiv/adaptive_refiner.h"
#include "fuzz_common.h"
#include "obj_mutator.h"
#include "pipeline/scheme_choice.h"

using namespace polarview;
using namespace polarview::fuzz;

namespace {

constexpr InputLimits kLimits{16 << 10, 200, 400};

void checkTotals(const std::vector<size_t>& totals, size_t baseFaces, size_t budget, int measured) {
  const size_t over = budget + 1;
  if (totals.size() != size_t(kMaxLevel) + 1) fail(std::to_string(totals.size()) + " totals for levels 0.." + std::to_string(kMaxLevel));
  if (totals[0] != baseFaces) fail("level 0 totals " + std::to_string(totals[0]) + " faces, the mesh has " + std::to_string(baseFaces));
  for (size_t m = 1; m < totals.size(); ++m) {
    auto level = [&] {  // built for a finding only
      return "level " + std::to_string(m) + " (" + std::to_string(totals[m]) + " faces after " + std::to_string(totals[m - 1]) +
             ", budget " + std::to_string(budget) + ")";
    };
    if (totals[m] > size_t(1e18)) fail(level() + " is over 1e18");
    if (totals[m] < totals[m - 1] && totals[m] != over) fail(level() + " has fewer faces than the level before");
    if (totals[m - 1] > budget && totals[m] <= budget) fail(level() + " is within the budget after a level over it");
    if (int(m) <= measured && totals[m] > budget && totals[m] != over) fail(level() + ", measured, is over the budget but not budget + 1");
  }
}

// The estimate against the refinement itself, at the deepest measured level within the budget and
// at the one after it.
void checkTruth(const PolyMesh& mesh, SchemeChoice choice, const std::vector<size_t>& totals, size_t budget, int measured) {
  int deepest = 0;
  while (deepest < measured && totals[size_t(deepest) + 1] <= budget) ++deepest;
  const std::string name = schemeChoiceCliName(choice);
  gStage = "AdaptiveRefinement(" + name + ", level " + std::to_string(deepest) + ")";
  {
    const AdaptiveRefinement made(mesh, refineOptionsFor(choice, deepest), kSource, deepest == 0 ? size_t(1) << 26 : budget);
    if (deepest > 0 && (made.totalFaces() > budget || made.totalFaces() < totals[size_t(deepest)]))
      fail("level " + std::to_string(deepest) + " holds " + std::to_string(made.totalFaces()) + " faces, estimated " +
           std::to_string(totals[size_t(deepest)]) + " (budget " + std::to_string(budget) + ")");
  }
  if (deepest == measured) return;
  gStage = "AdaptiveRefinement(" + name + ", level " + std::to_string(deepest + 1) + ")";
  try {
    const AdaptiveRefinement made(mesh, refineOptionsFor(choice, deepest + 1), kSource, budget);
    fail("level " + std::to_string(deepest + 1) + ", estimated over the budget of " + std::to_string(budget) + ", is made with " +
         std::to_string(made.totalFaces()) + " faces");
  } catch (const InputError&) {
  }
}

void run(const uint8_t* data, size_t size) {
  PolyMesh mesh;
  if (!parseInput(data, size, kLimits, mesh)) return;
  const uint32_t hash = inputHash(data, size);
  const size_t budget = size_t(16) << (hash % 6);  // 16 .. 512 faces, all levels together
  const int measured = 1 + int(hash / 36 % 7);       // 1 .. 7 levels refined, the deeper ones extrapolated
  for (int k = 0; k < kSchemeChoiceCount; ++k) {
    const SchemeChoice choice = SchemeChoice(k);
    gStage = std::string("estimateAdaptiveFaceCounts(") + schemeChoiceCliName(choice) + ", budget " + std::to_string(budget) +
             ", measured " + std::to_string(measured) + ")";
    const std::vector<size_t> totals = estimateAdaptiveFaceCounts(mesh, refineOptionsFor(choice, kMaxLevel), budget, measured);
    checkTotals(totals, size_t(mesh.faceCount()), budget, measured);
    if (k == int(hash / 6 % kSchemeChoiceCount)) checkTruth(mesh, choice, totals, budget, measured);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return runInput([&] { run(data, size); });
}
