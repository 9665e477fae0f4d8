#include "core/mesh/ev_to_polar.h"

#include <algorithm>

#include "core/mesh/topology.h"

namespace polarview {

namespace {

// The quads around v in rotational order as (e_i, f_i) with quad i = (v, e_i, f_i, e_{i+1}); empty
// when v is not an interior vertex with only quads around it, or the ring repeats a vertex.
bool quadRing(const PolyMesh& mesh, const MeshTopology& topo, Index v, std::vector<Index>& e, std::vector<Index>& f,
              std::vector<Index>& faces) {
  e.clear();
  f.clear();
  faces.clear();
  if (topo.vertexOnBoundary[v] || !topo.vertexUsed[v]) return false;
  for (Index k = topo.vertexFaceStart[v]; k < topo.vertexFaceStart[v + 1]; ++k) {
    const Index face = topo.vertexFaces[k];
    if (mesh.faceSize(face) != 4) return false;
    const Index corner = topo.vertexCorners[k] - mesh.faceStart[face];
    const Index* loop = mesh.face(face);
    e.push_back(loop[(corner + 1) % 4]);
    f.push_back(loop[(corner + 2) % 4]);
    faces.push_back(face);
    // Rotational order around v: the next face shares the edge (v, loop[corner - 1]).
  }
  const size_t n = faces.size();
  // Faces are counter-clockwise: quad (v, e_i, f_i, g_i) ends at g_i, which must be the next e.
  // Reorder so that quad i's last vertex is quad i+1's e.
  std::vector<size_t> order(1, 0);
  std::vector<uint8_t> used(n, 0);
  used[0] = 1;
  for (size_t step = 1; step < n; ++step) {
    const Index* loop = mesh.face(faces[order.back()]);
    const Index corner = Index(std::find(loop, loop + 4, v) - loop);
    const Index last = loop[(corner + 3) % 4];
    size_t next = n;
    for (size_t j = 0; j < n; ++j)
      if (!used[j] && e[j] == last) next = j;
    if (next == n) return false;
    used[next] = 1;
    order.push_back(next);
  }
  std::vector<Index> e2, f2, faces2;
  for (size_t i : order) e2.push_back(e[i]), f2.push_back(f[i]), faces2.push_back(faces[i]);
  e.swap(e2);
  f.swap(f2);
  faces.swap(faces2);
  std::vector<Index> ring = e;
  ring.insert(ring.end(), f.begin(), f.end());
  ring.push_back(v);
  std::sort(ring.begin(), ring.end());
  return std::adjacent_find(ring.begin(), ring.end()) == ring.end();
}

}  // namespace

PolarConversion convertExtraordinaryToPolar(const PolyMesh& mesh, bool pentagons, const std::string& sourceName) {
  const MeshTopology topo = buildTopology(mesh, sourceName);
  PolarConversion out;
  out.mesh.points = mesh.points;
  std::vector<uint8_t> faceTaken(mesh.faceCount(), 0), vertexTaken(mesh.vertexCount(), 0);
  std::vector<Index> e, f, faces;
  PolyMesh added;  // faces of the converted regions
  for (Index v = 0; v < mesh.vertexCount(); ++v) {
    if (topo.vertexOnBoundary[v] || !topo.vertexUsed[v] || topo.valence(v) == 4) continue;
    if (!quadRing(mesh, topo, v, e, f, faces)) continue;  // not all quads (a pole, a triangle fan...)
    // Skip a region that touches one already converted (its quads' vertices are taken).
    bool overlaps = false;
    for (Index face : faces)
      for (int c = 0; c < 4; ++c) overlaps = overlaps || vertexTaken[mesh.face(face)[c]];
    if (overlaps) {
      out.skipped.push_back(v);
      continue;
    }
    for (Index face : faces) {
      faceTaken[face] = 1;
      for (int c = 0; c < 4; ++c) vertexTaken[mesh.face(face)[c]] = 1;
    }
    const Index n = Index(faces.size());
    const Point& p = mesh.points[v];
    auto addPoint = [&](const Point& x) {
      out.mesh.points.push_back(x);
      return Index(out.mesh.points.size() - 1);
    };
    std::vector<Index> w(n), second(n);
    for (Index i = 0; i < n; ++i) {
      const Point& q = mesh.points[e[i]];
      w[i] = addPoint(pentagons ? p + (q - p) / 3.0 : 0.5 * (p + q));
    }
    if (pentagons) {
      for (Index i = 0; i < n; ++i) second[i] = addPoint(p + 2.0 * (mesh.points[e[i]] - p) / 3.0);
      for (Index i = 0; i < n; ++i) {
        const Index j = (i + 1) % n;
        added.addFace({v, w[i], w[j]});
        added.addFace({w[i], second[i], second[j], w[j]});
        added.addFace({second[i], e[i], f[i], e[j], second[j]});
      }
    } else {
      for (Index i = 0; i < n; ++i) {
        const Index j = (i + 1) % n;
        second[i] = addPoint(0.25 * (p + mesh.points[e[i]] + mesh.points[f[i]] + mesh.points[e[j]]));  // u_i
      }
      for (Index i = 0; i < n; ++i) {
        const Index j = (i + 1) % n;
        added.addFace({v, w[i], second[i]});
        added.addFace({v, second[i], w[j]});
        added.addFace({w[i], e[i], f[i], second[i]});
        added.addFace({second[i], f[i], e[j], w[j]});
      }
    }
    out.converted.push_back(v);
  }
  for (Index face = 0; face < mesh.faceCount(); ++face)
    if (!faceTaken[face]) out.mesh.addFace(mesh.face(face), size_t(mesh.faceSize(face)));
  for (Index face = 0; face < added.faceCount(); ++face) out.mesh.addFace(added.face(face), size_t(added.faceSize(face)));
  return out;
}

}  // namespace polarview
