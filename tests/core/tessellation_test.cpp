// core/export/tessellation: the triangle mesh of a PatchSet is a closed (or correctly bounded),
// consistently oriented 2-manifold of the control mesh's topology, with one vertex per seam point
// and per pole, and every vertex carries evaluatePatch's exact values.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/export/tessellation.h"
#include "core/export/tessellation_writers.h"
#include "core/mesh/input_error.h"
#include "core/mesh/obj_io.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/refiner.h"

using namespace polarview;

namespace {

struct Case {
  const char* file;
  Scheme scheme;
  int level;
  int samples;
};

PolyMesh asset(const char* file) { return loadObj(std::string(POLARVIEW_ASSET_DIR) + "/" + file); }

// The control mesh's Euler characteristic and boundary loops: the surface's topology.
struct Topology {
  long euler = 0;
  int boundaryLoops = 0;
};

// Boundary loops of a set of undirected boundary edges (each boundary vertex has two of them).
int countLoops(const std::vector<std::pair<long, long>>& edges) {
  std::map<long, std::vector<long>> around;
  for (const auto& [a, b] : edges) around[a].push_back(b), around[b].push_back(a);
  std::set<long> seen;
  int loops = 0;
  for (const auto& entry : around) {
    if (seen.count(entry.first)) continue;
    ++loops;
    std::vector<long> stack{entry.first};
    while (!stack.empty()) {
      const long v = stack.back();
      stack.pop_back();
      if (!seen.insert(v).second) continue;
      for (long w : around[v]) stack.push_back(w);
    }
  }
  return loops;
}

Topology controlTopology(const PolyMesh& mesh) {
  std::map<std::pair<long, long>, int> edges;
  for (Index f = 0; f < mesh.faceCount(); ++f)
    for (Index k = 0; k < mesh.faceSize(f); ++k) {
      const long a = mesh.face(f)[k], b = mesh.face(f)[(k + 1) % mesh.faceSize(f)];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  std::vector<std::pair<long, long>> boundary;
  for (const auto& [edge, uses] : edges)
    if (uses == 1) boundary.push_back(edge);
  return {long(mesh.vertexCount()) - long(edges.size()) + long(mesh.faceCount()), countLoops(boundary)};
}

double boxDiagonal(const std::vector<Point>& points) {
  Point low(1e300), high(-1e300);
  for (const Point& p : points) low = glm::min(low, p), high = glm::max(high, p);
  return glm::length(high - low);
}

// The smallest distance between two distinct vertices (sorted along x, a window).
double closestPair(std::vector<Point> points, double below) {
  std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) { return a.x < b.x; });
  double best = 1e300;
  for (size_t i = 0; i < points.size(); ++i)
    for (size_t j = i + 1; j < points.size() && points[j].x - points[i].x < below; ++j)
      best = std::min(best, glm::length(points[j] - points[i]));
  return best;
}

void checkTessellation(const Case& c) {
  const PolyMesh mesh = asset(c.file);
  const PatchSet set = extractPatches(Refinement(mesh, {c.scheme, c.level, false}, c.file));
  const Tessellation t = tessellatePatchSet(set, c.samples);
  const Topology expected = controlTopology(mesh);
  const double diagonal = boxDiagonal(t.positions);

  // Every edge twice, once each way, except at the mesh's boundary (counted by hand here, not by
  // countTessellationEdges, which is checked against it).
  std::map<std::pair<long, long>, std::pair<int, int>> uses;
  for (const auto& tri : t.triangles)
    for (int k = 0; k < 3; ++k) {
      const long a = tri[k], b = tri[(k + 1) % 3];
      auto& u = uses[{std::min(a, b), std::max(a, b)}];
      (a < b ? u.first : u.second) += 1;
    }
  std::vector<std::pair<long, long>> boundary;
  int bad = 0;
  for (const auto& [edge, u] : uses) {
    if (u.first + u.second == 1) boundary.push_back(edge);
    else if (u.first != 1 || u.second != 1) ++bad;
  }
  CHECK(bad == 0);
  CHECK(countLoops(boundary) == expected.boundaryLoops);
  const TessellationEdges counted = countTessellationEdges(t);
  CHECK(counted.edges == uses.size());
  CHECK(counted.boundary == boundary.size());
  CHECK(counted.watertight() == (expected.boundaryLoops == 0));

  // The control mesh's topology: V - E + F.
  CHECK(long(t.positions.size()) - long(uses.size()) + long(t.triangles.size()) == expected.euler);

  // No degenerate triangle; each faces the way the exact normals at its corners do.
  double smallestArea = 1e300, worstFacing = 1.0;
  for (const auto& tri : t.triangles) {
    const Point& a = t.positions[tri[0]];
    const Point n = glm::cross(t.positions[tri[1]] - a, t.positions[tri[2]] - a);
    smallestArea = std::min(smallestArea, 0.5 * glm::length(n));
    const Point corners = t.normals[tri[0]] + t.normals[tri[1]] + t.normals[tri[2]];
    worstFacing = std::min(worstFacing, glm::dot(glm::normalize(n), glm::normalize(corners)));
  }
  CHECK(smallestArea > 1e-10 * diagonal * diagonal);
  CHECK(worstFacing > 0.5);

  // Welded: no two vertices at one point (seams and the pole are single vertices).
  CHECK(closestPair(t.positions, 1e-6 * diagonal) > 1e-6 * diagonal);

  // Exact values: each vertex is evaluatePatch at its source, bit for bit.
  size_t mismatches = 0;
  for (size_t v = 0; v < t.positions.size(); ++v) {
    const TessellationSource& s = t.sources[v];
    const SurfacePoint p = evaluatePatch(set.patches[s.patch], s.u, s.v);
    if (p.position != t.positions[v] || p.normal != t.normals[v] || p.gaussian != t.gaussian[v] || p.mean != t.mean[v])
      ++mismatches;
    if (std::abs(glm::length(t.normals[v]) - 1.0) > 1e-12) ++mismatches;
  }
  CHECK(mismatches == 0);
  // These models have no coarse side facing mixed levels: the level jumps alone close them.
  CHECK(t.splitEdges == 0);
  MESSAGE(std::string(c.file) << " level " << c.level << " N=" << c.samples << ": " << t.positions.size() << " vertices, "
                 << t.triangles.size() << " triangles, " << t.splitEdges << " mixed-level splits");
}

// How many T-junction edges and caps a set has (so the cases below exercise them).
std::pair<int, size_t> junctionsAndCaps(const Case& c) {
  const PatchSet set = extractPatches(Refinement(asset(c.file), {c.scheme, c.level, false}, c.file));
  int junctions = 0;
  for (const Patch& p : set.patches)
    for (int8_t d : p.edgeLevelDelta) junctions += d > 0;
  return {junctions, set.count(PatchKind::PoleCap)};
}

}  // namespace

TEST_CASE("tessellation: the default model at C2PS levels 2 and 3 is closed across its T-junctions and caps") {
  for (const Case c : {Case{"default.obj", Scheme::C2PS, 2, 4}, Case{"default.obj", Scheme::C2PS, 3, 3},
                       Case{"default.obj", Scheme::C2PS, 2, 1}}) {
    const auto [junctions, caps] = junctionsAndCaps(c);
    CHECK(junctions > 0);
    CHECK(caps > 0);
    checkTessellation(c);
  }
}

TEST_CASE("tessellation: a globe, a Catmull-Clark cube with valence-3 vertices and an open cap") {
  checkTessellation({"globe.obj", Scheme::C2PS, 2, 4});
  checkTessellation({"cube_cc2.obj", Scheme::CatmullClark, 2, 4});
  checkTessellation({"cube_cc2.obj", Scheme::CatmullClark, 3, 2});
  checkTessellation({"cap12_paraboloid.obj", Scheme::C2PS, 3, 4});
  checkTessellation({"fingertips.obj", Scheme::C2PS, 2, 2});
}

TEST_CASE("tessellation: a pole is one vertex, with the cap's values at u = 0") {
  const PatchSet set = extractPatches(Refinement(asset("globe.obj"), {Scheme::C2PS, 2, false}, "globe"));
  const Tessellation t = tessellatePatchSet(set, 3);
  std::map<int, std::set<uint32_t>> poleVertices;  // pole -> the vertices at its caps' u = 0
  for (size_t p = 0; p < set.patches.size(); ++p) {
    if (set.patches[p].kind != PatchKind::PoleCap) continue;
    const Point pole = evaluatePatch(set.patches[p], 0.0, 0.5).position;
    for (uint32_t v = 0; v < t.positions.size(); ++v)
      if (glm::length(t.positions[v] - pole) < 1e-9) poleVertices[set.patches[p].pole].insert(v);
  }
  REQUIRE(poleVertices.size() == 2);
  for (const auto& [pole, vertices] : poleVertices) {
    REQUIRE(vertices.size() == 1);
    const uint32_t v = *vertices.begin();
    const Patch& cap = set.patches[t.sources[v].patch];
    CHECK(cap.kind == PatchKind::PoleCap);
    CHECK(t.sources[v].u == 0.0);
    // Its fan: one triangle per cap sector and segment (N = 3 per sector).
    size_t fan = 0;
    for (const auto& tri : t.triangles) fan += std::count(tri.begin(), tri.end(), v);
    CHECK(fan == 3 * set.count(PatchKind::PoleCap) / 2);
  }
}

TEST_CASE("tessellation: T-junctions are closed by the level jumps, and without them by the midpoint splits") {
  // The level jumps alone close the default model (no split). With them forgotten, the coarse sides
  // have N segments only (fewer vertices), and the midpoint rule splits each coarse segment at the
  // fine sides' samples until the cracks are closed.
  PatchSet set = extractPatches(Refinement(asset("default.obj"), {Scheme::C2PS, 3, false}, "default"));
  const Tessellation closed = tessellatePatchSet(set, 2);
  for (Patch& p : set.patches) p.edgeLevelDelta = {};
  const Tessellation repaired = tessellatePatchSet(set, 2);
  CHECK(closed.splitEdges == 0);
  CHECK(countTessellationEdges(closed).watertight());
  CHECK(repaired.splitEdges > 0);
  CHECK(countTessellationEdges(repaired).watertight());
  CHECK(closed.positions.size() > repaired.positions.size());
}

TEST_CASE("tessellation writers: a non-finite value or a missing colour is refused, naming the input and the vertex") {
  const PatchSet set = extractPatches(Refinement(asset("cap6_paraboloid.obj"), {Scheme::C2PS, 1, false}, "cap6"));
  Tessellation mesh = tessellatePatchSet(set, 2);
  TessellationFileInfo info;
  info.source = "cap6.obj";
  info.colours.assign(mesh.positions.size(), glm::vec3(0.5f));
  CHECK(plyBytes(mesh, info).size() > mesh.positions.size() * 75);
  CHECK(glbBytes(mesh, info).size() % 4 == 0);

  Tessellation broken = mesh;
  broken.mean[7] = std::nan("");
  for (auto bytes : {plyBytes, glbBytes}) {
    try {
      bytes(broken, info);
      FAIL("accepted a NaN");
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).rfind("cap6.obj: the tessellation has a non-finite mean curvature at vertex 7", 0) == 0);
    }
  }
  info.colours.pop_back();
  CHECK_THROWS_AS(plyBytes(mesh, info), InputError);
  CHECK_THROWS_AS(glbBytes(mesh, info), InputError);
}
