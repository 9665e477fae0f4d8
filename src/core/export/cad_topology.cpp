// The CAD writers' shell (cad_topology.h).
#include "core/export/cad_topology.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <glm/geometric.hpp>

#include "core/export/point_grid.h"

namespace polarview {

namespace {

// Corners welded within a tolerance (point_grid.h).
class VertexWelder {
 public:
  explicit VertexWelder(double tolerance) : grid_(Point(0.0), tolerance) {}

  // The vertex within the tolerance of p, or -1.
  int find(const Point& p) const {
    const uint32_t found = grid_.find(p, points_);
    return found == PointGrid::kNone ? -1 : int(found);
  }
  // The vertex within the tolerance of p, made when there is none.
  int weld(const Point& p) {
    const int found = find(p);
    if (found >= 0) return found;
    points_.push_back(p);
    grid_.insert(p, uint32_t(points_.size() - 1));
    return int(points_.size() - 1);
  }
  std::vector<Point> take() { return std::move(points_); }

 private:
  PointGrid grid_;
  std::vector<Point> points_;
};

// A piece [t0, t1] of a surface's side, from vertex a to vertex b.
struct SidePiece {
  size_t surface = 0;
  int side = 0;
  double t0 = 0.0, t1 = 1.0;
  int a = 0, b = 0;
  Point middle{};
  int partner = -1;  // the paired piece, -1 while free
};

double weldTolerance(const CadSurfaceSet& set) {
  const double largest = std::max({std::abs(set.boxMin.x), std::abs(set.boxMin.y), std::abs(set.boxMin.z),
                                   std::abs(set.boxMax.x), std::abs(set.boxMax.y), std::abs(set.boxMax.z)});
  const double tolerance = std::max(1e-9 * set.boxDiagonal, 64.0 * std::numeric_limits<double>::epsilon() * largest);
  return tolerance > 0.0 ? tolerance : 1e-300;
}

bool collapsed(const std::vector<Point>& curve, double tolerance) {
  return std::all_of(curve.begin(), curve.end(),
                     [&](const Point& p) { return glm::distance(p, curve.front()) <= tolerance; });
}

// Appends the pieces of [t0, t1] (vertices a, b): split at the middle where a vertex lies there.
void splitSide(const std::vector<Point>& curve, const VertexWelder& welder, SidePiece piece, int depth,
               std::vector<SidePiece>& out, size_t& splits) {
  const double middle = 0.5 * (piece.t0 + piece.t1);
  piece.middle = bezierPoint(curve, middle);
  const int vertex = welder.find(piece.middle);
  if (vertex < 0 || vertex == piece.a || vertex == piece.b || depth >= 40) {
    out.push_back(piece);
    return;
  }
  ++splits;
  SidePiece first = piece, second = piece;
  first.t1 = second.t0 = middle;
  first.b = second.a = vertex;
  splitSide(curve, welder, first, depth + 1, out, splits);
  splitSide(curve, welder, second, depth + 1, out, splits);
}

// Pairs each free piece with a free piece of another surface joining its vertices the other way
// whose middle is nearest (within `tolerance`). A surface glued to itself would need a seam edge
// (OpenCASCADE's reader fails on a loop using one edge twice): its sides stay free. Returns the
// number of pieces that lie on a curve more than two pieces lie on (non-manifold joins).
size_t pairPieces(std::vector<SidePiece>& pieces, double tolerance) {
  std::map<std::pair<int, int>, std::vector<int>> byEnds;
  for (size_t k = 0; k < pieces.size(); ++k) byEnds[{pieces[k].a, pieces[k].b}].push_back(int(k));
  // The pieces on the same curve as `piece` (itself included), either way round.
  auto alongside = [&](const SidePiece& piece) {
    std::vector<int> out;
    for (const auto& ends : {std::pair{piece.a, piece.b}, std::pair{piece.b, piece.a}}) {
      const auto it = byEnds.find(ends);
      if (it == byEnds.end()) continue;
      for (int other : it->second)
        if (glm::distance(pieces[size_t(other)].middle, piece.middle) <= tolerance) out.push_back(other);
      if (piece.a == piece.b) break;  // a closed curve: both ways are one list
    }
    return out;
  };
  size_t nonManifold = 0;
  for (size_t k = 0; k < pieces.size(); ++k) {
    SidePiece& piece = pieces[k];
    const std::vector<int> shared = alongside(piece);
    if (shared.size() > 2) ++nonManifold;
    if (piece.partner >= 0) continue;
    int best = -1;
    double bestDistance = tolerance;
    for (int other : shared) {
      const SidePiece& candidate = pieces[size_t(other)];
      if (candidate.a != piece.b || candidate.surface == piece.surface || candidate.partner >= 0)
        continue;  // a face is no seam of itself
      const double d = glm::distance(candidate.middle, piece.middle);
      if (d <= bestDistance) best = other, bestDistance = d;
    }
    if (best < 0) continue;
    piece.partner = best;
    pieces[size_t(best)].partner = int(k);
  }
  return nonManifold;
}

// The volume the surfaces enclose, by the divergence theorem: the sum of the integrals of
// x . (x_u x x_v) / 3, each by 5 x 5 Gauss-Legendre points (exact for bicubics).
double signedVolume(const CadSurfaceSet& set) {
  static constexpr double kNode[5] = {0.04691007703066800, 0.23076534494715845, 0.5, 0.76923465505284155,
                                      0.95308992296933200};
  static constexpr double kWeight[5] = {0.11846344252809454, 0.23931433524968324, 0.28444444444444444,
                                        0.23931433524968324, 0.11846344252809454};
  double volume = 0.0;
  for (const CadSurface& surface : set.surfaces)
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) {
        const CadSurfaceDerivatives d = evaluateCadSurface(surface, kNode[i], kNode[j]);
        volume += kWeight[i] * kWeight[j] * glm::dot(d.position, glm::cross(d.du, d.dv)) / 3.0;
      }
  return volume;
}

}  // namespace

Point bezierPoint(const std::vector<Point>& points, double t) {
  std::vector<Point> p = points;
  for (size_t level = 1; level < p.size(); ++level)
    for (size_t k = 0; k + level < p.size(); ++k) p[k] = (1.0 - t) * p[k] + t * p[k + 1];
  return p.front();
}

std::vector<Point> bezierSegment(const std::vector<Point>& points, double t0, double t1) {
  if (t0 == 0.0 && t1 == 1.0) return points;
  // The right part from t1's left part: split at t1 (keep [0, t1]), then at t0 / t1 (keep the right).
  const size_t n = points.size();
  std::vector<Point> p = points, left(n);
  for (size_t level = 0; level < n; ++level) {
    left[level] = p[0];
    for (size_t k = 0; k + 1 < n - level; ++k) p[k] = (1.0 - t1) * p[k] + t1 * p[k + 1];
  }
  const double s = t1 > 0.0 ? t0 / t1 : 0.0;
  std::vector<Point> right(n);
  p = left;
  for (size_t level = 0; level < n; ++level) {
    right[n - 1 - level] = p[n - 1 - level];
    for (size_t k = 0; k + 1 < n - level; ++k) p[k] = (1.0 - s) * p[k] + s * p[k + 1];
  }
  return right;
}

std::vector<Point> cadSideCurve(const CadSurface& surface, int side) {
  const BezierPatch& b = surface.bezier;
  const int columns = b.degV + 1;
  auto point = [&](int i, int j) { return b.cp[size_t(columns * i + j)]; };
  std::vector<Point> curve;
  switch (side) {
    case 0:
      for (int i = 0; i <= b.degU; ++i) curve.push_back(point(i, 0));
      break;
    case 1:
      for (int j = 0; j <= b.degV; ++j) curve.push_back(point(b.degU, j));
      break;
    case 2:
      for (int i = b.degU; i >= 0; --i) curve.push_back(point(i, b.degV));
      break;
    default:
      for (int j = b.degV; j >= 0; --j) curve.push_back(point(0, j));
      break;
  }
  return curve;
}

glm::dvec2 cadSideParameter(int side, double t) {
  switch (side) {
    case 0:
      return {t, 0.0};
    case 1:
      return {1.0, t};
    case 2:
      return {1.0 - t, 1.0};
    default:
      return {0.0, 1.0 - t};
  }
}

CadTopology cadTopology(const CadSurfaceSet& set) {
  CadTopology out;
  out.tolerance = weldTolerance(set);
  VertexWelder welder(out.tolerance);

  // Corners first (every T-vertex is one), then each side's pieces.
  struct Side {
    size_t surface;
    int side;
    std::vector<Point> curve;
    int a, b;
  };
  std::vector<Side> sides;
  for (size_t s = 0; s < set.surfaces.size(); ++s)
    for (int side = 0; side < 4; ++side) {
      std::vector<Point> curve = cadSideCurve(set.surfaces[s], side);
      if ((side == 3 && set.surfaces[s].collapsedAtU0()) || collapsed(curve, out.tolerance)) continue;
      const int a = welder.weld(curve.front()), b = welder.weld(curve.back());
      sides.push_back({s, side, std::move(curve), a, b});
    }
  std::vector<SidePiece> pieces;
  std::vector<size_t> firstPiece(set.surfaces.size() + 1, 0);
  size_t surface = 0;
  for (const Side& side : sides) {
    while (surface <= side.surface) firstPiece[surface++] = pieces.size();
    SidePiece whole;
    whole.surface = side.surface;
    whole.side = side.side;
    whole.a = side.a;
    whole.b = side.b;
    splitSide(side.curve, welder, whole, 0, pieces, out.tJunctionSplits);
  }
  while (surface <= set.surfaces.size()) firstPiece[surface++] = pieces.size();
  // Curves that share their ends but not their course stay apart (1e-6 of the diagonal: far above
  // round-off, far below any two distinct sides of one model).
  out.nonManifoldPieces = pairPieces(pieces, std::max(out.tolerance, 1e-6 * set.boxDiagonal));

  // Edges in loop order: a piece met first makes its edge, its partner reuses it.
  std::vector<int> edgeOf(pieces.size(), -1);
  out.loops.resize(set.surfaces.size());
  for (size_t s = 0; s < set.surfaces.size(); ++s)
    for (size_t k = firstPiece[s]; k < firstPiece[s + 1]; ++k) {
      const SidePiece& piece = pieces[k];
      CadCoedge coedge{0, true, piece.side, piece.t0, piece.t1};
      if (edgeOf[k] >= 0) {
        coedge.edge = edgeOf[k];
        coedge.forward = false;
        ++out.edges[size_t(edgeOf[k])].uses;
      } else {
        coedge.edge = int(out.edges.size());
        out.edges.push_back({piece.a, piece.b, piece.surface, piece.side, piece.t0, piece.t1, 1});
        if (piece.partner >= 0) edgeOf[size_t(piece.partner)] = coedge.edge;
      }
      out.loops[s].push_back(coedge);
    }
  out.freeEdges =
      size_t(std::count_if(out.edges.begin(), out.edges.end(), [](const CadEdge& e) { return e.uses == 1; }));
  out.vertices = welder.take();
  out.inwards = out.closed() && signedVolume(set) < 0.0;
  return out;
}

}  // namespace polarview
