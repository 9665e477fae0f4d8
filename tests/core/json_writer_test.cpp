// The CLI's JSON writer (src/pipeline/json_writer.h, header-only and GL-free, so it is tested here):
// numbers round-trip, and a non-finite number is refused with an error naming the input, never
// printed as null or nan.
#include <doctest/doctest.h>

#include <cstdlib>
#include <limits>
#include <string>

#include "pipeline/json_writer.h"

using namespace polarview;
using polarview::JsonWriter;

TEST_CASE("json writer: doubles round-trip and nesting is well formed") {
  JsonWriter w("in.obj");
  w.beginObject().field("k", 0.1).field("n", 3).key("p").value(glm::dvec3(1e150, -2.5, 1e-300));
  w.key("none").null().endObject();
  CHECK(w.str() == R"({"k":0.10000000000000001,"n":3,"p":[9.9999999999999998e+149,-2.5,1e-300],"none":null})");
  CHECK(std::strtod("0.10000000000000001", nullptr) == 0.1);
}

TEST_CASE("json writer: a non-finite number is an InputError naming the input file and the key") {
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity()}) {
    JsonWriter w("globe.obj");
    w.beginObject().field("limit", glm::dvec3(0.0));
    try {
      w.field("gaussian_curvature", bad);
      FAIL("a non-finite number was written");
    } catch (const InputError& e) {
      CHECK(e.file() == "globe.obj");
      CHECK(std::string(e.what()).find("\"gaussian_curvature\"") != std::string::npos);
    }
    CHECK(w.str().find("null") == std::string::npos);
    CHECK_THROWS_AS(JsonWriter("globe.obj").value(glm::dvec3(0.0, bad, 0.0)), InputError);
  }
}
