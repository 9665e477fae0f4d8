// The CAD writers' shell (core/export/cad_topology.h): closed models are closed shells of a
// sphere's (or torus') Euler characteristic whose every edge is used twice the opposite ways, loops
// close up, each use's pcurve runs its face along the edge's own curve (position equal to 1e-9 of
// the diagonal at every parameter), T-junctions are split where the adaptive levels meet; open
// models keep their boundary free; degenerate joins are never called closed.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/export/cad_surfaces.h"
#include "core/export/cad_topology.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/shapes.h"
#include "core/subdiv/adaptive_refiner.h"

using namespace polarview;

namespace {

CadSurfaceSet adaptiveSurfaces(const PolyMesh& mesh, Scheme scheme, int level) {
  return cadSurfaces(extractPatches(AdaptiveRefinement(mesh, {scheme, level, false}, "test")), "test");
}

PolyMesh asset(const std::string& name) { return loadObj(std::string(POLARVIEW_ASSET_DIR) + "/" + name); }

// The mesh with every face's loop reversed (normals inwards).
PolyMesh reversed(PolyMesh mesh) {
  for (Index f = 0; f < mesh.faceCount(); ++f)
    std::reverse(mesh.faceVerts.begin() + mesh.faceStart[size_t(f)],
                 mesh.faceVerts.begin() + mesh.faceStart[size_t(f) + 1]);
  return mesh;
}

// Checks the shell's invariants (loops close, each use runs along its edge's curve, no edge used
// more than twice, a shared edge once each way); returns V - E + F, F the faces with a loop.
long checkedEulerCharacteristic(const CadSurfaceSet& set, const CadTopology& topology) {
  std::vector<int> forwardUses(topology.edges.size(), 0), backwardUses(topology.edges.size(), 0);
  long faces = 0;
  double worst = 0.0;
  for (size_t s = 0; s < set.surfaces.size(); ++s) {
    const std::vector<CadCoedge>& loop = topology.loops[s];
    faces += loop.empty() ? 0 : 1;
    for (size_t k = 0; k < loop.size(); ++k) {
      const CadCoedge& use = loop[k];
      const CadEdge& edge = topology.edges[size_t(use.edge)];
      (use.forward ? forwardUses : backwardUses)[size_t(use.edge)]++;
      const CadCoedge& next = loop[(k + 1) % loop.size()];
      const CadEdge& nextEdge = topology.edges[size_t(next.edge)];
      REQUIRE((use.forward ? edge.end : edge.start) == (next.forward ? nextEdge.start : nextEdge.end));
      // The face along its pcurve (cadSideParameter of the piece, the edge's direction) is the edge's curve.
      const std::vector<Point> curve =
          bezierSegment(cadSideCurve(set.surfaces[edge.surface], edge.side), edge.t0, edge.t1);
      for (double e : {0.0, 0.3, 0.5, 0.9, 1.0}) {
        const double t = use.forward ? use.t0 + e * (use.t1 - use.t0) : use.t1 - e * (use.t1 - use.t0);
        const glm::dvec2 uv = cadSideParameter(use.side, t);
        worst = std::max(worst, glm::distance(set.surfaces[s].bezier.evaluate(uv.x, uv.y), bezierPoint(curve, e)));
      }
    }
  }
  CHECK(worst <= 1e-9 * set.boxDiagonal);
  for (size_t e = 0; e < topology.edges.size(); ++e) {
    REQUIRE(forwardUses[e] == 1);
    REQUIRE(backwardUses[e] <= 1);
    CHECK(topology.edges[e].uses == forwardUses[e] + backwardUses[e]);
  }
  return long(topology.vertices.size()) - long(topology.edges.size()) + faces;
}

}  // namespace

TEST_CASE("cad topology: closed models are one closed shell, every edge shared the opposite ways") {
  struct Case {
    std::string name;
    PolyMesh mesh;
    Scheme scheme;
    int level;
    long euler;
  };
  const std::vector<Case> cases = {
      {"default.obj C2PS 3", asset("default.obj"), Scheme::C2PS, 3, 2},
      {"default.obj RTS 4", asset("default.obj"), Scheme::RTS, 4, 2},
      {"default.obj BPS 2", asset("default.obj"), Scheme::BPS, 2, 2},
      {"globe.obj C2PS 3", asset("globe.obj"), Scheme::C2PS, 3, 2},
      {"cube_cc2.obj CC 2", asset("cube_cc2.obj"), Scheme::CatmullClark, 2, 2},
      {"torus CC 1", shapes::torus(6, 5), Scheme::CatmullClark, 1, 0},
  };
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const CadSurfaceSet set = adaptiveSurfaces(c.mesh, c.scheme, c.level);
    const CadTopology topology = cadTopology(set);
    CHECK(topology.closed());
    CHECK(topology.freeEdges == 0);
    CHECK(!topology.inwards);
    CHECK(checkedEulerCharacteristic(set, topology) == c.euler);
    // Feature-adaptive levels meet in T-junctions around every extraordinary vertex and pole.
    if (c.level > 1 && c.name.find("globe") == std::string::npos) CHECK(topology.tJunctionSplits > 0);
  }
}

TEST_CASE("cad topology: a mesh turned inside out is a closed shell marked inwards") {
  const CadSurfaceSet set = adaptiveSurfaces(reversed(asset("cube_cc2.obj")), Scheme::CatmullClark, 1);
  const CadTopology topology = cadTopology(set);
  CHECK(topology.closed());
  CHECK(topology.inwards);
  CHECK(checkedEulerCharacteristic(set, topology) == 2);
}

TEST_CASE("cad topology: an open cap keeps its boundary as free edges, one loop of them") {
  const CadSurfaceSet set = adaptiveSurfaces(shapes::polarCap(6, 3), Scheme::RTS, 2);
  const CadTopology topology = cadTopology(set);
  CHECK(!topology.closed());
  CHECK(checkedEulerCharacteristic(set, topology) == 1);  // a disc
  // The free edges are outer sides (no cap's) and form closed chains.
  std::vector<int> starts, ends;
  for (const CadEdge& edge : topology.edges)
    if (edge.uses == 1) {
      CHECK(set.surfaces[edge.surface].kind != PatchKind::PoleCap);
      starts.push_back(edge.start);
      ends.push_back(edge.end);
    }
  REQUIRE(!starts.empty());
  CHECK(topology.freeEdges == starts.size());
  std::sort(starts.begin(), starts.end());
  std::sort(ends.begin(), ends.end());
  CHECK(starts == ends);
}

TEST_CASE("cad topology: back-to-back sheets are not a closed shell") {
  PolyMesh sheets;
  sheets.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
  sheets.addFace({0, 1, 2, 3});
  sheets.addFace({1, 4, 5, 2});
  sheets.addFace({3, 2, 1, 0});
  sheets.addFace({2, 5, 4, 1});
  const CadSurfaceSet set = adaptiveSurfaces(sheets, Scheme::CatmullClark, 1);
  const CadTopology topology = cadTopology(set);
  CHECK(topology.nonManifoldPieces > 0);
  CHECK(!topology.closed());
}

TEST_CASE("cad topology: a Bezier segment is the curve on its interval") {
  const std::vector<Point> curve = {{0, 0, 0}, {1, 2, 0}, {3, -1, 1}, {4, 0, 2}, {5, 1, -1}};
  for (const auto& [t0, t1] : {std::pair{0.0, 1.0}, {0.25, 0.5}, {0.0, 0.125}, {0.5, 1.0}, {0.375, 0.875}}) {
    const std::vector<Point> piece = bezierSegment(curve, t0, t1);
    REQUIRE(piece.size() == curve.size());
    for (double s : {0.0, 0.2, 0.5, 0.7, 1.0})
      CHECK(glm::distance(bezierPoint(piece, s), bezierPoint(curve, t0 + s * (t1 - t0))) < 1e-13);
  }
}
