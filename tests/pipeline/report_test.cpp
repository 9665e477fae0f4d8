// Reports as trees (report_value.h) print as JsonWriter prints the same calls; the spectrum use case
// (spectrum_report.h) gives what core's spectrum functions give.
#include <doctest/doctest.h>

#include <limits>

#include "core/mesh/input_error.h"
#include "pipeline/json_writer.h"
#include "pipeline/report_value.h"
#include "pipeline/spectrum_report.h"

using namespace polarview;

namespace {

// The same calls on either writer.
template <class Writer>
void writeSample(Writer& w) {
  w.beginObject().field("name", "x").field("count", size_t(3)).field("ok", true).key("none").null();
  w.field("point", glm::dvec3(0.0, -0.0, 1e-300)).key("list").beginArray();
  for (double x : {0.1, 1.0, 1e17, -2.5}) w.value(x);
  w.beginObject().endObject().beginArray().endArray().endArray().endObject();
}

}  // namespace

TEST_CASE("report tree: reportJson prints what JsonWriter prints for the same calls") {
  JsonWriter json;
  writeSample(json);
  ReportBuilder builder;
  writeSample(builder);
  const ReportValue tree = builder.take();
  CHECK(reportJson(tree) == json.str());
  CHECK(tree["count"].kind == ReportValue::Kind::Integer);
  CHECK(tree["list"].items[1].kind == ReportValue::Kind::Number);
  CHECK(tree["list"].items.size() == 6);
  CHECK_THROWS_AS(tree["missing"], std::out_of_range);
}

TEST_CASE("report tree: a non-finite number is refused as JsonWriter refuses it, naming the key") {
  ReportBuilder builder("in.obj");
  builder.beginObject().key("limit");
  CHECK_THROWS_WITH_AS(builder.value(std::numeric_limits<double>::infinity()),
                       doctest::Contains("in.obj: the result has a non-finite number (\"limit\")"), InputError);
}

TEST_CASE("spectrum report: the core's eigenvalues and pairs; C2PS measured on RTS") {
  const SpectrumReport r = makeSpectrumReport({Scheme::RTS, 8, 6, true, true});
  CHECK(r.shown == 6);
  CHECK(r.all.size() == schemeSpectrum(Scheme::RTS, 8).size());
  CHECK(r.pairs.size() == 6);
  CHECK(r.matrix.size() == 48);
  CHECK(std::abs(r.all[1].value - Complex(0.5, 0.0)) < 1e-12);
  CHECK(spectrumIsMeasured(Scheme::C2PS));
  CHECK(spectrumMinValence(Scheme::C2PS) == schemeTraits(Scheme::RTS).minValence);
  const SpectrumReport c2ps = makeSpectrumReport({Scheme::C2PS, 6, 8, false, false, 3});
  CHECK(c2ps.measured);
  CHECK(c2ps.steps.size() == 3);
  CHECK(reportJson(measuredSpectrumValue(c2ps)).rfind("{\"scheme\":\"c2ps\",\"valence\":6,\"steps\":[{\"m\":1,", 0) == 0);
}
