#include "pipeline/mesh_report.h"

#include <algorithm>
#include <numeric>

#include "core/mesh/ngon_to_fan.h"
#include "core/subdiv/catmull_clark.h"
#include "core/subdiv/refiner.h"

namespace polarview {

const char* outerName(PolarConfig::Outer outer) {
  switch (outer) {
    case PolarConfig::Outer::Pole: return "pole";
    case PolarConfig::Outer::Boundary: return "boundary";
    case PolarConfig::Outer::Mesh: return "mesh";
  }
  return "?";
}

// What `scheme` does at a polar configuration, in words.
std::string schemeAction(Scheme scheme, const PolarConfig& c, bool radialMesh) {
  std::string why;
  if (!schemeRefinesPole(scheme, c, &why))
    return "Catmull-Clark (valence " + std::to_string(c.valence) + " stays; extraordinary vertex)" +
           (!schemeTraits(scheme).polar() || !c.refinable ? "" : ": " + why);
  const SchemeTraits& traits = schemeTraits(scheme);
  if (!traits.keepsValence) return std::string(traits.label) + " rules (1)-(5): valence doubles each level";
  return std::string(traits.label) + (radialMesh ? " radial refinement of the whole mesh (valence fixed)"
                            : " radial refinement of links 0.." + std::to_string(c.linkCount) +
                                  ", refined periodically to meet Catmull-Clark");
}

// Number of boundary loops: connected components of the boundary edges.
int countBoundaryLoops(const MeshTopology& topo) {
  std::vector<Index> parent(topo.vertexCount);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](Index v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<uint8_t> onBoundary(topo.vertexCount, 0);
  for (Index e = 0; e < topo.edgeCount; ++e)
    if (topo.edgeOnBoundary(e)) {
      Index a = topo.edgeVerts[2 * e], b = topo.edgeVerts[2 * e + 1];
      onBoundary[a] = onBoundary[b] = 1;
      parent[find(a)] = find(b);
    }
  int loops = 0;
  for (Index v = 0; v < topo.vertexCount; ++v) loops += onBoundary[v] && find(v) == v;
  return loops;
}

// The poles apart from rejected candidates: on a triangle mesh nearly every vertex is such a
// candidate, and Catmull-Clark refines it.
namespace {

void findPoles(const PolyMesh& mesh, const MeshTopology& topo, MeshReport& r) {
  for (PolarConfig& c : findPolarConfigs(mesh, topo)) (c.refinable ? r.poles : r.rejected).push_back(std::move(c));
  for (const PolarConfig& c : r.rejected) ++r.rejectedPerReason[c.rejection];
  if (!r.poles.empty()) {
    try {
      r.radialMesh = refinesRadially(mesh, Scheme::RTS);
    } catch (const std::exception&) {
    }
  }
}

}  // namespace

MeshReport reportMesh(const PolyMesh& input, const PolyMesh& mesh, const MeshTopology& topo) {
  MeshReport r;
  findPoles(mesh, topo, r);
  std::vector<uint8_t> isPole(topo.vertexCount, 0);
  for (const PolarConfig& c : r.poles) isPole[c.pole] = 1;
  for (Index v = 0; v < topo.vertexCount; ++v) r.used += topo.vertexUsed[v];
  r.copies = mesh.vertexCount() - input.vertexCount();  // the split's extra vertices
  r.used -= r.copies;
  // Hole faces (`t hole`, and the boundary faces of `t interpolateboundary 0`): no surface there.
  const std::vector<uint8_t> holes = baseHoles(mesh, topo);
  r.holeFaces = int(std::count(holes.begin(), holes.end(), uint8_t(1)));
  for (Index f = 0; f < mesh.faceCount(); ++f) {
    int k = mesh.faceSize(f);
    r.triangles += k == 3;
    r.quads += k == 4;
    r.polygons += k > 4;
  }
  for (Index v = 0; v < topo.vertexCount; ++v) {
    if (!topo.vertexUsed[v]) continue;
    int k = topo.valence(v);
    bool boundary = topo.vertexOnBoundary[v];
    if ((!boundary && k != 4) || (boundary && k > 3)) r.extraordinary.push_back({v, k, boundary, bool(isPole[v])});
  }
  r.loops = countBoundaryLoops(topo);
  r.fanFaces = countFanFaces(input);
  return r;
}

ReportValue meshInfoValue(const std::string& file, const PolyMesh& mesh, const MeshTopology& topo, const ManifoldSplit& split,
                          const MeshReport& r) {
  ReportBuilder w(file);
  w.beginObject();
  w.field("file", file).field("vertices", r.used).field("unreferenced_vertices", topo.vertexCount - r.used);
  w.field("faces", mesh.faceCount()).field("edges", topo.edgeCount).field("triangles", r.triangles);
  w.field("quads", r.quads).field("polygons", r.polygons).field("boundary_loops", r.loops);
  w.field("closed", r.loops == 0).field("radial_mesh", r.radialMesh);
  w.field("non_manifold_edges", split.nonManifoldEdges).field("non_manifold_vertices", split.nonManifoldVertices);
  w.field("hole_faces", r.holeFaces);
  w.key("poles").beginArray();
  for (const PolarConfig& c : r.poles) {
    w.beginObject().field("vertex", c.pole).field("valence", c.valence).field("links", c.linkCount);
    w.field("regular_links", c.regularLinks).field("outer", outerName(c.outer));
    if (c.oppositePole >= 0) w.field("opposite_pole", c.oppositePole);
    w.field("refinable", true);
    w.key("schemes").beginObject();
    for (const SchemeTraits& s : schemeTable()) w.field(s.name, schemeAction(s.scheme, c, r.radialMesh));
    w.endObject().endObject();
  }
  w.endArray();
  w.key("rejected_candidates").beginArray();
  for (const PolarConfig& c : r.rejected) {
    w.beginObject().field("vertex", c.pole).field("valence", c.valence);
    w.field("reason", polarRejectionKey(c.rejection)).field("detail", c.reason).endObject();
  }
  w.endArray();
  w.key("rejected_reasons").beginObject();
  for (const auto& [rejection, count] : r.rejectedPerReason) w.field(polarRejectionKey(rejection), count);
  w.endObject();
  // The text's grouping: per reason, the nearest candidates first (vertex ids).
  w.key("rejected_groups").beginArray();
  for (const RejectedGroup& group : groupRejectedCandidates(r.rejected)) {
    w.beginObject().field("reason", polarRejectionKey(group.rejection)).field("words", polarRejectionWords(group.rejection));
    w.field("max_valence", r.rejected[group.members.front()].valence).key("vertices").beginArray();
    for (size_t k : group.members) w.value(r.rejected[k].pole);
    w.endArray().endObject();
  }
  w.endArray();
  w.key("extraordinary_vertices").beginArray();
  for (const Extraordinary& x : r.extraordinary) {
    w.beginObject().field("vertex", x.vertex).field("valence", x.valence).field("boundary", x.boundary);
    w.field("pole", x.pole);
    w.field("treatment", x.pole ? "polar scheme (c2ps/rts/bps); Catmull-Clark under cc" : "Catmull-Clark in every scheme");
    w.endObject();
  }
  w.endArray().endObject();
  return w.take();
}

std::string meshInfoJson(const std::string& file, const PolyMesh& mesh, const MeshTopology& topo, const ManifoldSplit& split,
                         const MeshReport& r) {
  return reportJson(meshInfoValue(file, mesh, topo, split, r));
}

ReportValue meshInfoValue(const std::string& file, const PolyMesh& input) {
  ManifoldSplit split;  // a non-manifold input: its poles are the split mesh's (manifold_split.h)
  MeshTopology topo;
  const PolyMesh& mesh = refinableMesh(input, split, topo, file);
  return meshInfoValue(file, mesh, topo, split, reportMesh(input, mesh, topo));
}

}  // namespace polarview
