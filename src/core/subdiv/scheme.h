// Scheme: which refinement runs at polar configurations (Catmull-Clark runs everywhere else).
#pragma once

#include <optional>
#include <string>

namespace polarview {

enum class Scheme {
  CatmullClark,  // Catmull-Clark everywhere, poles included (OpenSubdiv's conventions)
  C2PS,          // bi-3 C2 polar subdivision, Myles & Peters 2009, rules (1)-(5), (29)
  RTS,           // radial Taylor subdivision, ibid. Definition 1, (9)-(12)
  BPS,           // bicubic polar subdivision, Karciauskas & Peters 2007 (weights: see bps.h)
};

const char* schemeName(Scheme s);                       // "cc", "c2ps", "rts", "bps"
std::optional<Scheme> parseScheme(const std::string& name);

struct RefineOptions {
  Scheme scheme = Scheme::C2PS;
  int levels = 3;
  bool uniformFirstStep = false;  // paper Section 6: first step's 2-link by uniform bi-3 rules
};

}  // namespace polarview
