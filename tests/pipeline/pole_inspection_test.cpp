// The pole inspector's numbers (pipeline/pole_inspection.h) on the viewer's default model: a
// valence-12 pole on a mushroom.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/mesh/obj_io.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/adaptive_refiner.h"

#include <glm/geometric.hpp>
#include "pipeline/pole_inspection.h"

namespace polarview {
namespace {

PolyMesh mushroom() { return loadObj(std::string(POLARVIEW_ASSET_DIR) + "/default.obj"); }

// Sign changes of K - mean(K) around the circle (closed): 2 per period of a wave.
int signChanges(const std::vector<double>& k) {
  const double mean = std::accumulate(k.begin(), k.end(), 0.0) / double(k.size());
  int changes = 0;
  for (size_t a = 0; a < k.size(); ++a) changes += (k[a] - mean) * (k[(a + 1) % k.size()] - mean) < 0.0;
  return changes;
}

}  // namespace

TEST_CASE("pole inspector: C2PS converges to the pole's K, RTS's spread stalls, BPS has none, Catmull-Clark oscillates n-fold") {
  const PolyMesh mesh = mushroom();
  const std::vector<Index> poles = modelPoles(mesh);
  REQUIRE(poles.size() == 1);
  CHECK_THROWS_AS(inspectPole(mesh, poles[0] + 1, SchemeChoice::C2PS, 4), std::invalid_argument);

  const PoleInspection c2ps = inspectPole(mesh, poles[0], SchemeChoice::C2PS, 10);
  CHECK(c2ps.byScheme);
  CHECK(c2ps.curvatureDefined);
  CHECK(c2ps.deviationFromPole);
  CHECK(c2ps.valence == 12);
  REQUIRE(c2ps.rings.size() >= 8);
  // About /2.5 a level (paper Section 5.2): over six levels at least 1/100.
  const double first = c2ps.rings[1].deviation, last = c2ps.rings[7].deviation;
  MESSAGE("C2PS max |K - K(pole)|: ring 2 " << first << ", ring 8 " << last << ", K(pole) " << c2ps.K);
  CHECK(last < first / 100.0);
  for (size_t m = 2; m < 8; ++m) CHECK(c2ps.rings[m].deviation < c2ps.rings[m - 1].deviation);

  const PoleInspection rts = inspectPole(mesh, poles[0], SchemeChoice::RTS, 12);
  CHECK(rts.directional);
  CHECK_FALSE(rts.deviationFromPole);
  REQUIRE(rts.rings.size() == 12);
  const double spread10 = rts.rings[9].deviation, spread12 = rts.rings[11].deviation;
  MESSAGE("RTS spread of K: ring 10 " << spread10 << ", ring 12 " << spread12);
  CHECK(spread12 > 0.7 * spread10);  // stalls: not C2 for finite n
  CHECK(spread12 > 1e-3 * std::abs(rts.K));

  const PoleInspection bps = inspectPole(mesh, poles[0], SchemeChoice::BPS, 6);
  CHECK_FALSE(bps.curvatureDefined);
  CHECK(bps.note.find("not defined") != std::string::npos);

  const PoleInspection cc = inspectPole(mesh, poles[0], SchemeChoice::CatmullClark, 6);
  CHECK_FALSE(cc.byScheme);
  REQUIRE(cc.rings.size() >= 3);
  // Around a valence-12 extraordinary vertex K waves 12 times a turn.
  const int changes = signChanges(cc.rings[2].kAlongAngle);
  MESSAGE("Catmull-Clark ring 3: " << changes << " sign changes of K - mean around the vertex, spread " << cc.rings[2].deviation);
  CHECK(changes == 24);
  for (const PoleRingCurves& ring : cc.rings) CHECK(ring.kAlongAngle.size() == size_t(kInspectorAngles));
}

}  // namespace polarview

namespace polarview {

TEST_CASE("pole zoom: rings m.. scaled by 2^m about the pole: shapes kept, K / 4^m, H / 2^m, ring m as large as ring 0") {
  const PolyMesh mesh = loadObj(std::string(POLARVIEW_ASSET_DIR) + "/default.obj");
  const PatchSet set = extractPatches(AdaptiveRefinement(mesh, RefineOptions{Scheme::C2PS, 8, false}));
  Point centre(0.0);
  for (const Patch& patch : set.patches)
    if (patch.kind == PatchKind::PoleCap) centre = patch.origin + patch.cp[0];
  auto extent = [&](const std::vector<Patch>& patches, int ring) {
    double far = 0.0;
    for (const Patch& patch : patches)
      if (patch.kind == PatchKind::PolarRing && patch.ring == ring)
        far = std::max(far, glm::length(evaluatePatch(patch, 1.0, 0.5).position - centre));
    return far;
  };
  const std::vector<Patch> ring5 = zoomAboutPole(set.patches, 0, 5, 1, centre);
  const std::vector<Patch> zoomed = zoomAboutPole(set.patches, 0, 6, 3, centre);
  REQUIRE_FALSE(zoomed.empty());
  int caps = 0;
  for (const Patch& patch : zoomed) {
    CHECK((patch.kind == PatchKind::PolarRing ? (patch.ring >= 6 && patch.ring <= 8) : patch.kind == PatchKind::PoleCap));
    caps += patch.kind == PatchKind::PoleCap;
  }
  CHECK(caps > 0);  // level 8 closes the hole within rings 6..8
  // Nested rings at one size: ring 6 zoomed by 2^6 spans what ring 5 zoomed by 2^5 spans (deep rings
  // are nearly similar: the characteristic map), to 1%.
  CHECK(extent(zoomed, 6) == doctest::Approx(extent(ring5, 5)).epsilon(0.01));
  // Each zoomed patch is the original scaled: K / 4^6, H / 2^6 at every parameter, the pole fixed.
  size_t k = 0;
  for (const Patch& original : set.patches) {
    if (original.kind != PatchKind::PolarRing || original.ring < 6 || original.ring > 8) continue;
    while (k < zoomed.size() && zoomed[k].kind != PatchKind::PolarRing) ++k;
    REQUIRE(k < zoomed.size());
    const SurfacePoint a = evaluatePatch(original, 0.3, 0.7), b = evaluatePatch(zoomed[k], 0.3, 0.7);
    CHECK(b.gaussian == doctest::Approx(a.gaussian / 4096.0).epsilon(1e-6));
    CHECK(b.mean == doctest::Approx(a.mean / 64.0).epsilon(1e-6));
    CHECK(glm::length((b.position - centre) - 64.0 * (a.position - centre)) < 1e-9);
    ++k;
  }
}

}  // namespace polarview
