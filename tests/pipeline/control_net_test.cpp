// The control net's segments: each edge once, crease and non-manifold edges marked (control_net.h).
#include <doctest/doctest.h>

#include <algorithm>

#include "core/mesh/shapes.h"
#include "core/mesh/topology.h"
#include "pipeline/control_net.h"

using namespace polarview;

TEST_CASE("control net: each edge once, with its crease sharpness; non-manifold edges infinitely sharp") {
  PolyMesh cube = shapes::cube();
  const MeshTopology topo = buildTopology(cube);
  const Index e0 = 0, e1 = 5;
  const Index a0 = std::min(topo.edgeVerts[2 * e0], topo.edgeVerts[2 * e0 + 1]), b0 = std::max(topo.edgeVerts[2 * e0], topo.edgeVerts[2 * e0 + 1]);
  const Index a1 = std::min(topo.edgeVerts[2 * e1], topo.edgeVerts[2 * e1 + 1]), b1 = std::max(topo.edgeVerts[2 * e1], topo.edgeVerts[2 * e1 + 1]);
  cube.tags.creases = {{a0, b0, 1.5}, {a1, b1, kInfiniteSharpness}};
  std::sort(cube.tags.creases.begin(), cube.tags.creases.end(),
            [](const CreaseEdge& x, const CreaseEdge& y) { return x.v0 != y.v0 ? x.v0 < y.v0 : x.v1 < y.v1; });
  const std::vector<NetSegment> segments = controlNetSegments(cube);
  CHECK(segments.size() == size_t(topo.edgeCount));  // 12, not 24 face sides
  size_t sharp = 0;
  for (const NetSegment& s : segments) {
    CHECK(s.a < s.b);
    if (s.a == a0 && s.b == b0) CHECK(s.sharpness == 1.5f);
    else if (s.a == a1 && s.b == b1) CHECK(s.sharpness == float(kInfiniteSharpness));
    else CHECK(s.sharpness == 0.0f);
    sharp += s.sharpness > 0.0f;
  }
  CHECK(sharp == 2);
  // Colours: smooth grey, sharper redder.
  CHECK(netSegmentColor(0.0f).x < 0.2);
  CHECK(netSegmentColor(10.0f).x > 0.8);
  CHECK(netSegmentColor(10.0f).y < netSegmentColor(0.5f).y);

  // A third face on an edge: that edge is non-manifold and drawn as infinitely sharp.
  PolyMesh fin;
  for (int i = 0; i < 5; ++i) fin.points.emplace_back(i % 2, i / 2, i * 0.1);
  fin.addFace({0, 1, 2});
  fin.addFace({1, 0, 3});
  fin.addFace({1, 0, 4});
  const std::vector<NetSegment> finSegments = controlNetSegments(fin);
  CHECK(finSegments.size() == 7);
  for (const NetSegment& s : finSegments) CHECK((s.sharpness >= float(kInfiniteSharpness)) == (s.a == 0 && s.b == 1));
}
