// The pole inspector's numbers (issue: the paper's claim made visible): per pole of the model and
// scheme, the limit point, normal, expansion (32) and K, H at the pole, and ring by ring how K
// approaches it: C2PS converges (about /2.5 a level), RTS's K keeps depending on the direction,
// Catmull-Clark oscillates n-fold around its extraordinary vertex. Plain data, no GL.
#pragma once

#include "core/subdiv/polar_config.h"

#include <array>
#include <string>
#include <vector>

#include "core/mesh/poly_mesh.h"
#include "core/spline/patch.h"
#include "pipeline/scheme_choice.h"

namespace polarview {

struct PoleRingCurves {
  int m = 0;                // ring m: r in [2, 4] 2^-m of level 0's radial unit (level m's patches for CC)
  double minK = 0.0, maxK = 0.0;
  // max |K - K(pole)| where K(pole) is defined (C2 schemes), else the spread maxK - minK.
  double deviation = 0.0;
  std::vector<double> kAlongAngle;  // K at kInspectorAngles uniform angles around the ring
};

struct PoleInspection {
  SchemeChoice scheme = SchemeChoice::C2PS;
  Index vertex = -1;
  int valence = 0;
  bool byScheme = true;            // false: the scheme leaves this pole to Catmull-Clark (why: note)
  bool hasExpansion = false;       // limit, normal, p0..p5 below are (32)'s
  Point limit{}, normal{};
  std::array<Point, 6> p{};
  bool curvatureDefined = false;   // K, H at the pole are defined (C2 at the pole: C2PS; RTS: Taylor K)
  double K = 0.0, H = 0.0;
  bool directional = false;        // K depends on the direction at the pole (RTS for finite n, CC)
  bool deviationFromPole = false;  // rings' deviation is |K - K(pole)| (else the spread)
  std::vector<PoleRingCurves> rings;
  std::string note;                // one line for the panel
};

constexpr int kInspectorAngles = 180;

// A vertex that looks polar (a fan of triangles around it) but is not a pole, and why.
struct RejectedPole {
  Index vertex = -1;
  int valence = 0;
  std::string reason;  // the sentence, with vertex ids (PolarConfig::reason)
};

// Rejected candidates of one kind (core/subdiv/polar_config.h groupRejectedCandidates).
struct RejectedPoleGroup {
  std::string words;                // polarRejectionWords: "a 1-link vertex is on a boundary"
  int count = 0;                    // candidates of this kind
  std::vector<RejectedPole> nearest;  // the nearest of them, nearest first (at most `listed`)
};

// What the Poles panel says about a model: its poles, and why the vertices that look polar are not.
struct PoleSurvey {
  std::vector<Index> poles;               // refinable polar configurations (any scheme), by vertex id
  std::vector<RejectedPoleGroup> rejected;  // the group with the nearest candidate first
  int rejectedCount = 0;
  int fanFaces = 0;  // faces the n-gon conversion would make triangle fans (core/mesh/ngon_to_fan.h)
};

// The polar vertices of the model (refinable polar configurations, any scheme), by vertex id. [O(mesh)]
std::vector<Index> modelPoles(const PolyMesh& mesh);
// The poles, the rejected candidates (the nearest `listed` of each kind) and the n-gons. [O(mesh)]
PoleSurvey surveyPoles(const PolyMesh& mesh, size_t listed);
// The same with `mesh`'s polar configurations found already (its analysis: ModelAnalysis::polarConfigs).
PoleSurvey surveyPoles(const PolyMesh& mesh, const std::vector<PolarConfig>& configs, size_t listed);
// The inspection of pole `vertex` of `mesh` under `scheme`, rings 1..rings (C2PS at most the rings
// that keep its doubled valence within 2^16). Polar schemes: from the pole's own links (pole-
// relative, any depth); Catmull-Clark: from its feature-adaptive patches around the vertex.
// Throws std::invalid_argument when `vertex` is not a pole of the mesh. [O(rings * ring size)]
PoleInspection inspectPole(const PolyMesh& mesh, Index vertex, SchemeChoice scheme, int rings);

}  // namespace polarview

namespace polarview {

// Pole zoom (the paper's Figs. 8, 9): the polar-ring patches of pole `pole` with rings
// firstRing .. firstRing + rings - 1 (and its cap when it closes the hole within them), scaled by
// 2^firstRing about `centre` (the pole's limit point) in double precision, so that ring m appears
// as large as ring 0 at any depth: positions c + s (p - c), the cap's vector slots (p1..p5, e) times
// s. K scales by 1 / s^2 and H by 1 / s (the viewer scales its colour range alike). [O(patches)]
std::vector<Patch> zoomAboutPole(const std::vector<Patch>& patches, int pole, int firstRing, int rings, const Point& centre);
// The patch level a surface needs for rings m .. m + 2 of the pole zoom: ring m is made at level m
// and closed by the cap at the last level, so level m + 2 holds all three (below m nothing shows).
constexpr int poleZoomLevel(int firstRing) { return firstRing + 2; }

}  // namespace polarview
