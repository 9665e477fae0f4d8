// Feature-adaptive patch extraction (rules and end-cap construction: patch_extraction.h).
// [SECTION] vertex and face classification
// [SECTION] regular patches: gathering the 4x4 stencil
// [SECTION] end caps: limit points, tangents, Bezier nets
// [SECTION] pole caps
// [SECTION] level jumps across patch edges (T-junctions)
// [SECTION] extraction driver
#include "core/spline/patch_extraction.h"

#include "core/mesh/constants.h"

#include "core/subdiv/catmull_clark.h"
#include "core/subdiv/face_regularity.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <cmath>
#include <memory>
#include <unordered_map>
#include <utility>

namespace polarview {

namespace {

// [SECTION] vertex and face classification

// The levels patches come from: a uniform Refinement (every face of every level, regular children
// of regular faces skipped), or an AdaptiveRefinement (only its needed faces, whose stencils must
// be exact: checked, since a miss would silently change the surface).
struct LevelStack {
  std::vector<const RefinedLevel*> levels;
  std::vector<const std::vector<uint8_t>*> needed, exact;  // adaptive only
  std::vector<const std::vector<uint8_t>*> radialRefined;  // adaptive only: faces refined radially
  bool radial = false;

  // Levels 0..count()-1; an adaptive refinement may hold deeper ones, which this stack ignores.
  int count() const { return int(levels.size()); }
  const RefinedLevel& level(int m) const { return *levels[size_t(m)]; }
  bool adaptive() const { return !needed.empty(); }
  bool isNeeded(int m, Index f) const { return !adaptive() || (*needed[size_t(m)])[f]; }
  // Whether face f of level m was refined radially (its children keep its columns).
  // The finest level of the stack refines nothing.
  bool refinedRadially(int m, Index f) const { return adaptive() && m + 1 < count() && (*radialRefined[size_t(m)])[f]; }
  // Throws std::logic_error when a patch of face f at level m reads a vertex that is not exact.
  void checkExact(int m, Index v, Index f) const {
    if (adaptive() && !(*exact[size_t(m)])[v])
      throw std::logic_error("adaptive refinement: the patch of face " + std::to_string(f) + " at level " + std::to_string(m) +
                             " reads vertex " + std::to_string(v) + ", which is not exact");
  }
};

struct LevelClasses {
  std::vector<VertexClass> vertex;
  std::vector<uint8_t> faceRegular;  // 1 when the face gets a B-spline patch at this level
};

// Children of a regular face are regular (the vertex, edge and face points of an all-quad regular
// neighbourhood keep valence 4, or 3 on the boundary), so only the other faces' vertices are
// classified, on demand.
LevelClasses classifyLevel(const LevelStack& stack, int m, const LevelClasses& parent) {
  const RefinedLevel& level = stack.level(m);
  const PolyMesh& mesh = level.mesh;
  const MeshTopology& topo = level.topology;
  const bool inherit = !stack.adaptive() && !parent.faceRegular.empty() && level.faceParent.size() == size_t(mesh.faceCount());
  LevelClasses classes;
  classes.vertex.assign(mesh.vertexCount(), VertexClass::Unknown);
  markSharpVertices(mesh, topo, level.sharpness, classes.vertex.data());
  classes.faceRegular.assign(mesh.faceCount(), 0);
  for (Index f = 0; f < mesh.faceCount(); ++f) {
    if (level.isHole(f)) continue;  // no patch
    if (inherit && parent.faceRegular[level.faceParent[f]]) {
      classes.faceRegular[f] = 1;
      continue;
    }
    if (!stack.isNeeded(m, f)) continue;
    classes.faceRegular[f] = isRegularFace(mesh, topo, f, classes.vertex.data());
  }
  return classes;
}

// Per vertex: up to two poles whose links 1..5 hold it (two for short globes), -1 otherwise.
struct RingMembership {
  std::vector<int32_t> first, second;
  bool holds(Index v, int pole) const { return first[v] == pole || second[v] == pole; }
};

RingMembership markRingLinks(const RefinedLevel& level) {
  RingMembership rings;
  rings.first.assign(level.mesh.vertexCount(), -1);
  rings.second.assign(level.mesh.vertexCount(), -1);
  for (size_t p = 0; p < level.poles.size(); ++p) {
    const PolarConfig& config = level.poles[p];
    const size_t count = size_t(std::min(config.linkCount, 5)) * config.valence;
    for (size_t k = 0; k < count && k < config.links.size(); ++k) {
      const Index v = config.links[k];
      if (rings.first[v] < 0) rings.first[v] = int32_t(p);
      else if (rings.first[v] != int32_t(p)) rings.second[v] = int32_t(p);
    }
  }
  return rings;
}

// [SECTION] regular patches: gathering the 4x4 stencil

Index nextCorner(const PolyMesh& mesh, Index face, Index corner) {
  const Index start = mesh.faceStart[face];
  return start + (corner - start + 1) % mesh.faceSize(face);
}

Index cornerAt(const PolyMesh& mesh, Index face, Index vertex) {
  for (Index c = mesh.faceStart[face]; c < mesh.faceStart[face + 1]; ++c)
    if (mesh.faceVerts[c] == vertex) return c;
  return -1;
}

// The 16 stencil vertex ids of a regular face, ids[4*j + i] as in patch.h; -1 where the point is a
// phantom beyond the boundary. `sideMissing[s]` tells whether side s (corner s -> s+1) is a
// boundary edge or infinitely sharp (face_regularity.h: a crease cuts like a boundary).
void gatherStencil(const PolyMesh& mesh, const MeshTopology& topo, const CreaseSharpness& sharpness, Index f,
                   std::array<Index, 16>& ids, std::array<bool, 4>& sideMissing) {
  ids.fill(-1);
  const Index* loop = mesh.face(f);
  // Grid positions (i, j) of the face corners, of the outward points of each side (at its first
  // and second corner) and of the diagonal point at each corner.
  static constexpr int kInner[4][2] = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  static constexpr int kOutward[4][2][2] = {{{1, 0}, {2, 0}}, {{3, 1}, {3, 2}}, {{2, 3}, {1, 3}}, {{0, 2}, {0, 1}}};
  static constexpr int kDiagonal[4][2] = {{0, 0}, {3, 0}, {3, 3}, {0, 3}};
  auto at = [&](const int (&ij)[2]) -> Index& { return ids[4 * ij[1] + ij[0]]; };
  for (int c = 0; c < 4; ++c) at(kInner[c]) = loop[c];
  for (int s = 0; s < 4; ++s) {
    const Index edge = topo.cornerEdge[mesh.faceStart[f] + s];
    const Index g = topo.faceAcross(edge, f);
    sideMissing[s] = isPatchCut(topo, &sharpness, edge);
    if (sideMissing[s]) continue;
    // g runs v_{s+1} -> v_s; after v_s come the point outward of v_s, then the one outward of v_{s+1}.
    const Index c = nextCorner(mesh, g, cornerAt(mesh, g, loop[s]));
    at(kOutward[s][0]) = mesh.faceVerts[c];
    at(kOutward[s][1]) = mesh.faceVerts[nextCorner(mesh, g, c)];
  }
  for (int c = 0; c < 4; ++c) {
    const Index v = loop[c];
    bool cut = false;  // on the boundary or a crease: the diagonal is mirrored later
    for (Index k = topo.vertexEdgeStart[v]; k < topo.vertexEdgeStart[v + 1] && !cut; ++k) cut = isPatchCut(topo, &sharpness, topo.vertexEdges[k]);
    if (cut) continue;
    // Interior valence 4: the face two steps round v from f is diagonal; take its corner opposite v.
    const Index first = topo.vertexFaceStart[v];
    Index k = first;
    while (topo.vertexFaces[k] != f) ++k;
    const Index diagonalCorner = topo.vertexCorners[first + (k - first + 2) % 4];
    const Index diagonalFace = topo.cornerFace[diagonalCorner];
    at(kDiagonal[c]) = mesh.faceVerts[nextCorner(mesh, diagonalFace, nextCorner(mesh, diagonalFace, diagonalCorner))];
  }
}

// Control points of a regular face: mesh points, phantoms mirrored (patch_extraction.h).
void fillControlPoints(const std::vector<Point>& points, const std::array<Index, 16>& ids,
                       const std::array<bool, 4>& sideMissing, std::array<Point, 16>& cp) {
  auto P = [&](int i, int j) -> Point& { return cp[4 * j + i]; };
  for (int k = 0; k < 16; ++k)
    if (ids[k] >= 0) cp[k] = points[ids[k]];
  // Sides first (the rows/columns next to a boundary edge), then the corners beyond them.
  for (int t = 1; t <= 2; ++t) {
    if (sideMissing[0]) P(t, 0) = 2.0 * P(t, 1) - P(t, 2);
    if (sideMissing[2]) P(t, 3) = 2.0 * P(t, 2) - P(t, 1);
    if (sideMissing[3]) P(0, t) = 2.0 * P(1, t) - P(2, t);
    if (sideMissing[1]) P(3, t) = 2.0 * P(2, t) - P(1, t);
  }
  // Corner (i, j) sits between a row side and a column side; mirror along whichever is missing.
  auto mirrorCorner = [&](int i, int j, int rowSide, int columnSide, int di, int dj) {
    if (ids[4 * j + i] >= 0) return;
    if (sideMissing[rowSide]) P(i, j) = 2.0 * P(i, j + dj) - P(i, j + 2 * dj);
    else if (sideMissing[columnSide]) P(i, j) = 2.0 * P(i + di, j) - P(i + 2 * di, j);
  };
  mirrorCorner(0, 0, 0, 3, 1, 1);
  mirrorCorner(3, 0, 0, 1, -1, 1);
  mirrorCorner(3, 3, 2, 1, -1, -1);
  mirrorCorner(0, 3, 2, 3, 1, -1);
}

// [SECTION] end caps: limit points, tangents, Bezier nets

// The point diagonal to vertex v in face `face` (corner c at v) between its edges to `a` and `b`:
// the opposite vertex of a quad; for other faces the parallelogram completion of the centroid,
// 4 centroid - v - a - b, which equals it for quads.
Point diagonalPoint(const PolyMesh& mesh, Index face, Index corner, const Point& v, const Point& a, const Point& b) {
  const Index size = mesh.faceSize(face);
  if (size == 4) return mesh.points[mesh.faceVerts[nextCorner(mesh, face, nextCorner(mesh, face, corner))]];
  Point sum(0.0);
  for (Index c = mesh.faceStart[face]; c < mesh.faceStart[face + 1]; ++c) sum += mesh.points[mesh.faceVerts[c]];
  return (4.0 / size) * sum - v - a - b;
}

// Catmull-Clark limit data at a face corner: limit point and the limit tangents along the face's
// two edges there (patch_extraction.h), in the parameter scale of a regular B-spline patch.
struct CornerFrame {
  Point limit{}, towardNext{}, towardPrev{};
  Point point{};        // the control point itself
  double weight = 4.0;  // Loop-Schaefer interior-point weight: valence (4 at boundary vertices)
};

// The limit point of a vertex and what its limit tangents along each of its edges need, computed
// once per vertex: every face around an extraordinary vertex of valence k asks for it, and
// recomputing the O(k) sums per face made end caps O(k^2) around it (10k-valent: 4.6 s).
struct VertexLimit {
  Point point{}, limit{};
  double weight = 4.0;
  bool boundary = false;
  // Interior: the tangent along edge i is cos(step i) cosine + sin(step i) sine (the mask's sums
  // over j of cos(step (j - i)) split by the angle-difference identity). Boundary: the ring itself.
  Point cosine{}, sine{};
  std::vector<Point> e, f;                    // boundary vertices only
  std::vector<std::pair<Index, Index>> edges;  // (edge id, position in the ring), sorted by edge id
};

class LimitFrames {
 public:
  LimitFrames(const PolyMesh& mesh, const MeshTopology& topo) : mesh_(mesh), topo_(topo) {}

  // Limit point and tangents at corner `corner` (an index into faceVerts) of `face`. [O(valence)
  // the first time a vertex is asked for, O(log valence) after]
  CornerFrame at(Index face, Index corner) {
    const Index v = mesh_.faceVerts[corner];
    const VertexLimit& vl = vertex(v);
    CornerFrame frame;
    frame.point = vl.point;
    frame.limit = vl.limit;
    frame.weight = vl.weight;
    // The face's outgoing and incoming edges at this corner, found in v's edge ring.
    const Index start = mesh_.faceStart[face], size = mesh_.faceSize(face);
    const Index previous = start + (corner - start + size - 1) % size;
    frame.towardNext = tangent(vl, ringPosition(vl, topo_.cornerEdge[corner]));
    frame.towardPrev = tangent(vl, ringPosition(vl, topo_.cornerEdge[previous]));
    return frame;
  }

 private:
  const VertexLimit& vertex(Index v) {
    auto [it, inserted] = cache_.try_emplace(v);
    if (inserted) compute(v, it->second);
    return it->second;
  }

  void compute(Index v, VertexLimit& out) {
    const Index edgeFirst = topo_.vertexEdgeStart[v], faceFirst = topo_.vertexFaceStart[v];
    const Index k = topo_.valence(v), faces = topo_.faceValence(v);
    out.boundary = topo_.vertexOnBoundary[v] != 0;
    out.point = mesh_.points[v];
    std::vector<Point>& e = ring_.e;
    std::vector<Point>& f = ring_.f;
    e.resize(k);
    f.resize(faces);
    for (Index j = 0; j < k; ++j) e[j] = mesh_.points[topo_.otherEnd(topo_.vertexEdges[edgeFirst + j], v)];
    for (Index j = 0; j < faces; ++j)
      f[j] = diagonalPoint(mesh_, topo_.vertexFaces[faceFirst + j], topo_.vertexCorners[faceFirst + j], out.point, e[j],
                           e[(j + 1) % k]);
    out.edges.resize(k);
    for (Index j = 0; j < k; ++j) out.edges[j] = {topo_.vertexEdges[edgeFirst + j], j};
    std::sort(out.edges.begin(), out.edges.end());
    if (out.boundary) {
      out.limit = (e.front() + 4.0 * out.point + e.back()) / 6.0;
      out.e = e;
      out.f = f;
      return;
    }
    Point edgeSum(0.0), faceSum(0.0);
    for (Index j = 0; j < k; ++j) edgeSum += e[j], faceSum += f[j];
    const double kd = double(k);
    const LimitMask mask = catmullClarkLimitMask(kd);
    out.limit = mask.vertex * out.point + mask.edge * edgeSum + mask.diagonal * faceSum;
    out.weight = kd;
    // Catmull-Clark tangent mask (Halstead, Kass, DeRose 1993), normalised so that a planar
    // symmetric k-ring with unit spokes has a unit tangent (k = 4: exactly 1/12):
    // t_i = scale sum_j A cos(step (j - i)) e_j + (cos(step (j - i)) + cos(step (j + 1 - i))) f_j.
    const double step = 2.0 * kPi / kd;
    const double A = 1.0 + std::cos(step) + std::cos(step / 2.0) * std::sqrt(2.0 * (9.0 + std::cos(step)));
    const double scale = 1.0 / (kd * (0.5 * A + 1.0 + std::cos(step)));
    Point cosine(0.0), sine(0.0);
    for (Index j = 0; j < k; ++j) {
      const double a = step * double(j), b = step * double(j + 1);
      cosine += (A * std::cos(a)) * e[j] + (std::cos(a) + std::cos(b)) * f[j];
      sine += (A * std::sin(a)) * e[j] + (std::sin(a) + std::sin(b)) * f[j];
    }
    out.cosine = scale * cosine;
    out.sine = scale * sine;
  }

  static Index ringPosition(const VertexLimit& vl, Index edge) {
    auto it = std::lower_bound(vl.edges.begin(), vl.edges.end(), std::pair<Index, Index>{edge, Index(-1)});
    return it != vl.edges.end() && it->first == edge ? it->second : 0;
  }

  // Limit tangent along edge i of the vertex's ring (patch_extraction.h). Both faces on an edge
  // read the same cached data, so their boundary curves agree. [O(1)]
  static Point tangent(const VertexLimit& vl, Index i) {
    if (vl.boundary) {
      const Index k = Index(vl.e.size());
      if (i == 0) return 0.5 * (vl.e.front() - vl.e.back());
      if (i == k - 1) return 0.5 * (vl.e.back() - vl.e.front());
      return (vl.f[i - 1] + 4.0 * vl.e[i] + vl.f[i]) / 6.0 - vl.limit;
    }
    const double angle = 2.0 * kPi * double(i) / double(vl.weight);
    return std::cos(angle) * vl.cosine + std::sin(angle) * vl.sine;
  }

  struct Scratch {
    std::vector<Point> e, f;  // edge neighbours e_j and diagonals f_j (face j between edges j, j+1)
  };
  const PolyMesh& mesh_;
  const MeshTopology& topo_;
  std::unordered_map<Index, VertexLimit> cache_;
  Scratch ring_;
};

using Bezier = std::array<Point, 4>;

// The Hermite cubic of the edge from corner a to the next corner b: depends only on the edge
// (both faces on it compute the same curve, up to direction).
Bezier edgeCurve(const CornerFrame& a, const CornerFrame& b) {
  return {a.limit, a.limit + a.towardNext / 3.0, b.limit + b.towardPrev / 3.0, b.limit};
}

// Bezier net b[i][j] (i along u) -> B-spline control points cp[4*j + i] of the same surface.
std::array<Point, 16> bezierToBSpline(const std::array<Point, 16>& b) {
  auto convert = [](const Point& b0, const Point& b1, const Point& b2, const Point& b3, Point* d, int stride) {
    d[0] = 6.0 * b0 - 7.0 * b1 + 2.0 * b2;
    d[stride] = 2.0 * b1 - b2;
    d[2 * stride] = 2.0 * b2 - b1;
    d[3 * stride] = 6.0 * b3 - 7.0 * b2 + 2.0 * b1;
  };
  std::array<Point, 16> rows, cp;
  for (int j = 0; j < 4; ++j) convert(b[4 * j], b[4 * j + 1], b[4 * j + 2], b[4 * j + 3], &rows[4 * j], 1);
  for (int i = 0; i < 4; ++i) convert(rows[i], rows[4 + i], rows[8 + i], rows[12 + i], &cp[i], 4);
  return cp;
}

// Loop-Schaefer interior Bezier point at corner `at` with neighbours a, b along the face and d
// diagonal.
Point interiorPoint(const CornerFrame& at, const Point& a, const Point& b, const Point& d) {
  return (at.weight * at.point + 2.0 * (a + b) + d) / (at.weight + 5.0);
}

// End cap of a quad face (patch_extraction.h).
Patch quadEndCap(const PolyMesh& mesh, Index f, LimitFrames& limits) {
  const Index start = mesh.faceStart[f];
  CornerFrame frames[4];
  for (int c = 0; c < 4; ++c) frames[c] = limits.at(f, start + c);
  std::array<Point, 16> b;
  auto B = [&](int i, int j) -> Point& { return b[4 * j + i]; };
  // Boundary curves, side s from corner s to s+1; grid positions of its 4 Bezier points.
  static constexpr int kSide[4][4][2] = {{{0, 0}, {1, 0}, {2, 0}, {3, 0}},
                                         {{3, 0}, {3, 1}, {3, 2}, {3, 3}},
                                         {{3, 3}, {2, 3}, {1, 3}, {0, 3}},
                                         {{0, 3}, {0, 2}, {0, 1}, {0, 0}}};
  for (int s = 0; s < 4; ++s) {
    const Bezier curve = edgeCurve(frames[s], frames[(s + 1) % 4]);
    for (int k = 0; k < 4; ++k) B(kSide[s][k][0], kSide[s][k][1]) = curve[k];
  }
  const Point p[4] = {frames[0].point, frames[1].point, frames[2].point, frames[3].point};
  B(1, 1) = interiorPoint(frames[0], p[1], p[3], p[2]);
  B(2, 1) = interiorPoint(frames[1], p[2], p[0], p[3]);
  B(2, 2) = interiorPoint(frames[2], p[3], p[1], p[0]);
  B(1, 2) = interiorPoint(frames[3], p[0], p[2], p[1]);
  Patch patch;
  patch.cp = bezierToBSpline(b);
  return patch;
}

// End caps of a k-gon (k != 4): k quads (corner, edge midpoint, centre, previous edge midpoint).
// Only at level 0 or at a pole left without a cap, so the per-face buffers do not matter.
void polygonEndCaps(const PolyMesh& mesh, Index f, LimitFrames& limits, std::vector<Patch>& out) {
  const Index k = mesh.faceSize(f), start = mesh.faceStart[f];
  std::vector<CornerFrame> frames(k);
  for (Index c = 0; c < k; ++c) frames[c] = limits.at(f, start + c);
  // Halves of each edge curve by de Casteljau at 1/2.
  std::vector<Bezier> firstHalf(k), secondHalf(k);
  Point centre(0.0);
  for (Index c = 0; c < k; ++c) {
    const Bezier e = edgeCurve(frames[c], frames[(c + 1) % k]);
    const Point m01 = 0.5 * (e[0] + e[1]), m12 = 0.5 * (e[1] + e[2]), m23 = 0.5 * (e[2] + e[3]);
    const Point m012 = 0.5 * (m01 + m12), m123 = 0.5 * (m12 + m23), mid = 0.5 * (m012 + m123);
    firstHalf[c] = {e[0], m01, m012, mid};
    secondHalf[c] = {mid, m123, m23, e[3]};
    centre += mid / double(k);
  }
  auto spoke = [&](Index c) {  // straight, from edge c's midpoint to the centre
    const Point& m = firstHalf[c][3];
    return Bezier{m, m + (centre - m) / 3.0, m + 2.0 * (centre - m) / 3.0, centre};
  };
  for (Index c = 0; c < k; ++c) {
    const Index prev = (c + k - 1) % k;
    const Bezier row0 = firstHalf[c], row3 = spoke(prev), column3 = spoke(c);
    const Bezier& back = secondHalf[prev];  // runs from edge prev's midpoint to this corner
    std::array<Point, 16> b;
    auto B = [&](int i, int j) -> Point& { return b[4 * j + i]; };
    for (int t = 0; t < 4; ++t) {
      B(t, 0) = row0[t];
      B(0, t) = back[3 - t];
      B(3, t) = column3[t];
      B(t, 3) = row3[t];
    }
    // Zero-twist interior points.
    B(1, 1) = B(1, 0) + B(0, 1) - B(0, 0);
    B(2, 1) = B(2, 0) + B(3, 1) - B(3, 0);
    B(1, 2) = B(0, 2) + B(1, 3) - B(0, 3);
    B(2, 2) = B(3, 2) + B(2, 3) - B(3, 3);
    Patch patch;
    patch.cp = bezierToBSpline(b);
    out.push_back(patch);
  }
}

// [SECTION] pole caps

// One PoleCap per column of a pole (patch.h layout), closing the disc inside link 2.
// Positions relative to `origin` (the pole's frame).
void poleCaps(const PolarGrid& grid, const TaylorCoefficients& taylor, const Point& origin, std::vector<Patch>& out, int level,
              int pole) {
  const int n = grid.n;
  auto boundaryPoint = [&](int j) { return (grid.q(1, j) + 4.0 * grid.q(2, j) + grid.q(3, j)) / 6.0; };
  // Radial derivative of the ring patch between links 2-3 at link 2 (per unit r: link i at r = i).
  auto crossDerivative = [&](int j) { return 0.5 * (grid.q(3, j) - grid.q(1, j)); };
  for (int j = 0; j < n; ++j) {
    Patch cap;
    cap.kind = PatchKind::PoleCap;
    cap.origin = origin;
    for (int k = 0; k < 6; ++k) cap.cp[k] = taylor.p[k];
    for (int k = 0; k < 4; ++k) cap.cp[6 + k] = boundaryPoint(j - 1 + k);
    for (int k = 0; k < 4; ++k) cap.cp[12 + k] = crossDerivative(j - 1 + k);
    cap.cp[10] = Point(double(j) / n, 1.0 / n, 2.0);
    cap.cp[11] = Point(double(taylor.order), 0.0, 0.0);
    cap.level = uint8_t(std::clamp(level, 0, 255));
    cap.ring = level;
    cap.pole = pole;
    cap.face = -1;
    out.push_back(cap);
  }
}

// [SECTION] level jumps across patch edges (T-junctions)

// The 4 sides of a face-based patch are the face's sides (patch.h EDGES); a k-gon's split end caps
// (k != 4) have other sides and take no part.
bool hasFaceSides(const Patch& patch, const LevelStack& refinement) {
  return patch.face >= 0 && refinement.level(patch.level).mesh.faceSize(patch.face) == 4;
}

// Fills Patch::edgeLevelDelta. cover[m][f] = the patch covering face f of level m: its own, an
// ancestor's (the face was not refined further for patches), or a cap's (hole faces), -1 where the
// surface there comes from finer levels. A patch side facing an uncovered face is a coarse side;
// one facing a face covered by a coarser patch Q is a fine side, and tells Q's side which faces
// the ancestor of its own face at Q's level. [O(faces of all levels + patches * level jump)]
void markLevelJumps(const LevelStack& refinement, std::vector<std::vector<int32_t>>& cover, std::vector<Patch>& patches) {
  const int levels = refinement.count();
  constexpr int32_t kHole = -2;  // a hole face (and its children): no surface across a side facing it
  for (int m = 0; m < levels; ++m)
    for (size_t f = 0; f < refinement.level(m).faceHole.size(); ++f)
      if (refinement.level(m).faceHole[f]) cover[m][f] = kHole;
  for (size_t k = 0; k < patches.size(); ++k)
    if (hasFaceSides(patches[k], refinement) && cover[patches[k].level][patches[k].face] == -1)
      cover[patches[k].level][patches[k].face] = int32_t(k);
  for (int m = 1; m < levels; ++m) {
    const std::vector<Index>& parent = refinement.level(m).faceParent;
    for (size_t f = 0; f < cover[m].size(); ++f)
      if (cover[m][f] == -1) cover[m][f] = cover[m - 1][parent[f]];
  }
  // Levels apart: a side's neighbour is looked up for every patch, its level decides.
  std::vector<uint8_t> patchLevel(patches.size());
  for (size_t k = 0; k < patches.size(); ++k) patchLevel[k] = patches[k].level;
  for (Patch& patch : patches) {
    if (!hasFaceSides(patch, refinement)) continue;
    const int m = patch.level;
    const RefinedLevel& level = refinement.level(m);
    for (int s = 0; s < 4; ++s) {
      const Index across = level.topology.faceAcross(level.topology.cornerEdge[level.mesh.faceStart[patch.face] + s], patch.face);
      if (across < 0) continue;
      const int32_t q = cover[m][across];
      if (q == kHole) continue;
      if (q < 0) {  // refined further: this is the coarse side (the fine sides set the exact jump)
        // unless refined radially: the finer rings keep the columns, so the side meets them whole
        if (!refinement.refinedRadially(m, across)) patch.edgeLevelDelta[s] = std::max<int8_t>(patch.edgeLevelDelta[s], 1);
        continue;
      }
      const int jump = m - int(patchLevel[size_t(q)]);
      if (jump <= 0) continue;  // the usual case, decided without touching the (large) patch
      Patch& coarse = patches[q];
      if (!hasFaceSides(coarse, refinement)) continue;
      bool keptColumns = true;  // every step from the coarse patch's level to this one radial
      for (Index face = patch.face, k = m; k > coarse.level && keptColumns; --k) {
        face = refinement.level(k).faceParent[face];
        keptColumns = refinement.refinedRadially(k - 1, face);
      }
      if (keptColumns) continue;
      patch.edgeLevelDelta[s] = int8_t(-std::min(jump, 127));
      // The ancestor of this face at the coarse level lies across one of the coarse patch's sides.
      Index ancestor = patch.face;
      for (int k = m; k > coarse.level; --k) ancestor = refinement.level(k).faceParent[ancestor];
      const RefinedLevel& coarseLevel = refinement.level(coarse.level);
      for (int t = 0; t < 4; ++t) {
        const Index edge = coarseLevel.topology.cornerEdge[coarseLevel.mesh.faceStart[coarse.face] + t];
        if (coarseLevel.topology.faceAcross(edge, coarse.face) == ancestor)
          coarse.edgeLevelDelta[t] = int8_t(std::max(int(coarse.edgeLevelDelta[t]), std::min(jump, 127)));
      }
    }
  }
}

}  // namespace

int transitionEdgeSegments(int level, int delta, int densityExponent) {
  const int wanted = densityExponent - level;
  const int exponent = delta > 0 ? std::min(std::max(wanted, int(delta)), 6) : std::min(std::max(wanted, 0), std::max(6 + delta, 0));
  return 1 << exponent;
}

// [SECTION] extraction driver

namespace {

// What level m contributes: its regular (boundary, polar-ring) patches whose parent was not
// regular, level jumps not yet set, with their sources.
struct LevelRegularPatches {
  std::vector<Patch> patches;
  std::vector<std::array<Index, 16>> stencil;
  std::vector<uint8_t> sidesMissing;
  std::vector<uint8_t> faceRegular;  // per face of the level (classifyLevel)
};

void extractRegular(const LevelStack& refinement, int m, const LevelClasses& classes, const LevelClasses& parentClasses,
                    LevelRegularPatches& out) {
  const RefinedLevel& level = refinement.level(m);
  const PolyMesh& mesh = level.mesh;
  const MeshTopology& topo = level.topology;
  const RingMembership rings = markRingLinks(level);
  const size_t regular = size_t(std::count(classes.faceRegular.begin(), classes.faceRegular.end(), uint8_t(1)));
  out.patches.reserve(regular);
  out.stencil.reserve(regular);
  out.sidesMissing.reserve(regular);
  std::array<Index, 16> ids;
  std::array<bool, 4> sideMissing;
  for (Index f = 0; f < mesh.faceCount(); ++f) {
    if (!classes.faceRegular[f]) continue;
    if (!refinement.adaptive() && m > 0 && parentClasses.faceRegular[level.faceParent[f]]) continue;
    gatherStencil(mesh, topo, level.sharpness, f, ids, sideMissing);
    for (Index id : ids)
      if (id >= 0) refinement.checkExact(m, id, f);
    Patch patch;
    fillControlPoints(mesh.points, ids, sideMissing, patch.cp);
    patch.origin = level.origin(ids[5]);  // a stencil lies in one frame (adaptive_refiner.h, Precision)
    const bool boundary = sideMissing[0] || sideMissing[1] || sideMissing[2] || sideMissing[3];
    patch.kind = boundary ? PatchKind::Boundary : PatchKind::Regular;
    for (int32_t candidate : {rings.first[ids[5]], rings.second[ids[5]]}) {
      if (candidate < 0) continue;
      bool inRing = true;
      for (Index id : ids) inRing = inRing && (id < 0 || rings.holds(id, candidate));
      if (!inRing) continue;
      patch.kind = PatchKind::PolarRing;
      patch.ring = m;
      patch.pole = candidate;
      break;
    }
    patch.level = uint8_t(std::min(m, 255));
    patch.face = f;
    out.patches.push_back(patch);
    out.stencil.push_back(ids);
    uint8_t missing = 0;
    for (int side = 0; side < 4; ++side) missing |= uint8_t(sideMissing[side]) << side;
    out.sidesMissing.push_back(missing);
  }
}

// What the finest level adds: pole caps (replacing the faces around each pole and its 1-link,
// `holeFaces`, with the index in `patches` of the pole's first cap) and end caps for every other
// needed face that is not regular.
struct FinestLevelCaps {
  std::vector<Patch> patches;
  std::vector<std::pair<Index, int32_t>> holeFaces;
};

void extractCaps(const LevelStack& refinement, int m, const std::vector<uint8_t>& faceRegular, FinestLevelCaps& out) {
  const RefinedLevel& level = refinement.level(m);
  const PolyMesh& mesh = level.mesh;
  const MeshTopology& topo = level.topology;
  std::vector<uint8_t> inHole(mesh.faceCount(), 0);
  for (size_t p = 0; p < level.poles.size(); ++p) {
    if (p >= level.poleTaylor.size() || p >= level.poleGrids.size() || level.poleGrids[p].links < 3) continue;
    const PolarConfig& pole = level.poles[p];
    refinement.checkExact(m, pole.pole, -1);
    for (int k = 0; k < level.poleGrids[p].links * pole.valence; ++k) refinement.checkExact(m, pole.links[size_t(k)], -1);
    const int32_t firstCap = int32_t(out.patches.size());
    poleCaps(level.poleGrids[p], level.poleTaylor[p], level.origin(pole.pole), out.patches, m, int(p));
    auto markFaces = [&](Index v) {
      for (Index k = topo.vertexFaceStart[v]; k < topo.vertexFaceStart[v + 1]; ++k) {
        inHole[topo.vertexFaces[k]] = 1;
        out.holeFaces.emplace_back(topo.vertexFaces[k], firstCap);  // same level as ring L: no level jump
      }
    };
    markFaces(pole.pole);
    for (int j = 0; j < pole.valence; ++j) markFaces(pole.links[j]);
  }
  // End caps for everything else not covered.
  LimitFrames limits(mesh, topo);
  for (Index f = 0; f < mesh.faceCount(); ++f) {
    if (faceRegular[f] || inHole[f] || level.isHole(f) || !refinement.isNeeded(m, f)) continue;
    if (refinement.adaptive())  // the limit frames read the faces around each corner
      for (Index c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; ++c)
        for (Index k = topo.vertexFaceStart[mesh.faceVerts[c]]; k < topo.vertexFaceStart[mesh.faceVerts[c] + 1]; ++k) {
          const Index g = topo.vertexFaces[k];
          for (Index d = mesh.faceStart[g]; d < mesh.faceStart[g + 1]; ++d) refinement.checkExact(m, mesh.faceVerts[d], f);
        }
    const size_t first = out.patches.size();
    if (mesh.faceSize(f) == 4) out.patches.push_back(quadEndCap(mesh, f, limits));
    else polygonEndCaps(mesh, f, limits, out.patches);
    for (size_t k = first; k < out.patches.size(); ++k) {
      out.patches[k].origin = level.origin(mesh.faceVerts[mesh.faceStart[f]]);
      out.patches[k].kind = PatchKind::EndCap;
      out.patches[k].level = uint8_t(std::min(m, 255));
      out.patches[k].face = f;
    }
  }
}

// The patch set of the stack's levels: each level's regular patches, then the finest level's caps
// (in that order: PatchSet's), level jumps marked over the whole. [O(patches + faces of all levels)]
template <class RegularOfLevel>
PatchSet assembleSet(const LevelStack& refinement, RegularOfLevel regularOf, const FinestLevelCaps& caps,
                     PatchSources* sources, std::vector<Patch> storage = {}) {
  PatchSet set;
  set.patches = std::move(storage);  // its memory, already touched: no page faults for it
  set.patches.clear();
  const int finest = refinement.count() - 1;
  size_t total = caps.patches.size();
  for (int m = 0; m <= finest; ++m) total += regularOf(m).patches.size();
  set.patches.reserve(total);
  if (sources) {
    sources->stencil.clear();
    sources->sidesMissing.clear();
    sources->stencil.reserve(total);
    sources->sidesMissing.reserve(total);
  }
  for (int m = 0; m <= finest; ++m) {
    const LevelRegularPatches& level = regularOf(m);
    set.patches.insert(set.patches.end(), level.patches.begin(), level.patches.end());
    if (sources) {
      sources->stencil.insert(sources->stencil.end(), level.stencil.begin(), level.stencil.end());
      sources->sidesMissing.insert(sources->sidesMissing.end(), level.sidesMissing.begin(), level.sidesMissing.end());
    }
  }
  const int32_t capsStart = int32_t(set.patches.size());
  set.patches.insert(set.patches.end(), caps.patches.begin(), caps.patches.end());
  // Radial levels (RTS/BPS caps and globes) keep the columns: patches of different levels meet
  // along whole edges there, so no side is a T-junction.
  if (!refinement.radial) {
    // Per level and face: the covering patch (markLevelJumps); here only the pole caps' hole faces.
    std::vector<std::vector<int32_t>> cover(size_t(finest) + 1);
    for (int m = 0; m <= finest; ++m) cover[m].assign(refinement.level(m).mesh.faceCount(), -1);
    for (const auto& [face, firstCap] : caps.holeFaces) cover[finest][face] = capsStart + firstCap;
    markLevelJumps(refinement, cover, set.patches);
  }
  for (const Patch& patch : set.patches) ++set.kindCounts[size_t(patch.kind)];
  if (sources) {  // caps are remade from their face or pole
    sources->stencil.resize(set.patches.size());
    sources->sidesMissing.resize(set.patches.size());
  }
  return set;
}

PatchSet extractFromStack(const LevelStack& refinement, PatchSources* sources) {
  const int finest = refinement.count() - 1;
  std::vector<LevelRegularPatches> regular(size_t(finest) + 1);
  LevelClasses parentClasses;
  for (int m = 0; m <= finest; ++m) {
    LevelClasses classes = classifyLevel(refinement, m, parentClasses);
    extractRegular(refinement, m, classes, parentClasses, regular[size_t(m)]);
    parentClasses = std::move(classes);
  }
  FinestLevelCaps caps;
  extractCaps(refinement, finest, parentClasses.faceRegular, caps);
  return assembleSet(refinement, [&](int m) -> const LevelRegularPatches& { return regular[size_t(m)]; }, caps, sources);
}

// Control points only, from the levels' current points: every patch made as extractFromStack made
// it (sources: its stencils), kind, level and level jumps kept.
void refreshFromStack(const LevelStack& refinement, const PatchSources& sources, PatchSet& set) {
  if (sources.stencil.size() != set.patches.size())
    throw std::invalid_argument("refreshPatches: the sources are not those of this patch set");
  std::unique_ptr<LimitFrames> limits;  // of the end caps' level (the set's finest)
  int limitsLevel = -1;
  std::vector<Patch> made;
  std::array<bool, 4> sideMissing;
  for (size_t k = 0; k < set.patches.size();) {
    Patch& patch = set.patches[k];
    const RefinedLevel& level = refinement.level(patch.level);
    if (patch.kind == PatchKind::PoleCap || patch.kind == PatchKind::EndCap) {
      // Caps come in runs (a pole's sectors, a polygon's quads): remake the run, keep the rest.
      made.clear();
      if (patch.kind == PatchKind::PoleCap) {
        poleCaps(level.poleGrids[size_t(patch.pole)], level.poleTaylor[size_t(patch.pole)],
                 level.origin(level.poles[size_t(patch.pole)].pole), made, patch.level, patch.pole);
      } else {
        if (limitsLevel != patch.level) limits = std::make_unique<LimitFrames>(level.mesh, level.topology);
        limitsLevel = patch.level;
        if (level.mesh.faceSize(patch.face) == 4) made.push_back(quadEndCap(level.mesh, patch.face, *limits));
        else polygonEndCaps(level.mesh, patch.face, *limits, made);
      }
      const Point origin = patch.kind == PatchKind::PoleCap ? (made.empty() ? Point(0.0) : made.front().origin)
                                                             : level.origin(level.mesh.faceVerts[level.mesh.faceStart[patch.face]]);
      for (size_t i = 0; i < made.size() && k + i < set.patches.size(); ++i) {
        set.patches[k + i].cp = made[i].cp;
        set.patches[k + i].origin = origin;
      }
      k += std::max<size_t>(made.size(), 1);
      continue;
    }
    for (int side = 0; side < 4; ++side) sideMissing[side] = (sources.sidesMissing[k] >> side) & 1;
    fillControlPoints(level.mesh.points, sources.stencil[k], sideMissing, patch.cp);
    patch.origin = level.origin(sources.stencil[k][5]);
    ++k;
  }
}

// Levels 0..finest of `refinement` (-1: all).
LevelStack stackOf(const AdaptiveRefinement& refinement, int finest = -1) {
  LevelStack stack;
  const int count = finest < 0 ? refinement.levelCount() : std::min(finest + 1, refinement.levelCount());
  for (int m = 0; m < count; ++m) {
    stack.levels.push_back(&refinement.level(m));
    stack.needed.push_back(&refinement.neededFaces(m));
    stack.exact.push_back(&refinement.exactVertices(m));
    stack.radialRefined.push_back(&refinement.radiallyRefinedFaces(m));
  }
  stack.radial = refinement.radialOnly();
  return stack;
}

}  // namespace

PatchSet extractPatches(const Refinement& refinement) {
  if (!refinement.finestHasVertexRings())
    throw std::logic_error("extractPatches: the finest level has no vertex rings (Refinement::completeFinestTopology)");
  LevelStack stack;
  for (int m = 0; m < refinement.levelCount(); ++m) stack.levels.push_back(&refinement.level(m));
  stack.radial = refinement.radialOnly();
  return extractFromStack(stack, nullptr);
}

PatchSet extractPatches(const AdaptiveRefinement& refinement, PatchSources* sources) {
  return extractFromStack(stackOf(refinement), sources);
}

void refreshPatches(const AdaptiveRefinement& refinement, const PatchSources& sources, PatchSet& set) {
  refreshFromStack(stackOf(refinement), sources, set);
}

struct LevelPatchCache::Impl {
  std::vector<LevelRegularPatches> regular;   // levels extracted so far (0..size-1)
  std::vector<std::unique_ptr<FinestLevelCaps>> caps;  // per level, made when it was a set's finest
};

LevelPatchCache::LevelPatchCache() : impl_(std::make_unique<Impl>()) {}
LevelPatchCache::~LevelPatchCache() = default;
LevelPatchCache::LevelPatchCache(LevelPatchCache&&) noexcept = default;
LevelPatchCache& LevelPatchCache::operator=(LevelPatchCache&&) noexcept = default;

void LevelPatchCache::prepare(const AdaptiveRefinement& refinement, int finest) {
  if (finest < 0 || finest >= refinement.levelCount())
    throw std::invalid_argument("LevelPatchCache: level " + std::to_string(finest) + " of a refinement of " +
                                std::to_string(refinement.levelCount() - 1) + " levels");
  const LevelStack stack = stackOf(refinement, finest);
  Impl& cache = *impl_;
  LevelClasses parentClasses;  // unused by adaptive stacks (no inheritance)
  for (int m = int(cache.regular.size()); m <= finest; ++m) {
    const LevelClasses classes = classifyLevel(stack, m, parentClasses);
    LevelRegularPatches level;
    extractRegular(stack, m, classes, parentClasses, level);
    level.faceRegular = classes.faceRegular;
    cache.regular.push_back(std::move(level));
  }
  if (cache.caps.size() <= size_t(finest)) cache.caps.resize(size_t(finest) + 1);
  if (!cache.caps[size_t(finest)]) {
    auto caps = std::make_unique<FinestLevelCaps>();
    extractCaps(stack, finest, cache.regular[size_t(finest)].faceRegular, *caps);
    cache.caps[size_t(finest)] = std::move(caps);
  }
}

PatchSet LevelPatchCache::patchSet(const AdaptiveRefinement& refinement, int finest, PatchSources* sources,
                                   std::vector<Patch> storage) {
  prepare(refinement, finest);
  const LevelStack stack = stackOf(refinement, finest);
  Impl& cache = *impl_;
  return assembleSet(stack, [&](int m) -> const LevelRegularPatches& { return cache.regular[size_t(m)]; },
                     *cache.caps[size_t(finest)], sources, std::move(storage));
}

std::pair<size_t, size_t> LevelPatchCache::preparedCounts(int finest) const {
  const Impl& cache = *impl_;
  if (finest < 0 || size_t(finest) >= cache.caps.size() || !cache.caps[size_t(finest)]) return {0, 0};
  return {sharedPrefix(finest, finest), cache.caps[size_t(finest)]->patches.size()};
}

size_t LevelPatchCache::sharedPrefix(int a, int b) const {
  size_t count = 0;
  for (int m = 0; m <= std::min(a, b) && m < int(impl_->regular.size()); ++m) count += impl_->regular[size_t(m)].patches.size();
  return count;
}

void LevelPatchCache::forget(int fromLevel) {
  const size_t keep = size_t(std::max(fromLevel, 0));
  if (impl_->regular.size() > keep) impl_->regular.resize(keep);
  if (impl_->caps.size() > keep) impl_->caps.resize(keep);
}

}  // namespace polarview
