// Scheme: which refinement runs at polar configurations (Catmull-Clark runs everywhere else), and
// the one table of what each scheme is. Every dispatch on the scheme (refiners, pole detection, the
// Taylor expansion, spectra, command lines, the viewer) reads SchemeTraits: a scheme is one row
// here plus its rule file.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "core/subdiv/polar_grid.h"

namespace polarview {

enum class Scheme {
  CatmullClark,  // Catmull-Clark everywhere, poles included (OpenSubdiv's conventions)
  C2PS,          // bi-3 C2 polar subdivision, Myles & Peters 2009, rules (1)-(5), (29)
  RTS,           // radial Taylor subdivision, ibid. Definition 1, (9)-(12)
  BPS,           // bicubic polar subdivision, Karciauskas & Peters 2007 (weights: see bps.h)
};

struct SchemeTraits {
  Scheme scheme;
  const char* name;   // command lines and JSON: "c2ps"
  const char* label;  // titles: "C2PS"
  int minValence;     // smallest polar valence it refines; 0: no polar rules (Catmull-Clark)
  // RTS, BPS: the valence stays and a pole's region refines radially (caps and globes wholly;
  // elsewhere on C2PS's connectivity from the pole's own radial grid). C2PS doubles the valence.
  bool keepsValence;
  bool hasUniformFirstStep;  // the paper's Section-6 variant exists (name "-u")
  int taylorOrder;           // at the pole (32): 2 full quadratic, 1 tangent plane (BPS is C1), 0 none
  // C2 at the pole: the curvature there is one K and H. RTS has a quadratic expansion but is not C2
  // for finite n (K depends on the direction of approach).
  bool curvatureContinuous;
  // One polar step of links 0..K: the whole grid (K -> 2K - 1 links), the pole, the new 1-link and
  // 2-link (C2PS writes 2n points each, the others n). Null for Catmull-Clark.
  PolarGrid (*refineGrid)(const PolarGrid&, bool uniformFirstStep);
  Point (*refinePole)(const PolarGrid&);
  void (*refineLink1)(const PolarGrid&, Point*);
  void (*refineLink2)(const PolarGrid&, Point*, bool uniformFirstStep);

  bool polar() const { return minValence > 0; }
};

// The table: one row per scheme, in enum order. [O(1)]
const std::array<SchemeTraits, 4>& schemeTable();
const SchemeTraits& schemeTraits(Scheme scheme);

const char* schemeName(Scheme s);  // "cc", "c2ps", "rts", "bps"

// A scheme and its first step: the names every command and the viewer take ("c2ps-u" is C2PS with
// the uniform first step).
struct SchemeVariant {
  Scheme scheme = Scheme::C2PS;
  bool uniformFirstStep = false;
};
// The one parser of scheme names (the CLI's --scheme, the viewer's, the Python module's): the table's
// names and "-u" for the Section-6 variant, case-insensitive; also "-uniform" or "u" for "-u"
// ("c2ps-uniform", "rtsu") and "catmull-clark" / "catmullclark" for "cc". [O(1)]
std::optional<SchemeVariant> parseSchemeVariant(const std::string& name);
std::string schemeVariantName(const SchemeVariant& variant);               // "c2ps-u"
std::string schemeVariantLabel(const SchemeVariant& variant);              // "C2PS-U"

struct RefineOptions {
  Scheme scheme = Scheme::C2PS;
  int levels = 3;
  bool uniformFirstStep = false;  // paper Section 6: first step's 2-link by uniform bi-3 rules
  // Refinement (uniform): false gives the finest level its faces, face parents, counts and vertex
  // flags only where Catmull-Clark's connectivity made it, as OpenSubdiv's RefineUniform does by
  // default (fullTopologyInLastLevel = false): what a caller that reads only its faces and points
  // needs (`refine`). Its edges and vertex rings (patch extraction, walking around its vertices)
  // need Refinement::completeFinestTopology first.
  bool fullFinestTopology = true;
  // AdaptiveRefinement: a level whose step inputs (faces, sharpness, holes, which faces are needed,
  // which vertices exact and complete) equal its parent level's is a fixed point of the sparse step,
  // so its step and child are copies of the previous ones (docs/performance.md, "Fixed points").
  // false refines every level anew (the tests compare both).
  bool copyFixedPointLevels = true;
};

}  // namespace polarview
