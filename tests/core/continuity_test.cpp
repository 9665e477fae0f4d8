// Continuity across seams (core/spline/continuity.h): the seams found geometrically are the ones the
// refinement's topology implies (Patch::edgeLevelDelta), B-spline seams are C2 to round-off, C2PS is
// G1 everywhere and C2 across its rings and its cap (the cap joins ring L C2 by construction, under
// every polar scheme), Catmull-Clark's end caps are not G1.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "core/mesh/obj_io.h"
#include "core/mesh/shapes.h"
#include "core/spline/continuity.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/adaptive_refiner.h"

using namespace polarview;

namespace {

// Round-off bound for positions and normals: gaps relative to the diagonal, angles in radians.
constexpr double kRoundOff = 1e-9;
// Curvature jumps of B-spline seams: round-off amplified by the second derivatives of small
// patches (4e-13 measured at C2PS level 4 on the valence-12 cap).
constexpr double kCurvatureRoundOff = 1e-10;

std::string asset(const char* name) { return std::string(POLARVIEW_ASSET_DIR) + "/" + name; }

// The patches `polarview export` writes (pipeline/patch_export.h: feature-adaptive).
PatchSet patchesOf(const PolyMesh& mesh, Scheme scheme, int level) {
  return extractPatches(AdaptiveRefinement(mesh, {scheme, level, false}));
}

// Seams and T-junctions as the refinement's level jumps imply on a closed mesh: a side of jump 0
// meets one side of jump 0, a fine side (jump < 0) meets one coarse side, a coarse side only fine
// ones; so seams = (sides of jump 0) / 2 + (fine sides), each fine side's seam a T-junction.
struct TopologyCount {
  size_t seams = 0, tJunctions = 0;
};
TopologyCount countFromLevelJumps(const PatchSet& set) {
  size_t level = 0, fine = 0;
  for (const Patch& patch : set.patches)
    for (int s = 0; s < 4; ++s) {
      if (patch.kind == PatchKind::PoleCap && s == 3) continue;  // the pole point
      level += patch.edgeLevelDelta[s] == 0;
      fine += patch.edgeLevelDelta[s] < 0;
    }
  return {level / 2 + fine, fine};
}

TopologyCount countMeasured(const ContinuityReport& report) {
  TopologyCount count;
  for (const SeamStats& s : report.seams) count.seams += s.count, count.tJunctions += s.tJunctions;
  return count;
}

}  // namespace

TEST_CASE("continuity: a torus of regular quads has two C2 seams a face and no boundary") {
  const PatchSet set = patchesOf(shapes::torus(12, 8), Scheme::CatmullClark, 0);
  REQUIRE(set.patches.size() == 96);
  const ContinuityReport report = measureContinuity(set);
  REQUIRE(report.seams.size() == 1);
  const SeamStats& s = report.seams[0];
  CHECK(s.kind == SeamKind::Regular);
  CHECK(s.count == 192);
  CHECK(s.tJunctions == 0);
  CHECK(report.boundarySides == 0);
  CHECK(s.maxPositionGap < kRoundOff);
  CHECK(s.maxNormalAngle < kRoundOff);
  CHECK(s.maxCurvatureJump() < kCurvatureRoundOff);
  // The torus bends: the jumps are relative to a real curvature.
  CHECK(report.maxAbsGaussian > 1.0);
  CHECK(report.maxAbsMean > 1.0);
}

TEST_CASE("continuity: the seams found are those the level jumps imply, on closed meshes") {
  struct Case {
    const char* name;
    PolyMesh mesh;
    Scheme scheme;
    int level;
  };
  const Case cases[] = {
      {"cube cc 1", shapes::cube(), Scheme::CatmullClark, 1},
      {"cube cc 3", shapes::cube(), Scheme::CatmullClark, 3},
      {"cube_cc2 cc 2", loadObj(asset("cube_cc2.obj")), Scheme::CatmullClark, 2},
      {"default c2ps 3", loadObj(asset("default.obj")), Scheme::C2PS, 3},
      {"default rts 2", loadObj(asset("default.obj")), Scheme::RTS, 2},
      {"globe bps 2", loadObj(asset("globe.obj")), Scheme::BPS, 2},
  };
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const PatchSet set = patchesOf(c.mesh, c.scheme, c.level);
    const ContinuityReport report = measureContinuity(set);
    const TopologyCount expected = countFromLevelJumps(set), measured = countMeasured(report);
    CHECK(report.boundarySides == 0);
    CHECK(measured.seams == expected.seams);
    CHECK(measured.tJunctions == expected.tJunctions);
    // Watertight: every seam's points agree to round-off, end caps included.
    for (const SeamStats& s : report.seams) CHECK(s.maxPositionGap < kRoundOff);
  }
}

TEST_CASE("continuity: the cube's Catmull-Clark level 1 is 24 end caps, two seams each") {
  // Level 1 of the cube: 24 quads, each with one valence-3 corner, none regular.
  const ContinuityReport report = measureContinuity(patchesOf(shapes::cube(), Scheme::CatmullClark, 1));
  REQUIRE(report.seams.size() == 1);
  CHECK(report.seams[0].kind == SeamKind::EndCap);
  CHECK(report.seams[0].count == 48);
  CHECK(report.seams[0].tJunctions == 0);
}

TEST_CASE("continuity: C2PS is G1 at every seam and C2 across its rings and its cap") {
  struct Case {
    const char* name;
    PolyMesh mesh;
  };
  const Case cases[] = {{"default.obj", loadObj(asset("default.obj"))},
                        {"cap12_paraboloid.obj", loadObj(asset("cap12_paraboloid.obj"))}};
  for (const Case& c : cases) {
    for (int level = 2; level <= 4; ++level) {
      CAPTURE(c.name);
      CAPTURE(level);
      const ContinuityReport report = measureContinuity(patchesOf(c.mesh, Scheme::C2PS, level));
      for (SeamKind kind : {SeamKind::RingRing, SeamKind::RingCap, SeamKind::CapCap, SeamKind::RegularRing})
        REQUIRE(report.find(kind) != nullptr);
      for (const SeamStats& s : report.seams) {
        CAPTURE(seamKindName(s.kind));
        CHECK(s.maxPositionGap < kRoundOff);
        // default.obj's stem keeps four valence-3 Catmull-Clark vertices: their end caps are not G1.
        if (s.kind == SeamKind::EndCap) continue;
        CHECK(s.maxNormalAngle < kRoundOff);
        CHECK(s.maxCurvatureJump() < kCurvatureRoundOff);
      }
    }
  }
}

// The cap matches ring L's position and first and second radial derivatives (patch.h: quintic
// blends), so the ring-cap seam is C2 to round-off under every polar scheme, BPS's tangent-plane
// cap included: K and H jumps at most 1e-9 of the model's largest |K|, |H| (the C1 cap left K
// jumps of 9e-5 of it under C2PS at level 3 on default.obj, 7e-3 under RTS, 1.7e-2 under BPS).
TEST_CASE("continuity: the pole cap joins ring L with curvature continuity under every polar scheme") {
  struct Variant {
    const char* name;
    Scheme scheme;
    bool uniformFirstStep;
  };
  const Variant variants[] = {{"c2ps", Scheme::C2PS, false},
                              {"c2ps-u", Scheme::C2PS, true},
                              {"rts", Scheme::RTS, false},
                              {"rts-u", Scheme::RTS, true},
                              {"bps", Scheme::BPS, false}};
  const char* meshes[] = {"default.obj", "cap6_saddle.obj", "cap12_monkey.obj"};
  for (const char* name : meshes) {
    const PolyMesh mesh = loadObj(asset(name));
    for (const Variant& variant : variants) {
      if (variant.uniformFirstStep && std::string(name) != "default.obj") continue;
      for (int level = 2; level <= 5; ++level) {
        CAPTURE(name);
        CAPTURE(variant.name);
        CAPTURE(level);
        const ContinuityReport report =
            measureContinuity(extractPatches(AdaptiveRefinement(mesh, {variant.scheme, level, variant.uniformFirstStep})));
        const SeamStats* seam = report.find(SeamKind::RingCap);
        REQUIRE(seam != nullptr);
        REQUIRE(report.maxAbsGaussian > 0.0);
        REQUIRE(report.maxAbsMean > 0.0);
        CHECK(seam->maxPositionGap < kRoundOff);
        CHECK(seam->maxNormalAngle < kRoundOff);
        // SeamStats' jumps are relative to the model's largest |K| and |H| already.
        CHECK(seam->maxGaussianJump <= 1e-9);
        CHECK(seam->maxMeanJump <= 1e-9);
      }
    }
  }
}

TEST_CASE("continuity: Catmull-Clark's end caps bend the normal where its regular patches do not") {
  const PolyMesh cube = loadObj(asset("cube_cc2.obj"));
  for (int level = 2; level <= 3; ++level) {
    CAPTURE(level);
    const ContinuityReport report = measureContinuity(patchesOf(cube, Scheme::CatmullClark, level));
    CHECK(report.boundarySides == 0);
    const SeamStats* regular = report.find(SeamKind::Regular);
    const SeamStats* endCap = report.find(SeamKind::EndCap);
    REQUIRE(regular != nullptr);
    REQUIRE(endCap != nullptr);
    CHECK(regular->maxNormalAngle < kRoundOff);
    CHECK(regular->maxCurvatureJump() < kCurvatureRoundOff);
    CHECK(endCap->maxPositionGap < kRoundOff);
    CHECK(endCap->maxNormalAngle > 1e-4);
    CHECK(endCap->maxCurvatureJump() > 1e-2);
  }
}

TEST_CASE("continuity: an open mesh's rim is counted apart, as boundary sides: those the extraction mirrored") {
  for (const char* name : {"cap12_paraboloid.obj", "convex16.obj"}) {
    for (Scheme scheme : {Scheme::C2PS, Scheme::CatmullClark}) {
      CAPTURE(name);
      CAPTURE(schemeName(scheme));
      PatchSources sources;
      const PatchSet set = extractPatches(AdaptiveRefinement(loadObj(asset(name)), {scheme, 2, false}), &sources);
      size_t missing = 0;
      for (uint8_t sides : sources.sidesMissing)
        for (int s = 0; s < 4; ++s) missing += (sides >> s) & 1;
      const ContinuityReport report = measureContinuity(set);
      CHECK(missing > 0);
      CHECK(report.boundarySides == missing);
    }
  }
}
