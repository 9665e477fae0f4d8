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
#include "core/subdiv/parallel_for.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <cmath>
#include <memory>
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
  // Adaptive only, per level: it equals its parent level in faces, tables and flags (a fixed point,
  // AdaptiveRefinement::repeatsParentLevel): its classification and stencils are the parent's.
  std::vector<uint8_t> repeatsParent;
  bool radial = false;

  // Levels 0..count()-1; an adaptive refinement may hold deeper ones, which this stack ignores.
  int count() const { return int(levels.size()); }
  const RefinedLevel& level(int m) const { return *levels[size_t(m)]; }
  bool adaptive() const { return !needed.empty(); }
  bool repeats(int m) const { return m >= 1 && size_t(m) < repeatsParent.size() && repeatsParent[size_t(m)]; }
  // Whether face f of level m was refined radially (its children keep its columns).
  // The finest level of the stack refines nothing.
  bool refinedRadially(int m, Index f) const { return adaptive() && m + 1 < count() && (*radialRefined[size_t(m)])[f]; }
  // Whether a patch of level m may read any vertex: uniform, or every vertex exact (then the
  // per-vertex checks are skipped). [O(vertices of the level)]
  bool everyVertexExact(int m) const {
    if (!adaptive()) return true;
    const std::vector<uint8_t>& flags = *exact[size_t(m)];
    return std::find(flags.begin(), flags.end(), uint8_t(0)) == flags.end();
  }
  // Throws std::logic_error when a patch of face f at level m reads a vertex that is not exact.
  void checkExact(int m, Index v, Index f) const {
    if (adaptive() && !(*exact[size_t(m)])[v])
      throw std::logic_error("adaptive refinement: the patch of face " + std::to_string(f) + " at level " + std::to_string(m) +
                             " reads vertex " + std::to_string(v) + ", which is not exact");
  }
};

// Per patch of a set, apart from the (large) patches, and known before they are made: its level,
// its face where the patch's 4 sides are the face's sides (patch.h EDGES), else -1 (pole caps, a
// k-gon's split end caps: no part in level jumps), and the faces across those sides. The level
// jumps are found from it alone, so that each patch is written once, whole.
struct SetIndex {
  std::vector<Index> face;
  std::vector<uint8_t> level;
  std::vector<std::array<Index, 4>> across;  // -1 on the boundary (and where face is -1)

  size_t size() const { return face.size(); }
  void reserve(size_t count) {
    face.reserve(count);
    level.reserve(count);
    across.reserve(count);
  }
  void add(Index patchFace, int patchLevel, const std::array<Index, 4>& acrossSides) {
    face.push_back(patchFace);
    level.push_back(uint8_t(std::min(patchLevel, 255)));
    across.push_back(acrossSides);
  }
  void append(const SetIndex& other) {
    face.insert(face.end(), other.face.begin(), other.face.end());
    level.insert(level.end(), other.level.begin(), other.level.end());
    across.insert(across.end(), other.across.begin(), other.across.end());
  }
};

// What one level's classification finds, in face order: the faces its regular patches come from
// (entries of a SetIndex) and the faces left for end caps (should it be the finest level).
struct LevelFaces {
  size_t firstPatch = 0, patchCount = 0;  // regular, and (uniform stacks) the parent was not
  std::vector<Index> capFaces;            // not regular, not holes (adaptive: needed)
  std::vector<uint8_t> faceRegular;       // uniform stacks only: per face, for the children's inheritance
  std::vector<VertexClass> vertexClass;   // per vertex; Unknown where nothing asked (gatherStencil reads it)
  bool quadsOnly = false;                 // every face of the level a quad (Catmull-Clark's levels >= 1)
};

// Whether every face of the mesh is a quad (then quad f's corners start at 4 f). [O(faces)]
bool hasQuadsOnly(const PolyMesh& mesh) {
  if (mesh.faceStart.front() != 0) return false;
  for (Index f = 0; f < mesh.faceCount(); ++f)
    if (mesh.faceSize(f) != 4) return false;
  return true;
}

// classifyVertex (face_regularity.h) once per vertex; on a level of quads only, without looking at
// the faces around it.
VertexClass vertexClassOf(const RefinedLevel& level, LevelFaces& faces, Index v) {
  VertexClass& known = faces.vertexClass[size_t(v)];
  if (known != VertexClass::Unknown) return known;
  if (!faces.quadsOnly) return known = classifyVertex(level.mesh, level.topology, v);
  const MeshTopology& topo = level.topology;
  if (!topo.vertexOnBoundary[v]) return known = topo.valence(v) == 4 && topo.faceValence(v) == 4 ? VertexClass::Interior : VertexClass::Irregular;
  return known = topo.valence(v) == 3 && topo.faceValence(v) == 2 ? VertexClass::Boundary : VertexClass::Irregular;
}

// isRegularFace (face_regularity.h) with the level's classes.
bool isRegularFace(const RefinedLevel& level, LevelFaces& faces, Index f) {
  if (level.mesh.faceSize(f) != 4) return false;
  const Index* loop = level.mesh.face(f);
  for (int c = 0; c < 4; ++c)
    if (vertexClassOf(level, faces, loop[c]) == VertexClass::Irregular) return false;
  return true;
}

// The faces across the 4 sides of quad f (-1 on the boundary).
std::array<Index, 4> facesAcross(const RefinedLevel& level, Index f) {
  const Index* edges = level.topology.cornerEdge.data() + level.mesh.faceStart[f];
  std::array<Index, 4> across;
  for (int s = 0; s < 4; ++s) across[size_t(s)] = level.topology.faceAcross(edges[s], f);
  return across;
}

// Adaptive levels: only the needed faces are classified (the others are support for the rules).
void classifyNeededFaces(const LevelStack& stack, int m, LevelFaces& faces, SetIndex& index) {
  const RefinedLevel& level = stack.level(m);
  const std::vector<uint8_t>& needed = *stack.needed[size_t(m)];
  for (Index f = 0; f < level.mesh.faceCount(); ++f) {
    if (!needed[size_t(f)] || level.isHole(f)) continue;  // holes: no patch
    if (isRegularFace(level, faces, f)) index.add(f, m, facesAcross(level, f));
    else faces.capFaces.push_back(f);
  }
}

// Uniform levels: children of a regular face are regular (the vertex, edge and face points of an
// all-quad regular neighbourhood keep valence 4, or 3 on the boundary) and their surface is the
// parent's patch, so only the other faces' vertices are classified.
void classifyAllFaces(const LevelStack& stack, int m, const LevelFaces* parent, LevelFaces& faces, SetIndex& index) {
  const RefinedLevel& level = stack.level(m);
  const Index faceCount = level.mesh.faceCount();
  const bool inherit = parent && !parent->faceRegular.empty() && level.faceParent.size() == size_t(faceCount);
  faces.faceRegular.assign(size_t(faceCount), 0);
  for (Index f = 0; f < faceCount; ++f) {
    if (level.isHole(f)) continue;  // no patch
    if (inherit && parent->faceRegular[size_t(level.faceParent[size_t(f)])]) {
      faces.faceRegular[size_t(f)] = 1;
      continue;
    }
    faces.faceRegular[size_t(f)] = isRegularFace(level, faces, f);
    if (faces.faceRegular[size_t(f)]) index.add(f, m, facesAcross(level, f));
    else faces.capFaces.push_back(f);
  }
}

// A level that repeats its parent (LevelStack::repeats): the parent's classification, its entries
// of `index` appended again at level m (the same faces, the same faces across). [O(patches)]
LevelFaces repeatClassification(const LevelFaces& parent, int m, SetIndex& index) {
  LevelFaces faces;
  faces.capFaces = parent.capFaces;
  faces.vertexClass = parent.vertexClass;
  faces.quadsOnly = parent.quadsOnly;
  faces.firstPatch = index.size();
  faces.patchCount = parent.patchCount;
  index.reserve(index.size() + parent.patchCount);  // no reallocation while its own entries are read
  for (size_t k = parent.firstPatch; k < parent.firstPatch + parent.patchCount; ++k) index.add(index.face[k], m, index.across[k]);
  return faces;
}

// Classifies level m, its regular patches' entries appended to `index`. `parent`: level m-1's
// classification (uniform stacks inherit from it; null at level 0).
LevelFaces classifyLevel(const LevelStack& stack, int m, const LevelFaces* parent, SetIndex& index) {
  const RefinedLevel& level = stack.level(m);
  if (parent && stack.repeats(m)) return repeatClassification(*parent, m, index);
  LevelFaces faces;
  faces.vertexClass.assign(size_t(level.mesh.vertexCount()), VertexClass::Unknown);
  markSharpVertices(level.mesh, level.topology, level.sharpness, faces.vertexClass.data());
  faces.quadsOnly = hasQuadsOnly(level.mesh);
  faces.firstPatch = index.size();
  if (stack.adaptive()) classifyNeededFaces(stack, m, faces, index);
  else classifyAllFaces(stack, m, parent, faces, index);
  faces.patchCount = index.size() - faces.firstPatch;
  return faces;
}

// At most how many regular patches level m of an adaptive stack gives (its needed faces), to make
// room for their index entries at once; 0 for uniform stacks. [O(faces of the level)]
size_t regularBound(const LevelStack& stack, int m) {
  if (!stack.adaptive()) return 0;
  return size_t(std::count(stack.needed[size_t(m)]->begin(), stack.needed[size_t(m)]->end(), uint8_t(1)));
}

// At most how many patches the stack's levels give (regularBound, and each pole of the finest
// level capped).
size_t patchBound(const LevelStack& stack) {
  if (!stack.adaptive()) return 0;
  size_t bound = 0;
  for (int m = 0; m < stack.count(); ++m) bound += regularBound(stack, m);
  for (const PolarGrid& grid : stack.level(stack.count() - 1).poleGrids) bound += size_t(std::max(grid.n, 0));
  return bound;
}

// Per vertex: up to two poles whose links 1..5 hold it (two for short globes), -1 otherwise, and
// where in each pole's links it is (PolarConfig::links: (i - 1) * valence + j).
struct RingMembership {
  std::vector<int32_t> first, second;
  std::vector<int32_t> firstAt, secondAt;
  std::vector<int32_t> valence;  // per pole
  bool holds(Index v, int pole) const { return first[v] == pole || second[v] == pole; }
  int32_t at(Index v, int pole) const { return first[v] == pole ? firstAt[v] : secondAt[v]; }
};

// Empty when the level has no pole (no patch is a PolarRing there).
RingMembership markRingLinks(const RefinedLevel& level) {
  RingMembership rings;
  if (level.poles.empty()) return rings;
  rings.first.assign(level.mesh.vertexCount(), -1);
  rings.second.assign(level.mesh.vertexCount(), -1);
  rings.firstAt.assign(level.mesh.vertexCount(), -1);
  rings.secondAt.assign(level.mesh.vertexCount(), -1);
  for (size_t p = 0; p < level.poles.size(); ++p) {
    const PolarConfig& config = level.poles[p];
    rings.valence.push_back(config.valence);
    const size_t count = size_t(std::min(config.linkCount, 5)) * config.valence;
    for (size_t k = 0; k < count && k < config.links.size(); ++k) {
      const Index v = config.links[k];
      if (rings.first[v] < 0) rings.first[v] = int32_t(p), rings.firstAt[v] = int32_t(k);
      else if (rings.first[v] != int32_t(p)) rings.second[v] = int32_t(p), rings.secondAt[v] = int32_t(k);
    }
  }
  return rings;
}

// [SECTION] regular patches: gathering the 4x4 stencil

Index nextCorner(const PolyMesh& mesh, Index face, Index corner) {
  const Index start = mesh.faceStart[face];
  return start + (corner - start + 1) % mesh.faceSize(face);
}

// The first corner of quad g: every face around a regular face's corners is a quad (a vertex
// touching another face is Irregular, face_regularity.h); on a level of quads only it is 4 g.
Index quadStart(const PolyMesh& mesh, const LevelFaces& faces, Index g) { return faces.quadsOnly ? 4 * g : mesh.faceStart[g]; }

// The 16 stencil vertex ids of a regular face, ids[4*j + i] as in patch.h; -1 where the point is a
// phantom beyond the boundary. `sideMissing[s]` tells whether side s (corner s -> s+1) is a
// boundary edge or infinitely sharp (face_regularity.h: a crease cuts like a boundary).
// `faces`: the level's classification (its vertex classes; a corner not classified yet is here);
// `across[s]`: the face across side s (-1 on the boundary; facesAcross).
void gatherStencil(const RefinedLevel& level, LevelFaces& faces, Index f, const std::array<Index, 4>& across, std::array<Index, 16>& ids,
                   std::array<bool, 4>& sideMissing) {
  const PolyMesh& mesh = level.mesh;
  const MeshTopology& topo = level.topology;
  ids.fill(-1);
  const Index* loop = mesh.face(f);
  // Grid positions (i, j) of the face corners, of the outward points of each side (at its first
  // and second corner) and of the diagonal point at each corner.
  static constexpr int kInner[4][2] = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  static constexpr int kOutward[4][2][2] = {{{1, 0}, {2, 0}}, {{3, 1}, {3, 2}}, {{2, 3}, {1, 3}}, {{0, 2}, {0, 1}}};
  static constexpr int kDiagonal[4][2] = {{0, 0}, {3, 0}, {3, 3}, {0, 3}};
  auto at = [&](const int (&ij)[2]) -> Index& { return ids[4 * ij[1] + ij[0]]; };
  for (int c = 0; c < 4; ++c) at(kInner[c]) = loop[c];
  const Index* edges = topo.cornerEdge.data() + quadStart(mesh, faces, f);
  for (int s = 0; s < 4; ++s) {
    const Index g = across[size_t(s)];
    // isPatchCut: a boundary edge (no face across) or an infinitely sharp one
    sideMissing[s] = g < 0 || (!level.sharpness.empty() && level.sharpness.edge[size_t(edges[s])] >= float(kInfiniteSharpness));
    if (sideMissing[s]) continue;
    // g runs v_{s+1} -> v_s; after v_s come the point outward of v_s, then the one outward of v_{s+1}.
    const Index* quad = mesh.faceVerts.data() + quadStart(mesh, faces, g);
    int c = 0;
    while (quad[c] != loop[s]) ++c;
    at(kOutward[s][0]) = quad[(c + 1) & 3];
    at(kOutward[s][1]) = quad[(c + 2) & 3];
  }
  for (int c = 0; c < 4; ++c) {
    const Index v = loop[c];
    // Only an Interior corner has no boundary or crease edge (a Boundary, Crease or Corner one has
    // a cut edge: its diagonal is mirrored later).
    if (vertexClassOf(level, faces, v) != VertexClass::Interior) continue;
    // Interior valence 4: the face two steps round v from f is diagonal; take its corner opposite v.
    const Index first = topo.vertexFaceStart[v];
    Index k = first;
    while (topo.vertexFaces[k] != f) ++k;
    const Index diagonal = first + ((k - first + 2) & 3);
    const Index start = quadStart(mesh, faces, topo.vertexFaces[diagonal]);
    at(kDiagonal[c]) = mesh.faceVerts[start + ((topo.vertexCorners[diagonal] - start + 2) & 3)];
  }
}

// Control points of a regular face: mesh points, phantoms mirrored (patch_extraction.h).
void fillControlPoints(const std::vector<Point>& points, const std::array<Index, 16>& ids,
                       const std::array<bool, 4>& sideMissing, std::array<Point, 16>& cp) {
  auto P = [&](int i, int j) -> Point& { return cp[4 * j + i]; };
  if (std::all_of(ids.begin(), ids.end(), [](Index id) { return id >= 0; })) {  // nothing to mirror
    for (int k = 0; k < 16; ++k) cp[k] = points[ids[k]];
    return;
  }
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

// What the tangent mask of interior valence k reads, the same numbers for every vertex of that
// valence (so computed once per valence, each as the mask's own expression).
struct ValenceTrig {
  double A = 0.0, scale = 0.0;
  std::vector<double> stepCos, stepSin;  // cos, sin of step j, j = 0..k (step = 2 pi / k)
  std::vector<double> edgeCos, edgeSin;  // cos, sin of the angle of edge i, 2 pi i / k, i = 0..k-1
};

// The limit point of a vertex and what its limit tangents along each of its edges need, computed
// once per vertex: every face around an extraordinary vertex of valence k asks for it, and
// recomputing the O(k) sums per face made end caps O(k^2) around it (10k-valent: 4.6 s).
struct VertexLimit {
  Point point{}, limit{};
  double weight = 4.0;
  bool boundary = false;
  Index valence = 0;
  // Interior: the tangent along edge i is cos(step i) cosine + sin(step i) sine (the mask's sums
  // over j of cos(step (j - i)) split by the angle-difference identity). Boundary: the ring itself.
  Point cosine{}, sine{};
  size_t ring = 0;         // boundary: e_0..e_{k-1}, then f_0..f_{k-2}, from here in LimitFrames' rings
  size_t sortedEdges = 0;  // valence > kScannedRing: (edge id, position) sorted by edge id, from here
  const ValenceTrig* trig = nullptr;  // interior: its valence's
};

class LimitFrames {
 public:
  // `vertices`: about how many vertices will be asked for (room made for them at once).
  LimitFrames(const PolyMesh& mesh, const MeshTopology& topo, size_t vertices = 0) : mesh_(mesh), topo_(topo) {
    limits_.reserve(std::min(vertices, size_t(mesh.vertexCount())));
  }

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
    const Index previous = corner == mesh_.faceStart[face] ? mesh_.faceStart[face + 1] - 1 : corner - 1;
    frame.towardNext = tangent(vl, ringPosition(v, vl, topo_.cornerEdge[corner]));
    frame.towardPrev = tangent(vl, ringPosition(v, vl, topo_.cornerEdge[previous]));
    return frame;
  }

 private:
  static constexpr Index kScannedRing = 16;  // rings up to this valence are searched, not sorted

  const VertexLimit& vertex(Index v) {
    if (slot_.empty()) slot_.assign(size_t(mesh_.vertexCount()), -1);
    int32_t& slot = slot_[size_t(v)];
    if (slot < 0) {
      slot = int32_t(limits_.size());
      compute(v, limits_.emplace_back());
    }
    return limits_[size_t(slot)];
  }

  const ValenceTrig& trig(Index k) {
    if (trig_.size() <= size_t(k)) trig_.resize(size_t(k) + 1);
    std::unique_ptr<ValenceTrig>& table = trig_[size_t(k)];
    if (table) return *table;
    table = std::make_unique<ValenceTrig>();
    // Catmull-Clark tangent mask (Halstead, Kass, DeRose 1993), normalised so that a planar
    // symmetric k-ring with unit spokes has a unit tangent (k = 4: exactly 1/12):
    // t_i = scale sum_j A cos(step (j - i)) e_j + (cos(step (j - i)) + cos(step (j + 1 - i))) f_j.
    const double kd = double(k), step = 2.0 * kPi / kd;
    table->A = 1.0 + std::cos(step) + std::cos(step / 2.0) * std::sqrt(2.0 * (9.0 + std::cos(step)));
    table->scale = 1.0 / (kd * (0.5 * table->A + 1.0 + std::cos(step)));
    for (Index j = 0; j <= k; ++j) {
      table->stepCos.push_back(std::cos(step * double(j)));
      table->stepSin.push_back(std::sin(step * double(j)));
    }
    for (Index i = 0; i < k; ++i) {
      const double angle = 2.0 * kPi * double(i) / kd;
      table->edgeCos.push_back(std::cos(angle));
      table->edgeSin.push_back(std::sin(angle));
    }
    return *table;
  }

  void compute(Index v, VertexLimit& out) {
    const Index edgeFirst = topo_.vertexEdgeStart[v], faceFirst = topo_.vertexFaceStart[v];
    const Index k = topo_.valence(v), faces = topo_.faceValence(v);
    out.boundary = topo_.vertexOnBoundary[v] != 0;
    out.valence = k;
    out.point = mesh_.points[v];
    std::vector<Point>& e = ring_.e;
    std::vector<Point>& f = ring_.f;
    e.resize(k);
    f.resize(faces);
    for (Index j = 0; j < k; ++j) e[j] = mesh_.points[topo_.otherEnd(topo_.vertexEdges[edgeFirst + j], v)];
    for (Index j = 0; j < faces; ++j)
      f[j] = diagonalPoint(mesh_, topo_.vertexFaces[faceFirst + j], topo_.vertexCorners[faceFirst + j], out.point, e[j],
                           e[(j + 1) % k]);
    if (k > kScannedRing) {
      out.sortedEdges = sortedEdges_.size();
      for (Index j = 0; j < k; ++j) sortedEdges_.emplace_back(topo_.vertexEdges[edgeFirst + j], j);
      std::sort(sortedEdges_.begin() + std::ptrdiff_t(out.sortedEdges), sortedEdges_.end());
    }
    if (out.boundary) {
      out.limit = (e.front() + 4.0 * out.point + e.back()) / 6.0;
      out.ring = rings_.size();
      rings_.insert(rings_.end(), e.begin(), e.end());
      rings_.insert(rings_.end(), f.begin(), f.end());
      return;
    }
    Point edgeSum(0.0), faceSum(0.0);
    for (Index j = 0; j < k; ++j) edgeSum += e[j], faceSum += f[j];
    const double kd = double(k);
    const LimitMask mask = catmullClarkLimitMask(kd);
    out.limit = mask.vertex * out.point + mask.edge * edgeSum + mask.diagonal * faceSum;
    out.weight = kd;
    const ValenceTrig& t = trig(k);
    out.trig = &t;
    Point cosine(0.0), sine(0.0);
    for (Index j = 0; j < k; ++j) {
      cosine += (t.A * t.stepCos[j]) * e[j] + (t.stepCos[j] + t.stepCos[j + 1]) * f[j];
      sine += (t.A * t.stepSin[j]) * e[j] + (t.stepSin[j] + t.stepSin[j + 1]) * f[j];
    }
    out.cosine = t.scale * cosine;
    out.sine = t.scale * sine;
  }

  // The position of `edge` in the edge ring of v (0 if absent). [O(log valence)]
  Index ringPosition(Index v, const VertexLimit& vl, Index edge) const {
    if (vl.valence <= kScannedRing) {
      const Index* ring = topo_.vertexEdges.data() + topo_.vertexEdgeStart[v];
      for (Index j = 0; j < vl.valence; ++j)
        if (ring[j] == edge) return j;
      return 0;
    }
    const auto first = sortedEdges_.begin() + std::ptrdiff_t(vl.sortedEdges), last = first + vl.valence;
    auto it = std::lower_bound(first, last, std::pair<Index, Index>{edge, Index(-1)});
    return it != last && it->first == edge ? it->second : 0;
  }

  // Limit tangent along edge i of the vertex's ring (patch_extraction.h). Both faces on an edge
  // read the same cached data, so their boundary curves agree. [O(1)]
  Point tangent(const VertexLimit& vl, Index i) const {
    if (vl.boundary) {
      const Index k = vl.valence;
      const Point* e = rings_.data() + vl.ring;
      const Point* f = e + k;
      if (i == 0) return 0.5 * (e[0] - e[k - 1]);
      if (i == k - 1) return 0.5 * (e[k - 1] - e[0]);
      return (f[i - 1] + 4.0 * e[i] + f[i]) / 6.0 - vl.limit;
    }
    return vl.trig->edgeCos[size_t(i)] * vl.cosine + vl.trig->edgeSin[size_t(i)] * vl.sine;
  }

  struct Scratch {
    std::vector<Point> e, f;  // edge neighbours e_j and diagonals f_j (face j between edges j, j+1)
  };
  const PolyMesh& mesh_;
  const MeshTopology& topo_;
  std::vector<int32_t> slot_;         // per vertex: its entry in limits_, -1 until asked for
  std::vector<VertexLimit> limits_;
  std::vector<Point> rings_;          // boundary vertices' rings (VertexLimit::ring)
  std::vector<std::pair<Index, Index>> sortedEdges_;  // high-valence vertices' edges (VertexLimit::sortedEdges)
  std::vector<std::unique_ptr<ValenceTrig>> trig_;  // by valence
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

// End cap of a quad face (patch_extraction.h): its B-spline control points.
std::array<Point, 16> quadEndCap(const PolyMesh& mesh, Index f, LimitFrames& limits) {
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
  return bezierToBSpline(b);
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
  // First and second radial derivatives of the ring patch between links 2-3 at link 2 (per unit r:
  // link i at r = i).
  auto crossDerivative = [&](int j) { return 0.5 * (grid.q(3, j) - grid.q(1, j)); };
  auto secondDerivative = [&](int j) { return grid.q(1, j) - 2.0 * grid.q(2, j) + grid.q(3, j); };
  for (int j = 0; j < n; ++j) {
    Patch cap;
    cap.kind = PatchKind::PoleCap;
    cap.origin = origin;
    // The tangent plane only where the scheme has no quadratic terms (BPS): p3..p5 stay zero.
    for (int k = 0; k < (taylor.order >= 2 ? 6 : 3); ++k) cap.cp[k] = taylor.p[k];
    for (int k = 0; k < 4; ++k) cap.cp[6 + k] = boundaryPoint(j - 1 + k);
    for (int k = 0; k < 4; ++k) cap.cp[12 + k] = crossDerivative(j - 1 + k);
    for (int k = 0; k < 4; ++k) capSecondPoint(cap, k) = secondDerivative(j - 1 + k);
    cap.sectorCount = n;
    cap.level = uint8_t(std::clamp(level, 0, 255));
    cap.ring = level;
    cap.pole = pole;
    cap.face = -1;
    cap.link = 0;
    cap.sector = j;
    out.push_back(cap);
  }
}

// [SECTION] level jumps across patch edges (T-junctions)

constexpr int32_t kHoleCover = -2;  // a hole face (and its children): no surface across a side facing it

// cover[m][f] = the patch covering face f of level m: its own, an ancestor's (the face was not
// refined further for patches), or a pole cap's (`holeFaces`: finest-level faces with their pole's
// first cap, counted from `capsStart` in the set); kHoleCover for holes; -1 where the surface
// there comes from finer levels.
std::vector<std::vector<int32_t>> coverFaces(const LevelStack& stack, const std::vector<std::pair<Index, int32_t>>& holeFaces,
                                             size_t capsStart, const SetIndex& patches) {
  const int levels = stack.count();
  std::vector<std::vector<int32_t>> cover(static_cast<size_t>(levels));
  for (int m = 0; m < levels; ++m) cover[size_t(m)].assign(size_t(stack.level(m).mesh.faceCount()), -1);
  for (const auto& [face, firstCap] : holeFaces) cover[size_t(levels) - 1][size_t(face)] = int32_t(capsStart) + firstCap;
  for (int m = 0; m < levels; ++m) {
    const std::vector<uint8_t>& hole = stack.level(m).faceHole;
    for (size_t f = 0; f < hole.size(); ++f)
      if (hole[f]) cover[size_t(m)][f] = kHoleCover;
  }
  for (size_t k = 0; k < patches.size(); ++k) {
    if (patches.face[k] < 0) continue;
    int32_t& covered = cover[patches.level[k]][size_t(patches.face[k])];
    if (covered == -1) covered = int32_t(k);
  }
  for (int m = 1; m < levels; ++m) {
    const std::vector<Index>& parent = stack.level(m).faceParent;
    std::vector<int32_t>& level = cover[size_t(m)];
    const std::vector<int32_t>& coarser = cover[size_t(m) - 1];
    for (size_t f = 0; f < level.size(); ++f)
      if (level[f] == -1) level[f] = coarser[size_t(parent[f])];
  }
  return cover;
}

using LevelDeltas = std::vector<std::array<int8_t, 4>>;  // per patch, as Patch::edgeLevelDelta

// Patch k's side s faces a face covered by the coarser patch q, `jump` levels coarser: unless every
// step between them was radial (the columns kept, no jump in parameter), k's side is a fine side,
// and q's side facing the ancestor of k's face at q's level is a coarse side.
void markFineSide(const LevelStack& stack, const SetIndex& index, size_t k, int s, int32_t q, int jump, LevelDeltas& deltas) {
  const int m = index.level[k], coarseLevel = index.level[size_t(q)];
  bool keptColumns = true;  // every step from the coarse patch's level to this one radial
  for (Index face = index.face[k], l = m; l > coarseLevel && keptColumns; --l) {
    face = stack.level(l).faceParent[size_t(face)];
    keptColumns = stack.refinedRadially(l - 1, face);
  }
  if (keptColumns) return;
  deltas[k][size_t(s)] = int8_t(-std::min(jump, 127));
  Index ancestor = index.face[k];
  for (int l = m; l > coarseLevel; --l) ancestor = stack.level(l).faceParent[size_t(ancestor)];
  std::array<int8_t, 4>& coarse = deltas[size_t(q)];
  for (int t = 0; t < 4; ++t)
    if (index.across[size_t(q)][size_t(t)] == ancestor) coarse[size_t(t)] = int8_t(std::max(int(coarse[size_t(t)]), std::min(jump, 127)));
}

// Patch::edgeLevelDelta of every patch of a set (`holeFaces`, `capsStart` as coverFaces'). A patch
// side facing an uncovered face is a coarse side; one facing a face covered by a coarser patch Q is
// a fine side, and tells Q's side (markFineSide). Empty for radial levels (RTS/BPS caps and globes),
// which keep the columns: patches of different levels meet along whole edges there, so no side is
// a T-junction. [O(faces of all levels + patches * level jump)]
LevelDeltas levelJumps(const LevelStack& stack, const std::vector<std::pair<Index, int32_t>>& holeFaces, size_t capsStart,
                       const SetIndex& index) {
  if (stack.radial) return {};
  const std::vector<std::vector<int32_t>> cover = coverFaces(stack, holeFaces, capsStart, index);
  LevelDeltas deltas(index.size());
  for (size_t k = 0; k < index.size(); ++k) {
    if (index.face[k] < 0) continue;
    const int m = index.level[k];
    for (int s = 0; s < 4; ++s) {
      const Index across = index.across[k][size_t(s)];
      if (across < 0) continue;
      const int32_t q = cover[size_t(m)][size_t(across)];
      if (q == kHoleCover) continue;
      if (q < 0) {  // refined further: this is the coarse side (the fine sides set the exact jump)
        // unless refined radially: the finer rings keep the columns, so the side meets them whole
        if (!stack.refinedRadially(m, across)) deltas[k][size_t(s)] = std::max<int8_t>(deltas[k][size_t(s)], 1);
        continue;
      }
      const int jump = m - int(index.level[size_t(q)]);
      if (jump <= 0 || index.face[size_t(q)] < 0) continue;  // the usual case: same level
      markFineSide(stack, index, k, s, q, jump, deltas);
    }
  }
  return deltas;
}

}  // namespace

int transitionEdgeSegments(int level, int delta, int densityExponent) {
  const int wanted = densityExponent - level;
  const int exponent = delta > 0 ? std::min(std::max(wanted, int(delta)), 6) : std::min(std::max(wanted, 0), std::max(6 + delta, 0));
  return 1 << exponent;
}

// [SECTION] extraction driver

namespace {

// Where extracted patches go: the set's own vectors (a one-off extraction: made in place, never
// copied) or a level's in LevelPatchCache. `stencil` and `sidesMissing`: null when no sources are
// wanted.
struct PatchOutput {
  std::vector<Patch>& patches;
  std::array<size_t, 5>& kindCounts;
  std::vector<std::array<Index, 16>>* stencil = nullptr;
  std::vector<uint8_t>* sidesMissing = nullptr;
};

// Patches are made this many ahead of the memory they will take being asked for (tuned on
// catmark_car level 6: 4-16 all about as good; without, a set in cold memory waits on each line).
constexpr size_t kPrefetchPatches = 8;

// Asks for the cache lines of the element `ahead` places past the end of `v` (reserved, not made
// yet), to be written.
template <class T>
void prefetchForWrite(const std::vector<T>& v, size_t ahead) {
#if defined(__GNUC__) || defined(__clang__)
  if (v.size() + ahead >= v.capacity()) return;
  const char* slot = reinterpret_cast<const char*>(v.data() + v.size() + ahead);
  for (size_t line = 0; line < sizeof(T); line += 64) __builtin_prefetch(slot + line, 1);
#else
  (void)v, (void)ahead;
#endif
}

// Where a PolarRing's face lies in its pole's grid (Patch::link, sector, ringTurn): the corner
// whose next corner along u is one link further out is the turned patch's first; its column, counted
// in the direction the turned v runs, is the sector. Left -1 if no corner is (not a grid face).
void setRingPlace(const RingMembership& rings, int32_t pole, const std::array<Index, 16>& ids, Patch& patch) {
  static constexpr int kCorners[4] = {5, 6, 10, 9};  // (u, v) = (0,0), (1,0), (1,1), (0,1)
  const int32_t valence = rings.valence[size_t(pole)];
  int32_t link[4], column[4];
  for (int c = 0; c < 4; ++c) {
    const int32_t at = rings.at(ids[size_t(kCorners[c])], pole);
    link[c] = at / valence + 1;
    column[c] = at % valence;
  }
  for (int turn = 0; turn < 4; ++turn) {
    const int first = turn, alongU = (turn + 1) % 4, alongV = (turn + 3) % 4;
    if (link[alongU] != link[first] + 1 || column[alongU] != column[first] || link[alongV] != link[first]) continue;
    const int32_t step = (column[alongV] - column[first] + valence) % valence;
    if (step != 1 && step != valence - 1) return;
    patch.link = int16_t(link[first]);
    patch.sector = step == 1 ? column[first] : (valence - column[first]) % valence;
    patch.ringTurn = int8_t(turn);
    return;
  }
}

// Kind, ring and pole of a regular patch from its stencil: a PolarRing when the whole stencil lies
// in links 1..5 of one pole.
void setRegularKind(const RingMembership& rings, int m, const std::array<Index, 16>& ids, const std::array<bool, 4>& sideMissing,
                    Patch& patch) {
  const bool boundary = sideMissing[0] || sideMissing[1] || sideMissing[2] || sideMissing[3];
  patch.kind = boundary ? PatchKind::Boundary : PatchKind::Regular;
  if (rings.first.empty()) return;  // no pole at this level
  for (int32_t candidate : {rings.first[ids[5]], rings.second[ids[5]]}) {
    if (candidate < 0) continue;
    bool inRing = true;
    for (Index id : ids) inRing = inRing && (id < 0 || rings.holds(id, candidate));
    if (!inRing) continue;
    patch.kind = PatchKind::PolarRing;
    patch.ring = m;
    patch.pole = candidate;
    setRingPlace(rings, candidate, ids, patch);
    return;
  }
}

// The stencils of a level's regular patches, in their order (ids, and bit s of sidesMissing for
// side s), reused by a level that repeats it (LevelStack::repeats): the same vertex ids.
struct StencilRun {
  const std::array<Index, 16>* ids = nullptr;
  const uint8_t* sidesMissing = nullptr;
};

// Appends level m's regular patches (`faces`' entries of `index`, in order) to `out`, with their
// level jumps (`deltas`, per entry of `index`; empty: none yet) and, when asked, their sources;
// `reuse`: the stencils of the level it repeats, taken instead of gathered.
// Throws std::logic_error if a stencil reads a vertex that is not exact (checked only where some
// vertex of the level is not).
void extractRegular(const LevelStack& stack, int m, LevelFaces& faces, const SetIndex& index, const LevelDeltas& deltas,
                    PatchOutput out, StencilRun reuse = {}) {
  const RefinedLevel& level = stack.level(m);
  const PolyMesh& mesh = level.mesh;
  const bool checkIds = !reuse.ids && !stack.everyVertexExact(m);  // a repeated level's: checked on its parent
  const RingMembership rings = markRingLinks(level);
  std::array<Index, 16> ids;
  std::array<bool, 4> sideMissing;
  for (size_t k = faces.firstPatch; k < faces.firstPatch + faces.patchCount; ++k) {
    const Index f = index.face[k];
    if (reuse.ids) {
      const size_t i = k - faces.firstPatch;
      ids = reuse.ids[i];
      for (int side = 0; side < 4; ++side) sideMissing[size_t(side)] = (reuse.sidesMissing[i] >> side) & 1;
    } else {
      gatherStencil(level, faces, f, index.across[k], ids, sideMissing);
    }
    if (checkIds)
      for (Index id : ids)
        if (id >= 0) stack.checkExact(m, id, f);
    prefetchForWrite(out.patches, kPrefetchPatches);
    Patch& patch = out.patches.emplace_back();
    fillControlPoints(mesh.points, ids, sideMissing, patch.cp);
    patch.origin = level.origin(ids[5]);  // a stencil lies in one frame (adaptive_refiner.h, Precision)
    setRegularKind(rings, m, ids, sideMissing, patch);
    patch.level = uint8_t(std::min(m, 255));
    patch.face = f;
    if (!deltas.empty()) patch.edgeLevelDelta = deltas[k];
    ++out.kindCounts[size_t(patch.kind)];
    if (!out.stencil) continue;
    out.stencil->push_back(ids);
    uint8_t missing = 0;
    for (int side = 0; side < 4; ++side) missing |= uint8_t(sideMissing[side]) << side;
    out.sidesMissing->push_back(missing);
  }
}

// The poles of level m that get caps (Taylor data, at least 3 links).
bool poleGetsCaps(const RefinedLevel& level, size_t p) {
  return p < level.poleTaylor.size() && p < level.poleGrids.size() && level.poleGrids[p].links >= 3;
}

// The caps the finest level m will get, before any is made: pole caps (each pole's first in
// `holeFaces`, counted from the first cap, with the faces around the pole and its 1-link that they
// replace, no level jump against ring m), then end caps for the other cap faces (one per quad, k
// per k-gon), and the index entries of them all.
struct CapPlan {
  std::vector<uint8_t> inHole;                       // per face; empty when no pole gets caps
  std::vector<std::pair<Index, int32_t>> holeFaces;  // (face, its pole's first cap)
  std::vector<Index> endCapFaces;
  SetIndex index;
};

CapPlan planCaps(const LevelStack& stack, int m, const std::vector<Index>& capFaces) {
  const RefinedLevel& level = stack.level(m);
  const MeshTopology& topo = level.topology;
  CapPlan plan;
  int32_t caps = 0;
  for (size_t p = 0; p < level.poles.size(); ++p) {
    if (!poleGetsCaps(level, p)) continue;
    if (plan.inHole.empty()) plan.inHole.assign(size_t(level.mesh.faceCount()), 0);
    const PolarConfig& pole = level.poles[p];
    auto markFaces = [&](Index v) {
      for (Index k = topo.vertexFaceStart[v]; k < topo.vertexFaceStart[v + 1]; ++k) {
        plan.inHole[size_t(topo.vertexFaces[k])] = 1;
        plan.holeFaces.emplace_back(topo.vertexFaces[k], caps);
      }
    };
    markFaces(pole.pole);
    for (int j = 0; j < pole.valence; ++j) markFaces(pole.links[size_t(j)]);
    for (int j = 0; j < level.poleGrids[p].n; ++j, ++caps) plan.index.add(-1, m, {-1, -1, -1, -1});
  }
  for (Index f : capFaces) {
    if (!plan.inHole.empty() && plan.inHole[size_t(f)]) continue;
    plan.endCapFaces.push_back(f);
    if (level.mesh.faceSize(f) == 4) plan.index.add(f, m, facesAcross(level, f));
    else
      for (Index k = 0; k < level.mesh.faceSize(f); ++k) plan.index.add(-1, m, {-1, -1, -1, -1});
  }
  return plan;
}

// Throws std::logic_error unless every vertex of the faces around face f's corners (what its
// limit frames read) is exact.
void checkEndCapExact(const LevelStack& stack, int m, Index f) {
  const PolyMesh& mesh = stack.level(m).mesh;
  const MeshTopology& topo = stack.level(m).topology;
  for (Index c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; ++c)
    for (Index k = topo.vertexFaceStart[mesh.faceVerts[c]]; k < topo.vertexFaceStart[mesh.faceVerts[c] + 1]; ++k) {
      const Index g = topo.vertexFaces[k];
      for (Index d = mesh.faceStart[g]; d < mesh.faceStart[g + 1]; ++d) stack.checkExact(m, mesh.faceVerts[d], f);
    }
}

// Appends the caps `plan` lists for the finest level m to `patches` (pole caps, then end caps).
void extractCaps(const LevelStack& stack, int m, const CapPlan& plan, std::vector<Patch>& patches) {
  const RefinedLevel& level = stack.level(m);
  const PolyMesh& mesh = level.mesh;
  for (size_t p = 0; p < level.poles.size(); ++p) {
    if (!poleGetsCaps(level, p)) continue;
    const PolarConfig& pole = level.poles[p];
    stack.checkExact(m, pole.pole, -1);
    for (int k = 0; k < level.poleGrids[p].links * pole.valence; ++k) stack.checkExact(m, pole.links[size_t(k)], -1);
    poleCaps(level.poleGrids[p], level.poleTaylor[p], level.origin(pole.pole), patches, m, int(p));
  }
  const bool checkIds = !stack.everyVertexExact(m);
  LimitFrames limits(mesh, level.topology, 4 * plan.endCapFaces.size());
  for (Index f : plan.endCapFaces) {
    if (checkIds) checkEndCapExact(stack, m, f);
    const size_t first = patches.size();
    if (mesh.faceSize(f) == 4) patches.emplace_back().cp = quadEndCap(mesh, f, limits);
    else polygonEndCaps(mesh, f, limits, patches);
    for (size_t k = first; k < patches.size(); ++k) {
      patches[k].origin = level.origin(mesh.faceVerts[mesh.faceStart[f]]);
      patches[k].kind = PatchKind::EndCap;
      patches[k].level = uint8_t(std::min(m, 255));
      patches[k].face = f;
    }
  }
}

// The finest level's caps as a set holds them: made by extractCaps, counted, their level jumps
// (`deltas` from patch `capsStart` of the set; empty: none) set.
void appendCaps(const LevelStack& stack, int m, const CapPlan& plan, const LevelDeltas& deltas, size_t capsStart, PatchSet& set) {
  extractCaps(stack, m, plan, set.patches);
  for (size_t k = capsStart; k < set.patches.size(); ++k) {
    if (!deltas.empty()) set.patches[k].edgeLevelDelta = deltas[k];
    ++set.kindCounts[size_t(set.patches[k].kind)];
  }
}

// Clears `sources` and makes room for a set of `count` patches; null when none are wanted.
void startSources(PatchSources* sources, size_t count) {
  if (!sources) return;
  sources->stencil.clear();
  sources->sidesMissing.clear();
  sources->stencil.reserve(count);
  sources->sidesMissing.reserve(count);
}

// Caps are remade from their face or pole: their sources are empty stencils.
void finishSources(PatchSources* sources, size_t count) {
  if (!sources) return;
  sources->stencil.resize(count);
  sources->sidesMissing.resize(count);
}

// Appends `from` to `to`, each patch with its level jumps (`deltas` from `to`'s end; empty: none),
// a few at a time so that a patch is still in cache when its jumps are written.
void appendWithJumps(const std::vector<Patch>& from, const LevelDeltas& deltas, std::vector<Patch>& to) {
  constexpr size_t kChunk = 64;
  for (size_t begin = 0; begin < from.size(); begin += kChunk) {
    const size_t first = to.size(), end = std::min(begin + kChunk, from.size());
    to.insert(to.end(), from.begin() + std::ptrdiff_t(begin), from.begin() + std::ptrdiff_t(end));
    if (deltas.empty()) continue;
    for (size_t k = first; k < to.size(); ++k) to[k].edgeLevelDelta = deltas[k];
  }
}

// Sets with at least this many caps make them on a second thread (a thread's start, ~10-50 us
// here, against ~2 us a cap).
constexpr size_t kCapsOnSecondThread = 1024;

// Each level classified, the set indexed and its level jumps found first, so that the set (and
// its sources) is allocated once, at its size, and each patch is made in place there, whole: no
// per-level copies (which would hold the patches twice at the peak) and no second pass over the
// (cold) patches. [O(patches + faces of all levels)]
PatchSet extractFromStack(const LevelStack& stack, PatchSources* sources) {
  const int finest = stack.count() - 1;
  SetIndex index;
  index.reserve(patchBound(stack));
  std::vector<LevelFaces> faces;
  faces.reserve(size_t(finest) + 1);
  for (int m = 0; m <= finest; ++m) faces.push_back(classifyLevel(stack, m, m > 0 ? &faces.back() : nullptr, index));
  const size_t regular = index.size();
  const CapPlan caps = planCaps(stack, finest, faces.back().capFaces);
  index.append(caps.index);

  PatchSet set;
  LevelDeltas deltas;
  auto regularPatches = [&] {
    deltas = levelJumps(stack, caps.holeFaces, regular, index);
    set.patches.reserve(index.size());
    startSources(sources, index.size());
    PatchOutput out{set.patches, set.kindCounts, sources ? &sources->stencil : nullptr, sources ? &sources->sidesMissing : nullptr};
    // Levels that repeat their parent take its stencils: from the sources, or (none asked) from
    // the first level of the run, kept aside.
    std::vector<std::array<Index, 16>> keptStencil;
    std::vector<uint8_t> keptMissing;
    size_t parentFirst = 0;
    for (int m = 0; m <= finest; ++m) {
      LevelFaces& level = faces[size_t(m)];
      StencilRun reuse;
      PatchOutput levelOut = out;
      if (stack.repeats(m)) {
        reuse = sources ? StencilRun{sources->stencil.data() + parentFirst, sources->sidesMissing.data() + parentFirst}
                        : StencilRun{keptStencil.data(), keptMissing.data()};
      } else if (!sources && m < finest && stack.repeats(m + 1)) {
        keptStencil.reserve(level.patchCount), keptMissing.reserve(level.patchCount);
        levelOut.stencil = &keptStencil, levelOut.sidesMissing = &keptMissing;
      }
      parentFirst = level.firstPatch;
      extractRegular(stack, m, level, index, deltas, levelOut, reuse);
      if (m < finest) level = LevelFaces();  // the children have inherited
    }
  };
  // The finest level's caps (limit frames, Bezier nets: ~15% of a set's time) need neither the
  // level jumps nor the regular patches: made on a second thread where there are enough of them,
  // then copied after the regular patches (the same set either way).
  if (threadLimit() > 1 && caps.index.size() >= kCapsOnSecondThread) {
    std::vector<Patch> capPatches;
    runBoth(true, regularPatches, [&] {
      capPatches.reserve(caps.index.size());
      extractCaps(stack, finest, caps, capPatches);
    });
    appendWithJumps(capPatches, deltas, set.patches);
    for (const Patch& patch : capPatches) ++set.kindCounts[size_t(patch.kind)];
  } else {
    regularPatches();
    appendCaps(stack, finest, caps, deltas, regular, set);
  }
  finishSources(sources, set.patches.size());
  return set;
}

// What level m contributes to every set it is part of: its regular (boundary, polar-ring) patches
// with no level jumps (those depend on the set), their sources and index entries, and its cap
// faces (for the sets it is the finest of).
struct LevelRegularPatches {
  std::vector<Patch> patches;
  std::vector<std::array<Index, 16>> stencil;
  std::vector<uint8_t> sidesMissing;
  SetIndex index;
  std::array<size_t, 5> kindCounts{};
  std::vector<Index> capFaces;
};

// What the finest level adds to a set: its caps (no level jumps), as planned.
struct FinestLevelCaps {
  CapPlan plan;
  std::vector<Patch> patches;
  std::array<size_t, 5> kindCounts{};
};

// The set of a LevelPatchCache from the levels it keeps (so copied, not moved) and the finest
// level's caps, level jumps set as they are copied. [O(patches)]
template <class RegularOfLevel>
PatchSet assembleSet(const LevelStack& stack, RegularOfLevel regularOf, const FinestLevelCaps& caps, PatchSources* sources,
                     std::vector<Patch> storage) {
  const int finest = stack.count() - 1;
  SetIndex index;
  size_t regular = 0;
  for (int m = 0; m <= finest; ++m) regular += regularOf(m).patches.size();
  index.reserve(regular + caps.patches.size());
  for (int m = 0; m <= finest; ++m) index.append(regularOf(m).index);
  index.append(caps.plan.index);
  const LevelDeltas deltas = levelJumps(stack, caps.plan.holeFaces, regular, index);

  PatchSet set;
  set.patches = std::move(storage);  // its memory, already touched: no page faults for it
  set.patches.clear();
  set.patches.reserve(index.size());
  startSources(sources, index.size());
  for (int m = 0; m <= finest; ++m) {
    const LevelRegularPatches& level = regularOf(m);
    appendWithJumps(level.patches, deltas, set.patches);
    for (size_t kind = 0; kind < set.kindCounts.size(); ++kind) set.kindCounts[kind] += level.kindCounts[kind];
    if (!sources) continue;
    sources->stencil.insert(sources->stencil.end(), level.stencil.begin(), level.stencil.end());
    sources->sidesMissing.insert(sources->sidesMissing.end(), level.sidesMissing.begin(), level.sidesMissing.end());
  }
  appendWithJumps(caps.patches, deltas, set.patches);
  for (size_t kind = 0; kind < set.kindCounts.size(); ++kind) set.kindCounts[kind] += caps.kindCounts[kind];
  finishSources(sources, set.patches.size());
  return set;
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
        if (level.mesh.faceSize(patch.face) == 4) made.emplace_back().cp = quadEndCap(level.mesh, patch.face, *limits);
        else polygonEndCaps(level.mesh, patch.face, *limits, made);
      }
      const Point origin = patch.kind == PatchKind::PoleCap ? (made.empty() ? Point(0.0) : made.front().origin)
                                                             : level.origin(level.mesh.faceVerts[level.mesh.faceStart[patch.face]]);
      for (size_t i = 0; i < made.size() && k + i < set.patches.size(); ++i) {
        set.patches[k + i].cp = made[i].cp;
        set.patches[k + i].capExtra = made[i].capExtra;
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
    stack.repeatsParent.push_back(refinement.repeatsParentLevel(m));
  }
  stack.radial = refinement.radialOnly();
  return stack;
}

}  // namespace

PatchSet extractPatches(const Refinement& refinement) {
  if (!refinement.finestTopologyComplete())
    throw std::logic_error("extractPatches: the finest level has its faces only (Refinement::completeFinestTopology)");
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
  for (int m = int(cache.regular.size()); m <= finest; ++m) {
    LevelRegularPatches level;
    LevelFaces faces;
    StencilRun reuse;
    if (stack.repeats(m)) {  // the parent's faces and stencils (LevelStack::repeats)
      const LevelRegularPatches& parent = cache.regular[size_t(m) - 1];
      level.index = parent.index;
      std::fill(level.index.level.begin(), level.index.level.end(), uint8_t(std::min(m, 255)));
      faces.capFaces = parent.capFaces;
      faces.patchCount = parent.patches.size();
      reuse = StencilRun{parent.stencil.data(), parent.sidesMissing.data()};
    } else {
      level.index.reserve(regularBound(stack, m));
      faces = classifyLevel(stack, m, nullptr, level.index);  // adaptive stacks inherit nothing
    }
    level.patches.reserve(faces.patchCount);
    level.stencil.reserve(faces.patchCount);
    level.sidesMissing.reserve(faces.patchCount);
    extractRegular(stack, m, faces, level.index, {}, PatchOutput{level.patches, level.kindCounts, &level.stencil, &level.sidesMissing},
                   reuse);
    level.capFaces = std::move(faces.capFaces);
    cache.regular.push_back(std::move(level));
  }
  if (cache.caps.size() <= size_t(finest)) cache.caps.resize(size_t(finest) + 1);
  if (!cache.caps[size_t(finest)]) {
    auto caps = std::make_unique<FinestLevelCaps>();
    caps->plan = planCaps(stack, finest, cache.regular[size_t(finest)].capFaces);
    caps->patches.reserve(caps->plan.index.size());
    extractCaps(stack, finest, caps->plan, caps->patches);
    for (const Patch& patch : caps->patches) ++caps->kindCounts[size_t(patch.kind)];
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

bool LevelPatchCache::empty() const { return impl_->regular.empty(); }

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
