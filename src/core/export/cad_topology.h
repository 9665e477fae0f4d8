// The surfaces of a CadSurfaceSet joined into one shell: shared vertices and edges, as a CAD
// reader expects of a model (docs/formats.md, "STEP topology").
//
// SIDES. A surface's boundary is walked counter-clockwise in its parameter square: side 0 is
// v = 0 (u from 0 to 1), side 1 is u = 1 (v from 0 to 1), side 2 is v = 1 (u from 1 to 0), side 3
// is u = 0 (v from 1 to 0); t in [0, 1] runs along the side in that direction (cadSideParameter).
// A side whose control points all lie on one vertex (a cap piece's pole u = 0) is collapsed and
// has no edge, as OpenCASCADE writes a degenerate edge itself.
//
// VERTICES are the surfaces' corners welded within `tolerance` (max of 1e-9 of the bounding-box
// diagonal and 64 ulps of the largest coordinate): corners that the limit surface shares come out
// of different patches equal to round-off.
//
// T-JUNCTIONS. Where a coarse side meets finer ones (adaptive 2:1 levels, C2PS's doubled valence,
// a cap sector written in 2^k pieces) the finer sides' corners lie on the coarse side at dyadic
// parameters: a side piece [t0, t1] is split at its middle wherever a vertex lies on the side's
// curve there (within the tolerance), and its halves are split again the same way. Subdivision's
// vertex sets are nested, so every T-vertex is found this way.
//
// EDGES. Two side pieces pair into one edge when they join the same two vertices in opposite
// directions and their curves meet at the piece's middle (within the tolerance): the edge's curve
// is the first piece's (the side's Bezier curve restricted to [t0, t1], running start -> end); the
// first uses it forwards, the second backwards. A piece without a partner (a mesh boundary, a
// non-manifold or inconsistently oriented join, a surface meeting itself) is a free edge used once. The shell is closed
// when no edge is free and no curve has more than two pieces on it.
//
// ORIENTATION. A closed shell whose surfaces' normals point inwards (a mesh whose faces turn
// clockwise seen from outside: a negative enclosed volume by the divergence theorem) is marked
// `inwards`; the STEP writer then writes its faces reversed, as a solid's faces point outwards.
#pragma once

#include <glm/vec2.hpp>

#include <vector>

#include "core/export/cad_surfaces.h"

namespace polarview {

// One use of an edge in a face's loop: the piece [t0, t1] of the face's side `side`.
struct CadCoedge {
  int edge = 0;
  bool forward = true;  // the loop runs start -> end of the edge
  int side = 0;
  double t0 = 0.0, t1 = 1.0;
};

struct CadEdge {
  int start = 0, end = 0;  // vertex indices
  // Its curve: side `side` of surface `surface`, on [t0, t1] (the first coedge's piece).
  size_t surface = 0;
  int side = 0;
  double t0 = 0.0, t1 = 1.0;
  int uses = 1;  // 2 where two faces share it, 1 for a free edge
};

struct CadTopology {
  std::vector<Point> vertices;
  std::vector<CadEdge> edges;
  std::vector<std::vector<CadCoedge>> loops;  // per surface, counter-clockwise from side 0
  double tolerance = 0.0;
  size_t freeEdges = 0;
  size_t tJunctionSplits = 0;    // side pieces split at a T-vertex
  size_t nonManifoldPieces = 0;  // side pieces on a curve that more than two pieces lie on
  bool inwards = false;          // closed, and the surfaces' normals (du x dv) point into the solid

  // Every edge shared by two faces, none by more (back-to-back sheets bound no solid).
  bool closed() const { return freeEdges == 0 && nonManifoldPieces == 0 && !edges.empty(); }
};

// The shell of `set` (rules above). [O(sides * log(tolerance-cells) + splits)]
CadTopology cadTopology(const CadSurfaceSet& set);

// The control points of side `side` of `surface`, in the side's direction. [O(degree)]
std::vector<Point> cadSideCurve(const CadSurface& surface, int side);
// (u, v) of parameter t along side `side` (rules above). [O(1)]
glm::dvec2 cadSideParameter(int side, double t);
// The Bezier curve `points` restricted to [t0, t1] and reparametrised to [0, 1], by two de
// Casteljau splits. [O(degree^2)]
std::vector<Point> bezierSegment(const std::vector<Point>& points, double t0, double t1);
// The point of the Bezier curve `points` at t, by de Casteljau. [O(degree^2)]
Point bezierPoint(const std::vector<Point>& points, double t);

}  // namespace polarview
