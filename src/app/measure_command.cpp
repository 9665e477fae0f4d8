// `polarview measure IN.obj`: area, enclosed volume, centroid and inertia of the limit surface
// (pipeline/surface_measures.h), as text or JSON; docs/commands.md (measure).
#include "app/measure_command.h"

#include <cstdio>
#include <iostream>
#include <string>

#include "app/cli_options.h"
#include "app/json_writer.h"
#include "pipeline/model.h"
#include "pipeline/patch_export.h"
#include "pipeline/surface_measures.h"

namespace polarview::cli {
namespace {

struct MeasureArgs : SurfaceArgs {
  int points = 8;  // --points N
  bool json = false;
};

OptionTable measureTable(MeasureArgs& o) {
  return {inputRow(o.input),
          required(schemeRow(o, "the scheme")),
          levelsRow(o, {"--level", "--levels"}),
          intOption({"--points"}, "N", "Gauss-Legendre points per direction on each patch (2..16, default 8)", &o.points, 2,
                    16),
          uniformFirstStepRow(o),
          memoryBudgetRow(o), threadsRow(),
          jsonRow(&o.json)};
}

void writeTensor(JsonWriter& w, const char* key, const glm::dmat3& t) {
  w.key(key).beginArray();
  for (int i = 0; i < 3; ++i) w.value(glm::dvec3(t[0][i], t[1][i], t[2][i]));
  w.endArray();
}

// The report as JSON (docs/commands.md, measure); a non-finite number is refused. The solid's
// measures are null for an open surface.
std::string measureJson(const MeasureArgs& o, const SurfaceMeasures& m) {
  JsonWriter w(o.input);
  w.beginObject().field("scheme", cliSchemeName(o.scheme, o.uniformFirstStep)).field("level", o.levels);
  w.field("patches", m.patches).field("points", m.points).field("closed", m.closed);
  w.field("area", m.area).field("area_error", m.areaError).field("area_centroid", m.areaCentroid);
  writeTensor(w, "shell_inertia", m.shellInertia);
  if (m.closed) {
    w.field("volume", m.volume).field("volume_error", m.volumeError).field("centroid", m.centroid);
    writeTensor(w, "inertia", m.inertia);
  } else {
    w.key("volume").null().key("volume_error").null().key("centroid").null().key("inertia").null();
  }
  return w.endObject().str();
}

void printTensor(const char* title, const glm::dmat3& t) {
  std::printf("  %s\n", title);
  for (int i = 0; i < 3; ++i) std::printf("    %17.10g %17.10g %17.10g\n", t[0][i], t[1][i], t[2][i]);
}

void printMeasures(const MeasureArgs& o, const SurfaceMeasures& m) {
  std::printf("%s, %s level %d: %zu feature-adaptive patches, %d x %d Gauss-Legendre points each\n", o.input.c_str(),
              cliSchemeName(o.scheme, o.uniformFirstStep).c_str(), o.levels, m.patches, m.points, m.points);
  std::printf("  area      %.12g (error estimate %.2g)\n", m.area, m.areaError);
  std::printf("  area centroid (%.10g, %.10g, %.10g)\n", m.areaCentroid.x, m.areaCentroid.y, m.areaCentroid.z);
  printTensor("inertia of the shell about its centroid (unit density per area):", m.shellInertia);
  if (!m.closed) {
    std::printf("  open surface (boundary or holes): no enclosed volume\n");
    return;
  }
  std::printf("  volume    %.12g (error estimate %.2g)%s\n", m.volume, m.volumeError,
              m.volume < 0.0 ? "; negative: the faces turn clockwise (normals inwards)" : "");
  std::printf("  centroid  (%.10g, %.10g, %.10g)\n", m.centroid.x, m.centroid.y, m.centroid.z);
  printTensor("inertia of the solid about its centroid (unit density):", m.inertia);
}

int runMeasure(MeasureArgs& o) {
  checkFirstStep(o);
  PolyMesh mesh = loadInput(o.input);
  requireCurvatureExtent(mesh, o.input);
  const PatchSet set = makePatchSet(mesh, o.input, refineRequest(o, false));  // the patches `export` writes
  const SurfaceMeasures measures = measureSurface(set.patches, meshIsClosed(mesh), o.points);
  const std::string json = measureJson(o, measures);  // also for text: it refuses a non-finite number
  if (o.json) std::cout << json << "\n";
  else printMeasures(o, measures);
  return 0;
}

}  // namespace

CommandParser measureCommand() { return makeCommandParser(measureTable, runMeasure); }

}  // namespace polarview::cli
