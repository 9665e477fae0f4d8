// N-gon caps into triangle fans (Blender's "triangle fan" cap fill): a cylinder's caps become poles.
#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <utility>

#include "core/mesh/constants.h"
#include "core/mesh/ngon_to_fan.h"
#include "core/mesh/shapes.h"
#include "core/mesh/topology.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/polar_config.h"
#include "core/subdiv/refiner.h"

using namespace polarview;

namespace {

// Blender's cone: an n-gon base, a fan of n triangles to the tip (vertex n).
PolyMesh ngonCone(int n) {
  PolyMesh mesh;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * kPi * i / n;
    mesh.points.push_back({std::cos(a), std::sin(a), 0.0});
  }
  mesh.points.push_back({0.0, 0.0, 2.0});
  for (int i = 0; i < n; ++i) mesh.addFace({i, (i + 1) % n, n});
  std::vector<Index> base;
  for (int i = 0; i < n; ++i) base.push_back(n - 1 - i);
  mesh.addFace(base.data(), base.size());
  return mesh;
}

// Every directed edge (a, b) once, and its twin (b, a) once: a closed mesh whose faces all wind the
// same way as their neighbours.
bool consistentlyOriented(const PolyMesh& mesh) {
  std::map<std::pair<Index, Index>, int> directed;
  for (Index f = 0; f < mesh.faceCount(); ++f)
    for (Index c = 0; c < mesh.faceSize(f); ++c) ++directed[{mesh.face(f)[c], mesh.face(f)[(c + 1) % mesh.faceSize(f)]}];
  for (const auto& [edge, count] : directed) {
    const auto twin = directed.find({edge.second, edge.first});
    if (count != 1 || twin == directed.end() || twin->second != 1) return false;
  }
  return true;
}

std::vector<PolarConfig> refinablePoles(const PolyMesh& mesh) {
  std::vector<PolarConfig> poles;
  for (PolarConfig& config : findPolarConfigs(mesh, buildTopology(mesh)))
    if (config.refinable) poles.push_back(std::move(config));
  return poles;
}

}  // namespace

TEST_CASE("ngon to fan: a cylinder's 24-gon caps become two valence-24 poles facing each other") {
  const PolyMesh cylinder = shapes::ngonCylinder(24);
  CHECK(findPolarConfigs(cylinder, buildTopology(cylinder)).empty());  // no triangle anywhere
  const FanConversion fans = convertNgonsToFans(cylinder);
  CHECK(fans.faces == std::vector<Index>{24, 25});
  CHECK(fans.centres == std::vector<Index>{48, 49});
  CHECK(fans.mesh.vertexCount() == 50);
  CHECK(fans.mesh.faceCount() == 24 + 2 * 24);
  // The centres sit at the caps' centres; the fans wind as the side quads do.
  CHECK(fans.mesh.points[48].z == doctest::Approx(1.0));
  CHECK(fans.mesh.points[49].z == doctest::Approx(-1.0));
  CHECK(std::abs(fans.mesh.points[48].x) < 1e-12);
  CHECK(consistentlyOriented(cylinder));
  CHECK(consistentlyOriented(fans.mesh));
  const std::vector<PolarConfig> poles = refinablePoles(fans.mesh);
  REQUIRE(poles.size() == 2);
  for (const PolarConfig& pole : poles) {
    CHECK(pole.valence == 24);
    CHECK(pole.outer == PolarConfig::Outer::Pole);
    CHECK(schemeRefinesPole(Scheme::C2PS, pole));
    CHECK(schemeRefinesPole(Scheme::RTS, pole));
  }
  CHECK(poles[0].oppositePole == poles[1].pole);
  // C2PS refines them as poles: caps of 24 * 4 sectors each at level 2.
  const PatchSet patches = extractPatches(Refinement(fans.mesh, {Scheme::C2PS, 2, false}));
  CHECK(patches.count(PatchKind::PoleCap) == 2 * 24 * 4);
}

TEST_CASE("ngon to fan: quads and triangles stay, pentagons and up convert, hole ids follow, lines kept") {
  // A cone: its base converts, but neither fan is a pole (the rim is 4-valent among triangles only).
  const FanConversion cone = convertNgonsToFans(ngonCone(12));
  CHECK(cone.centres.size() == 1);
  CHECK(cone.mesh.faceCount() == 24);
  CHECK(consistentlyOriented(cone.mesh));
  CHECK(refinablePoles(cone.mesh).empty());
  // Faces: a quad, a pentagon (hole), a pentagon, a triangle; minSides 5.
  PolyMesh mesh;
  for (int i = 0; i < 12; ++i) mesh.points.push_back({double(i), double(i * i % 7), 0.0});
  mesh.addFace({0, 1, 2, 3});
  mesh.addFace({1, 4, 5, 6, 2});
  mesh.addFace({3, 2, 6, 7, 8});
  mesh.addFace({8, 9, 10});
  mesh.faceLine = {10, 11, 12, 13};
  mesh.tags.holes = {1};
  mesh.tags.creases = {{2, 3, 1.5}};
  CHECK(countFanFaces(mesh) == 1);
  const FanConversion fans = convertNgonsToFans(mesh);
  CHECK(fans.faces == std::vector<Index>{2});
  CHECK(fans.mesh.faceCount() == 1 + 1 + 5 + 1);
  CHECK(fans.mesh.tags.holes == std::vector<Index>{1});
  CHECK(fans.mesh.tags.creases == mesh.tags.creases);
  CHECK(fans.mesh.faceLine == std::vector<int64_t>{10, 11, 12, 12, 12, 12, 12, 13});
  CHECK(fans.mesh.points[12] == (mesh.points[3] + mesh.points[2] + mesh.points[6] + mesh.points[7] + mesh.points[8]) / 5.0);
  // Triangle i runs (loop[i], loop[i+1], centre).
  CHECK(std::vector<Index>(fans.mesh.face(2), fans.mesh.face(2) + 3) == std::vector<Index>{3, 2, 12});
  CHECK(std::vector<Index>(fans.mesh.face(6), fans.mesh.face(6) + 3) == std::vector<Index>{8, 3, 12});
  CHECK(convertNgonsToFans(mesh, 4).faces == std::vector<Index>{0, 2});
}

TEST_CASE("rejected pole candidates: grouped by kind, the highest valence first, then the later check failed") {
  auto candidate = [](Index pole, int valence, PolarRejection rejection) {
    PolarConfig config;
    config.pole = pole, config.valence = valence, config.rejection = rejection;
    config.refinable = rejection == PolarRejection::None;
    return config;
  };
  const std::vector<PolarConfig> configs{
      candidate(0, 6, PolarRejection::Link1NotFourValent), candidate(1, 5, PolarRejection::Link1NotFourValent),
      candidate(2, 8, PolarRejection::None),  // a pole: left out
      candidate(3, 6, PolarRejection::NoLink2), candidate(4, 32, PolarRejection::Link1OnBoundary),
      candidate(5, 7, PolarRejection::Link1NotFourValent)};
  CHECK(nearerPolarCandidate(configs[3], configs[0]));  // same valence: NoLink2 passed more checks
  CHECK_FALSE(nearerPolarCandidate(configs[0], configs[3]));
  const std::vector<RejectedGroup> groups = groupRejectedCandidates(configs);
  REQUIRE(groups.size() == 3);
  CHECK(groups[0].rejection == PolarRejection::Link1OnBoundary);
  CHECK(groups[0].members == std::vector<size_t>{4});
  CHECK(groups[1].rejection == PolarRejection::Link1NotFourValent);
  CHECK(groups[1].members == std::vector<size_t>{5, 0, 1});
  CHECK(groups[2].rejection == PolarRejection::NoLink2);
  // The cone after the conversion: its tip and base centre (12-valent, their rims among triangles
  // only) come before the rim's 4-valent vertices (ids 0..11), rejected at the first rim vertex
  // that fails (a 12-valent one, or a 4-valent one among triangles).
  const PolyMesh cone = convertNgonsToFans(ngonCone(12)).mesh;
  const std::vector<PolarConfig> coneConfigs = findPolarConfigs(cone, buildTopology(cone));
  const std::vector<RejectedGroup> coneGroups = groupRejectedCandidates(coneConfigs);
  REQUIRE(coneGroups.size() == 2);
  CHECK(coneGroups[0].rejection == PolarRejection::Link1NotTwoQuads);
  REQUIRE(coneGroups[0].members.size() >= 2);
  CHECK(coneConfigs[coneGroups[0].members[0]].pole == 12);
  CHECK(coneConfigs[coneGroups[0].members[1]].pole == 13);
  CHECK(coneGroups[1].rejection == PolarRejection::Link1NotFourValent);
  CHECK(coneGroups[0].members.size() + coneGroups[1].members.size() == 14);
  for (size_t k : coneGroups[1].members) CHECK(coneConfigs[k].valence == 4);
}
