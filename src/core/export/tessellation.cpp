// Watertight tessellation of a PatchSet (tessellation.h has the rules).
#include "core/export/tessellation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "core/export/point_grid.h"

namespace polarview {

namespace {

constexpr uint32_t kNoVertex = PointGrid::kNone;

// The diagonal of the box around the patches' control positions (the surface lies in it: convex
// hull of B-spline patches; a cap stays near its boundary points and pole). Non-finite points are
// left out here; the writers refuse them.
double controlBoxDiagonal(const PatchSet& set, Point& low) {
  low = Point(std::numeric_limits<double>::infinity());
  Point high = -low;
  for (const Patch& patch : set.patches)
    for (int k = 0; k < 16; ++k) {
      if (!isPositionPoint(patch.kind, k)) continue;
      const Point p = patch.cp[size_t(k)] + patch.origin;
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
      low = glm::min(low, p);
      high = glm::max(high, p);
    }
  if (!(high.x >= low.x)) {
    low = Point(0.0);
    return 0.0;
  }
  return glm::length(high - low);
}

// The welder of a patch set's seams (vertices on patch borders): kWeldTolerance times its box's diagonal.
PointGrid seamWelderFor(const PatchSet& set) {
  Point low;
  const double diagonal = controlBoxDiagonal(set, low);
  return PointGrid(low, kWeldTolerance * diagonal);
}

// A triangle side on its patch's border, with the parameters of its ends: where a mixed-level
// T-junction leaves it without a partner, its midpoint is evaluated to look for the missing vertex.
struct BorderSegment {
  uint32_t from, to;  // directed as in its triangle
  uint32_t patch;
  double u0, v0, u1, v1;
};

uint64_t directedKey(uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; }

// The triangles' sides grouped by their smaller vertex (CSR), each bucket sorted by the other end,
// then direction, then triangle: every use of an unordered edge lies in one short run. Hash maps of
// all edges (millions of nodes) cost most of an export before (docs/performance.md, Exports).
class TriangleSides {
 public:
  struct Side {
    uint32_t other;     // the larger vertex
    uint32_t backward;  // 1 when the triangle runs from the larger vertex to the smaller
    uint32_t triangle;
    bool operator<(const Side& s) const {
      return other != s.other ? other < s.other : backward != s.backward ? backward < s.backward : triangle < s.triangle;
    }
  };

  TriangleSides(const std::vector<std::array<uint32_t, 3>>& triangles, size_t vertexCount) : start_(vertexCount + 1, 0) {
    for (const auto& t : triangles)
      for (int k = 0; k < 3; ++k) ++start_[size_t(std::min(t[size_t(k)], t[size_t(k + 1) % 3])) + 1];
    for (size_t v = 0; v < vertexCount; ++v) start_[v + 1] += start_[v];
    sides_.resize(start_.back());
    std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
    for (uint32_t i = 0; i < triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = triangles[i][size_t(k)], b = triangles[i][size_t(k + 1) % 3];
        sides_[fill[std::min(a, b)]++] = {std::max(a, b), a > b ? 1u : 0u, i};
      }
    for (size_t v = 0; v < vertexCount; ++v) std::sort(sides_.begin() + start_[v], sides_.begin() + start_[v + 1]);
  }

  // The uses of edge {a, b} (a run of sides, both directions). [O(log valence)]
  std::pair<const Side*, const Side*> uses(uint32_t a, uint32_t b) const {
    const Side* first = sides_.data() + start_[std::min(a, b)];
    const Side* last = sides_.data() + start_[size_t(std::min(a, b)) + 1];
    const uint32_t other = std::max(a, b);
    first = std::lower_bound(first, last, other, [](const Side& s, uint32_t o) { return s.other < o; });
    last = std::upper_bound(first, last, other, [](uint32_t o, const Side& s) { return o < s.other; });
    return {first, last};
  }
  // Calls f(first, last) for each edge's run of sides, edges by their smaller vertex.
  template <class F>
  void forEachEdge(F&& f) const {
    for (size_t v = 0; v + 1 < start_.size(); ++v)
      for (size_t i = start_[v]; i < start_[v + 1];) {
        size_t j = i + 1;
        while (j < start_[v + 1] && sides_[j].other == sides_[i].other) ++j;
        f(&sides_[i], &sides_[j]);
        i = j;
      }
  }

 private:
  std::vector<size_t> start_;
  std::vector<Side> sides_;
};

class TessellationBuilder {
 public:
  TessellationBuilder(const PatchSet& set, int samples) : set_(set), n_(samples), welder_(seamWelderFor(set)) {
    mesh_.samples = samples;
  }

  // Samples patch `index`, welds its border and triangulates its cells. [O(samples^2)]
  void addPatch(uint32_t index);
  // Splits the border segments no neighbour shares where a midpoint welds to a vertex (mixed-level
  // T-junctions). [O(triangles) when there are such segments, else O(border segments)]
  void splitMixedLevelJunctions();
  Tessellation take() { return std::move(mesh_); }

 private:
  // A sample of the current patch: its vertex and its parameter in units of 1/denominator_.
  struct Sample {
    uint32_t id;
    int64_t a, b;
  };
  uint32_t vertexAt(uint32_t patch, double u, double v, bool border);
  Sample sampleAt(int64_t a, int64_t b) {
    const double u = double(a) / double(denominator_), v = double(b) / double(denominator_);
    const bool border = a == 0 || b == 0 || a == denominator_ || b == denominator_;
    return {vertexAt(patch_, u, v, border), a, b};
  }
  void cellLoop(int i, int j, const std::vector<Sample>& grid, std::vector<Sample>& loop);
  void emitTriangle(const Sample& x, const Sample& y, const Sample& z);
  void recordBorder(const Sample& x, const Sample& y);

  const PatchSet& set_;
  int n_;
  PointGrid welder_;
  Tessellation mesh_;
  std::vector<BorderSegment> border_;
  // The patch being triangulated: its index, parameter denominator (2 N 2^dmax: grid, refined
  // edges and cell centres are integers) and the segments of its refined edges (0: not refined).
  uint32_t patch_ = 0;
  int64_t denominator_ = 1;
  std::array<int64_t, 4> edgeSegments_{};
};

uint32_t TessellationBuilder::vertexAt(uint32_t patch, double u, double v, bool border) {
  const SurfacePoint sp = evaluatePatch(set_.patches[patch], u, v);
  if (border) {
    const uint32_t found = welder_.find(sp.position, mesh_.positions);
    if (found != kNoVertex) return found;
  }
  if (mesh_.positions.size() >= size_t(kNoVertex)) throw std::length_error("tessellation: more than 2^32 - 1 vertices");
  const uint32_t id = uint32_t(mesh_.positions.size());
  mesh_.positions.push_back(sp.position);
  mesh_.normals.push_back(sp.normal);
  mesh_.gaussian.push_back(sp.gaussian);
  mesh_.mean.push_back(sp.mean);
  mesh_.sources.push_back({patch, u, v});
  if (border) welder_.insert(sp.position, id);
  return id;
}

void TessellationBuilder::addPatch(uint32_t index) {
  const Patch& patch = set_.patches[index];
  patch_ = index;
  int finest = 0;
  for (int8_t delta : patch.edgeLevelDelta) finest = std::max(finest, int(delta));
  denominator_ = int64_t(2) * n_ << finest;
  for (int s = 0; s < 4; ++s)
    edgeSegments_[size_t(s)] = patch.edgeLevelDelta[size_t(s)] > 0 ? int64_t(n_) << patch.edgeLevelDelta[size_t(s)] : 0;

  // The grid, row by row (i along u).
  const int64_t step = denominator_ / n_;
  std::vector<Sample> grid;
  grid.reserve(size_t(n_ + 1) * size_t(n_ + 1));
  for (int j = 0; j <= n_; ++j)
    for (int i = 0; i <= n_; ++i) grid.push_back(sampleAt(i * step, j * step));

  // Cells: two triangles, or a fan from the centre where a side has the refined edge's samples.
  std::vector<Sample> loop;
  for (int j = 0; j < n_; ++j)
    for (int i = 0; i < n_; ++i) {
      cellLoop(i, j, grid, loop);
      if (loop.size() == 4) {
        emitTriangle(loop[0], loop[1], loop[2]);
        emitTriangle(loop[0], loop[2], loop[3]);
        continue;
      }
      const Sample centre = sampleAt((2 * i + 1) * step / 2, (2 * j + 1) * step / 2);
      for (size_t k = 0; k < loop.size(); ++k) emitTriangle(centre, loop[k], loop[(k + 1) % loop.size()]);
    }
}

// The boundary of cell (i,j), counter-clockwise in (u,v) from its corner (i,j): each side its first
// corner, then the refined edge's samples inside it where the side lies on such an edge.
void TessellationBuilder::cellLoop(int i, int j, const std::vector<Sample>& grid, std::vector<Sample>& loop) {
  const int64_t step = denominator_ / n_, D = denominator_;
  const auto corner = [&](int ci, int cj) { return grid[size_t(cj) * size_t(n_ + 1) + size_t(ci)]; };
  // Side s from corner `from` along (du, db) (+-1 in a or b), on patch edge s when `onEdge`.
  const auto side = [&](int s, bool onEdge, const Sample& from, int da, int db) {
    loop.push_back(from);
    if (!onEdge || edgeSegments_[size_t(s)] == 0) return;
    const int64_t fine = D / edgeSegments_[size_t(s)];
    for (int64_t t = fine; t < step; t += fine) loop.push_back(sampleAt(from.a + da * t, from.b + db * t));
  };
  loop.clear();
  side(0, j == 0, corner(i, j), 1, 0);
  side(1, i == n_ - 1, corner(i + 1, j), 0, 1);
  side(2, j == n_ - 1, corner(i + 1, j + 1), -1, 0);
  side(3, i == 0, corner(i, j + 1), 0, -1);
}

void TessellationBuilder::emitTriangle(const Sample& x, const Sample& y, const Sample& z) {
  // A pole cap's u = 0 samples are one vertex: a cell touching it degenerates to a triangle.
  if (x.id == y.id || y.id == z.id || z.id == x.id) return;
  mesh_.triangles.push_back({x.id, y.id, z.id});
  recordBorder(x, y);
  recordBorder(y, z);
  recordBorder(z, x);
}

void TessellationBuilder::recordBorder(const Sample& x, const Sample& y) {
  const int64_t D = denominator_;
  const bool sameSide = (x.b == 0 && y.b == 0) || (x.a == D && y.a == D) || (x.b == D && y.b == D) || (x.a == 0 && y.a == 0);
  if (!sameSide) return;
  const double scale = 1.0 / double(D);
  border_.push_back({x.id, y.id, patch_, double(x.a) * scale, double(x.b) * scale, double(y.a) * scale, double(y.b) * scale});
}

void TessellationBuilder::splitMixedLevelJunctions() {
  // Which border segments nobody shares, and the triangle each belongs to (directed edge ->
  // triangle; kept up to date below for the segments' halves, the only edges looked up again).
  std::unordered_map<uint64_t, uint32_t> owner;
  std::vector<BorderSegment> open;
  {
    const TriangleSides sides(mesh_.triangles, mesh_.positions.size());
    for (const BorderSegment& segment : border_) {
      const auto [first, last] = sides.uses(segment.from, segment.to);
      if (last - first != 1) continue;
      open.push_back(segment);
      owner[directedKey(segment.from, segment.to)] = first->triangle;
    }
  }
  if (open.empty()) return;

  while (!open.empty()) {
    const BorderSegment s = open.back();
    open.pop_back();
    const double um = 0.5 * (s.u0 + s.u1), vm = 0.5 * (s.v0 + s.v1);
    const uint32_t m = welder_.find(evaluatePatch(set_.patches[s.patch], um, vm).position, mesh_.positions);
    const auto it = owner.find(directedKey(s.from, s.to));
    if (m == kNoVertex || it == owner.end()) continue;  // a real boundary
    const uint32_t t = it->second;
    std::array<uint32_t, 3>& tri = mesh_.triangles[t];
    const int k = tri[0] == s.from ? 0 : tri[1] == s.from ? 1 : 2;
    const uint32_t c = tri[size_t(k + 2) % 3];
    if (m == s.from || m == s.to || m == c) continue;
    // (from, to, c) -> (from, m, c) and (m, to, c).
    tri = {s.from, m, c};
    const uint32_t added = uint32_t(mesh_.triangles.size());
    mesh_.triangles.push_back({m, s.to, c});
    owner.erase(directedKey(s.from, s.to));
    owner[directedKey(s.from, m)] = t;
    owner[directedKey(m, c)] = t;
    owner[directedKey(m, s.to)] = added;
    owner[directedKey(s.to, c)] = added;
    owner[directedKey(c, m)] = added;
    ++mesh_.splitEdges;
    // Either half may need splitting again (the coarse side can be several levels finer).
    open.push_back({s.from, m, s.patch, s.u0, s.v0, um, vm});
    open.push_back({m, s.to, s.patch, um, vm, s.u1, s.v1});
  }
}

}  // namespace

Tessellation tessellatePatchSet(const PatchSet& set, int samples) {
  if (samples < 1) throw std::invalid_argument("tessellatePatchSet: samples must be at least 1");
  TessellationBuilder builder(set, samples);
  for (size_t k = 0; k < set.patches.size(); ++k) builder.addPatch(uint32_t(k));
  builder.splitMixedLevelJunctions();
  return builder.take();
}

TessellationEdges countTessellationEdges(const Tessellation& mesh) {
  // Per unordered edge: uses one way and the other.
  TessellationEdges count;
  TriangleSides(mesh.triangles, mesh.positions.size()).forEachEdge([&](const TriangleSides::Side* first, const TriangleSides::Side* last) {
    size_t forward = 0, backward = 0;
    for (const TriangleSides::Side* s = first; s != last; ++s) ++(s->backward ? backward : forward);
    ++count.edges;
    if (forward + backward == 1) ++count.boundary;
    else if (forward + backward > 2) ++count.nonManifold;
    else if (forward != 1) ++count.misoriented;
  });
  return count;
}

}  // namespace polarview
