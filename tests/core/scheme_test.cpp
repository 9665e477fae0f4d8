#include <doctest/doctest.h>

#include "core/subdiv/scheme.h"

using namespace polarview;

TEST_CASE("scheme names round-trip through the parser") {
  for (Scheme s : {Scheme::CatmullClark, Scheme::C2PS, Scheme::RTS, Scheme::BPS})
    CHECK(parseScheme(schemeName(s)) == s);
  CHECK_FALSE(parseScheme("loop").has_value());
}
