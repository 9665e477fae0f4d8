// Polar configurations found in a mesh: a triangle fan around a polar vertex, ringed by quads
// with 4-valent vertices (paper Section 3). Detection reports both the refinable ones and the
// vertices that look polar but must fall back to Catmull-Clark, with the reason.
#pragma once

#include <string>
#include <vector>

#include "core/mesh/poly_mesh.h"
#include "core/mesh/topology.h"
#include "core/subdiv/scheme.h"

namespace polarview {

// Why a vertex that looks polar is not a polar configuration, by kind (PolarConfig::reason holds
// the sentence with the vertex ids). In the order detection checks them: a later kind passed more
// checks, so its candidate is nearer a polar configuration (nearerPolarCandidate).
enum class PolarRejection {
  None,                // refinable
  FanNotCycle,         // the triangles around it do not form one closed fan
  FanRepeatsVertex,    // the fan visits a rim vertex twice
  Link1OnBoundary,     // a 1-link vertex lies on a boundary
  Link1NotFourValent,  // a 1-link vertex does not have valence 4
  Link1NotTwoQuads,    // a 4-valent 1-link vertex is not surrounded by 2 fan triangles and 2 quads
  NoLink2,             // no ring of quads beyond the 1-link
  StencilOverlap,      // its fan and 1-link overlap those of another pole
  SharpFeature,        // a crease or corner tag touches its pole or links 1-3 (the polar rules have no creases)
  Hole,                // a hole face touches its pole or links 1-3 (its caps would close over the hole)
};

struct PolarConfig {
  Index pole = -1;       // the polar vertex
  int valence = 0;       // n: number of fan triangles
  // Vertex ids by link: links[(i-1)*valence + j] = q_{ij} for i = 1..linkCount, in the column
  // order of PolarGrid (fan triangles (pole, q_{1j}, q_{1,j+1}) counter-clockwise).
  std::vector<Index> links;
  int linkCount = 0;     // complete links found (link 1 always; link i+1 exists when all q_{ij} are 4-valent interior vertices joined by quads)
  int regularLinks = 0;  // links 1..regularLinks consist of regular 4-valent interior vertices
  // How the region ends beyond the last link: another pole (globe), a boundary loop (cap), or CC mesh.
  enum class Outer { Pole, Boundary, Mesh } outer = Outer::Mesh;
  Index oppositePole = -1;  // the other polar vertex when outer == Pole
  bool refinable = false;   // C2PS/RTS/BPS may refine it; otherwise Catmull-Clark does
  std::string reason;       // why not refinable (empty when refinable)
  PolarRejection rejection = PolarRejection::None;  // the kind of `reason`
};

// A stable snake_case key for JSON ("link1_not_4_valent") and a few words for text ("a 1-link
// vertex is not 4-valent"). [O(1)]
const char* polarRejectionKey(PolarRejection rejection);
const char* polarRejectionWords(PolarRejection rejection);

// Whether rejected candidate `a` is nearer a polar configuration than `b`, the order `info` and the
// viewer list them in: the higher valence first (a cap's fan centre before the vertices of a
// triangulated surface), then the later check it failed, then the lower vertex id. [O(1)]
bool nearerPolarCandidate(const PolarConfig& a, const PolarConfig& b);

// Rejected candidates of one kind, nearest first (indices into the list grouped).
struct RejectedGroup {
  PolarRejection rejection = PolarRejection::None;
  std::vector<size_t> members;
};

// The rejected configurations of `configs` (refinable ones are left out) grouped by kind, the group
// with the nearest candidate first, each group nearest first (nearerPolarCandidate). [O(k log k)]
std::vector<RejectedGroup> groupRejectedCandidates(const std::vector<PolarConfig>& configs);

// Finds every vertex that looks polar (interior, all incident faces triangles, valence >= 3) and
// decides whether it can be refined as a pole: candidates that are not come back with refinable
// false and their rejection (a triangle mesh makes nearly every vertex such a candidate). [O(mesh)]
std::vector<PolarConfig> findPolarConfigs(const PolyMesh& mesh, const MeshTopology& topo);

// Whether `scheme` refines this refinable configuration as a pole; if not, why (Catmull-Clark then
// treats it). RTS and BPS need n >= 5: their 1-link weights hold Fourier modes up to 2 (RTS) and 3
// (BPS), which alias for smaller n (BPS at n = 3 is not even affine invariant); the paper's
// analysis of RTS stipulates n >= 5 too. C2PS takes any n >= 3 (its valence doubles). [O(1)]
bool schemeRefinesPole(Scheme scheme, const PolarConfig& config, std::string* reason = nullptr);

}  // namespace polarview
