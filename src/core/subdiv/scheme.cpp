#include "core/subdiv/scheme.h"

#include <cctype>

#include "core/subdiv/bps.h"
#include "core/subdiv/c2ps.h"
#include "core/subdiv/rts.h"

namespace polarview {

namespace {

const std::array<SchemeTraits, 4> kSchemes = {{
    {Scheme::CatmullClark, "cc", "CC", 0, false, false, 0, false, nullptr, nullptr, nullptr, nullptr},
    {Scheme::C2PS, "c2ps", "C2PS", 3, false, true, 2, true, [](const PolarGrid& g, bool u) { return c2ps::refineGrid(g, u); },
     c2ps::refinePole, c2ps::refineLink1, c2ps::refineLink2},
    // RTS and BPS need n >= 5: their 1-link weights hold Fourier modes up to 2 (RTS) and 3 (BPS),
    // which alias for smaller n (BPS at n = 3 is not even affine invariant).
    {Scheme::RTS, "rts", "RTS", 5, true, true, 2, false, [](const PolarGrid& g, bool u) { return rts::refineGrid(g, u); },
     rts::refinePole, rts::refineLink1, rts::refineLink2},
    // BPS's 2-link rule already is the uniform one: no first-step variant.
    {Scheme::BPS, "bps", "BPS", 5, true, false, 1, false, [](const PolarGrid& g, bool) { return bps::refineGrid(g); },
     bps::refinePole, bps::refineLink1, [](const PolarGrid& g, Point* out, bool) { bps::refineLink2(g, out); }},
}};

// Catmull-Clark's other spellings (lower case).
constexpr const char* kCatmullClarkAliases[] = {"catmull-clark", "catmullclark"};

}  // namespace

const std::array<SchemeTraits, 4>& schemeTable() { return kSchemes; }
const SchemeTraits& schemeTraits(Scheme scheme) { return kSchemes[size_t(scheme)]; }

const char* schemeName(Scheme s) { return schemeTraits(s).name; }

std::optional<SchemeVariant> parseSchemeVariant(const std::string& name) {
  std::string key = name;
  for (char& c : key) c = char(std::tolower(static_cast<unsigned char>(c)));
  for (const SchemeTraits& traits : kSchemes) {
    const std::string row = traits.name;
    if (key == row) return SchemeVariant{traits.scheme, false};
    if (traits.hasUniformFirstStep && (key == row + "-u" || key == row + "-uniform" || key == row + "u"))
      return SchemeVariant{traits.scheme, true};
  }
  for (const char* alias : kCatmullClarkAliases)
    if (key == alias) return SchemeVariant{Scheme::CatmullClark, false};
  return std::nullopt;
}

std::string schemeVariantName(const SchemeVariant& variant) {
  return std::string(schemeName(variant.scheme)) + (variant.uniformFirstStep ? "-u" : "");
}

std::string schemeVariantLabel(const SchemeVariant& variant) {
  return std::string(schemeTraits(variant.scheme).label) + (variant.uniformFirstStep ? "-U" : "");
}

}  // namespace polarview
