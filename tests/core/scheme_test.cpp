#include <doctest/doctest.h>

#include "core/subdiv/scheme.h"

using namespace polarview;

TEST_CASE("scheme names round-trip through the one parser, which also takes the other spellings") {
  for (Scheme s : {Scheme::CatmullClark, Scheme::C2PS, Scheme::RTS, Scheme::BPS}) {
    CHECK(parseSchemeVariant(schemeName(s))->scheme == s);
    CHECK_FALSE(parseSchemeVariant(schemeName(s))->uniformFirstStep);
  }
  CHECK_FALSE(parseSchemeVariant("loop").has_value());
  CHECK_FALSE(parseSchemeVariant("").has_value());
  for (const char* name : {"catmull-clark", "CatmullClark", "CC"}) {
    REQUIRE(parseSchemeVariant(name));
    CHECK(parseSchemeVariant(name)->scheme == Scheme::CatmullClark);
  }
  for (const char* name : {"c2ps-uniform", "C2PSU", "C2PS-U"}) {
    REQUIRE(parseSchemeVariant(name));
    CHECK(parseSchemeVariant(name)->scheme == Scheme::C2PS);
    CHECK(parseSchemeVariant(name)->uniformFirstStep);
  }
  CHECK(parseSchemeVariant("rts-uniform")->uniformFirstStep);
  CHECK_FALSE(parseSchemeVariant("bps-uniform"));
  CHECK_FALSE(parseSchemeVariant("bpsu"));
}

TEST_CASE("scheme table: one row per scheme in enum order; every name and variant reads back") {
  const std::array<Scheme, 4> all = {Scheme::CatmullClark, Scheme::C2PS, Scheme::RTS, Scheme::BPS};
  int variants = 0;
  for (Scheme s : all) {
    const SchemeTraits& traits = schemeTraits(s);
    CHECK(traits.scheme == s);
    CHECK(parseSchemeVariant(traits.name)->scheme == s);
    // A polar scheme has all four rules; Catmull-Clark none and no Taylor expansion.
    CHECK(traits.polar() == (traits.refineGrid && traits.refinePole && traits.refineLink1 && traits.refineLink2));
    CHECK(traits.polar() == (traits.taylorOrder > 0));
    for (bool uniform : {false, true}) {
      if (uniform && !traits.hasUniformFirstStep) {
        CHECK_FALSE(parseSchemeVariant(std::string(traits.name) + "-u"));
        continue;
      }
      const std::optional<SchemeVariant> back = parseSchemeVariant(schemeVariantName({s, uniform}));
      REQUIRE(back);
      CHECK(back->scheme == s);
      CHECK(back->uniformFirstStep == uniform);
      ++variants;
    }
  }
  CHECK(variants == 6);  // cc, c2ps, c2ps-u, rts, rts-u, bps
  CHECK(schemeVariantLabel({Scheme::C2PS, true}) == "C2PS-U");
  CHECK_FALSE(parseSchemeVariant("bps-u"));
  CHECK(parseSchemeVariant("C2PS")->scheme == Scheme::C2PS);  // case-insensitive, as the viewer always took it
}
