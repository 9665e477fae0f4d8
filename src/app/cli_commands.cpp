#include "app/cli_commands.h"
#include "app/command_args.h"

#include <algorithm>
#include <fstream>
#include <cmath>
#include <limits>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <new>
#include <numeric>
#include <optional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "app/bench_peer.h"
#include "pipeline/stopwatch.h"
#include "pipeline/patch_export.h"
#include "pipeline/surface_export.h"
#include "app/json_writer.h"
#include "core/mesh/ev_to_polar.h"
#include "core/mesh/ngon_to_fan.h"
#include "core/mesh/input_error.h"
#include "core/mesh/manifold_split.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/shape_catalog.h"
#include "core/mesh/topology.h"
#include "core/spline/continuity.h"
#include "core/spline/patch_extraction.h"
#include "core/spline/pole_taylor.h"
#include "core/spline/ring_curvature.h"
#include "core/subdiv/spectrum.h"
#include "core/subdiv/adaptive_refiner.h"
#include "pipeline/scheme_choice.h"
#include "pipeline/surface_pipeline.h"
#include "pipeline/memory_budget.h"
#include "pipeline/mesh_report.h"
#include "pipeline/pole_report.h"
#include "pipeline/report_value.h"
#include "pipeline/spectrum_report.h"
#include "core/subdiv/polar_config.h"
#include "core/subdiv/parallel_for.h"
#include "core/subdiv/refiner.h"
#include "core/subdiv/table_pool.h"

namespace polarview::cli {

namespace {

// How many rejected pole candidates `info` lists in text per reason (the JSON lists all).
constexpr size_t kRejectedListedPerReason = 5;

// Options shared by the subcommands: the storage their option tables write into.
struct CommonOptions {
  std::string input, output;
  Scheme scheme = Scheme::C2PS;
  bool schemeGiven = false;
  bool uniformScheme = false;  // --scheme c2ps-u or rts-u
  bool uniformFlag = false;    // --uniform-first-step
  int levels = -1;
  int reps = 5;
  int rings = 0;  // pole --rings M
  size_t memoryBudget = 0;  // --memory-budget SIZE in bytes (0: from the available memory)
  bool uniformFirstStep = false;  // either of the two above (checkFirstStep)
  bool json = false;
  bool adaptive = false, edit = false;  // bench --adaptive [--edit]
  bool vsOpenSubdiv = false;             // bench --vs-opensubdiv
  bool uniform = false;                  // export --uniform
  std::string format, units = "mm";      // export --format NAME --units UNIT
  int samples = 8;                       // export --samples N
  bool evToPolar = false, pentagons = false;  // convert --ev-to-polar [--pentagons]
  bool ngonToFan = false;                     // convert --ngon-to-fan
};

// "2G", "500M", "64k", "123456" (bytes; binary units, case-insensitive, optional trailing B).
size_t parseByteSize(const std::string& flag, const std::string& text) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  std::string unit = text.substr(used);
  if (!unit.empty() && (unit.back() == 'B' || unit.back() == 'b')) unit.pop_back();
  double scale = 1.0;
  if (unit == "k" || unit == "K") scale = 1024.0;
  else if (unit == "m" || unit == "M") scale = 1024.0 * 1024.0;
  else if (unit == "g" || unit == "G") scale = 1024.0 * 1024.0 * 1024.0;
  else if (unit == "t" || unit == "T") scale = 1024.0 * 1024.0 * 1024.0 * 1024.0;
  else if (!unit.empty()) used = 0;
  if (used == 0 || !(value > 0.0) || !std::isfinite(value * scale) || value * scale > 1e18)
    throw UsageError{flag + " expects a size such as 2G, 500M or a number of bytes, got '" + text + "'"};
  return size_t(value * scale);
}

// The memory a refinement may take: --memory-budget, else memory_budget.h's default.
size_t memoryBudgetBytes(const CommonOptions& o) { return polarview::memoryBudgetBytes(o.memoryBudget); }

// memory_budget.h's refusal of o.levels, or the budget as a face count.
size_t checkMemoryBudget(const PolyMesh& mesh, const CommonOptions& o, bool adaptive = false) {
  return polarview::checkMemoryBudget(mesh, {o.scheme, o.levels, o.uniformFirstStep}, o.input, o.memoryBudget, adaptive);
}

// The name a scheme prints as: "c2ps-u" for C2PS with the uniform first step.
std::string cliSchemeName(Scheme scheme, bool uniformFirstStep) { return schemeVariantName({scheme, uniformFirstStep}); }

// [SECTION] Option rows the commands share

// Which scheme variants a command takes (every one, or those with a property of the scheme table).
using SchemeFilter = bool (*)(const SchemeVariant&);
bool anyScheme(const SchemeVariant&) { return true; }
bool polarScheme(const SchemeVariant& v) { return schemeTraits(v.scheme).polar(); }
// spectrum: a scheme-table row as it is (the Section-6 first step is no subdivision matrix of its own).
bool plainScheme(const SchemeVariant& v) { return !v.uniformFirstStep; }

// The names `accepts` takes, from the scheme-choice table: "cc|c2ps|c2ps-u|rts|rts-u|bps".
std::string schemeNames(SchemeFilter accepts, const std::string& separator) {
  return schemeChoiceNames(separator, [accepts](SchemeChoice c) { return accepts(schemeChoiceVariant(c)); });
}

// --scheme S: the scheme table's names, "-u" for the paper's Section-6 variant (the same as
// --uniform-first-step); a name `accepts` refuses is a usage error that lists the ones it takes.
// `help` names them (schemeNames).
OptionRow schemeRow(Scheme* scheme, bool* given, bool* uniform, SchemeFilter accepts, const std::string& help) {
  return actionOption({"--scheme"}, "S", help, [=](const std::string& name) {
    const std::optional<SchemeVariant> variant = parseSchemeVariant(name);
    if (!variant) throw UsageError{"unknown scheme '" + name + "' (" + schemeNames(accepts, ", ") + ")"};
    if (!accepts(*variant)) throw UsageError{"--scheme " + name + ": this command takes " + schemeNames(accepts, ", ")};
    *scheme = variant->scheme;
    *uniform = variant->uniformFirstStep;
    if (given) *given = true;
  });
}
// --scheme S for the commands that read IN.obj; `listed`: the schemes the help names.
OptionRow schemeRow(CommonOptions& o, const std::string& help = "the scheme, default c2ps", SchemeFilter listed = anyScheme) {
  return schemeRow(&o.scheme, &o.schemeGiven, &o.uniformScheme, anyScheme,
                   help + " (" + schemeNames(listed, "|") + ")");
}

OptionRow inputRow(CommonOptions& o) { return required(positionalOption("IN.obj", "the input mesh (OBJ)", &o.input)); }
OptionRow outputRow(std::string* output, const std::string& metavar, const std::string& help) {
  return required(textOption({"-o", "--output"}, metavar, help, output));
}
OptionRow levelsRow(CommonOptions& o, std::vector<std::string> names) {
  return required(intOption(std::move(names), "L", "refinement levels (0..64)", &o.levels, 0, 64));
}
// The schemes with the paper's Section-6 variant (the choices with a uniform first step): "c2ps and
// rts", or as names "c2ps-u, rts-u".
bool firstStepVariant(const SchemeVariant& v) { return v.uniformFirstStep; }
std::string firstStepSchemes() {
  std::string names;
  for (const SchemeTraits& s : schemeTable())
    if (s.hasUniformFirstStep) names += (names.empty() ? "" : " and ") + std::string(s.name);
  return names;
}

OptionRow uniformFirstStepRow(CommonOptions& o) {
  return flagOption({"--uniform-first-step"}, "the paper's Section-6 first step (" + firstStepSchemes() + " only; = --scheme " +
                    schemeNames(firstStepVariant, ", ") + ")", &o.uniformFlag);
}
OptionRow memoryBudgetRow(CommonOptions& o) {
  return actionOption({"--memory-budget"}, "SIZE", "refuse levels whose estimate needs more (2G, 500M, bytes; default 80% of "
                      "the available memory)", [&o](const std::string& text) { o.memoryBudget = parseByteSize("--memory-budget", text); });
}
OptionRow jsonRow(bool* json) { return flagOption({"--json"}, "print JSON", json); }

// After parsing: --scheme c2ps-u and --uniform-first-step are one choice. The Section-6 variant
// changes the first step's 2-link of C2PS and RTS only; elsewhere the flag would do nothing.
void checkFirstStep(CommonOptions& o) {
  o.uniformFirstStep = o.uniformFlag || o.uniformScheme;
  if (o.uniformFlag && !schemeTraits(o.scheme).hasUniformFirstStep)
    throw UsageError{"--uniform-first-step applies to " + firstStepSchemes() + " only"};
}

// Loads the OBJ and prints its warnings on stderr.
PolyMesh loadInput(const std::string& path) {
  std::vector<std::string> warnings;
  PolyMesh mesh = loadObj(path, &warnings);
  for (const std::string& w : warnings) std::cerr << "polarview: warning: " << path << ": " << w << "\n";
  return mesh;
}

// [SECTION] refine, export, convert

OptionTable refineTable(CommonOptions& o) {
  return {inputRow(o), outputRow(&o.output, "OUT.obj", "the finest level's mesh (OBJ)"), schemeRow(o),
          levelsRow(o, {"--levels", "--level"}), uniformFirstStepRow(o), memoryBudgetRow(o)};
}

int runRefine(CommonOptions& o) {
  checkFirstStep(o);
  PolyMesh mesh = loadInput(o.input);
  const size_t maxFaces = checkMemoryBudget(mesh, o);
  RefineOptions options{o.scheme, o.levels, o.uniformFirstStep};
  options.finestVertexRings = false;  // only the finest level's faces and points are written
  Refinement refinement(mesh, options, o.input, maxFaces);
  // A non-manifold input was refined split: its copies merge back (the input's topology refined).
  if (refinement.splitInput()) saveObj(o.output, refinement.outputMesh(), o.input);
  else saveObj(o.output, refinement.finest().mesh, o.input);
  return 0;
}

OptionTable exportTable(CommonOptions& o) {
  return {inputRow(o),
          outputRow(&o.output, "OUT.bv",
                    "the limit surface; the format from the extension (" + exportFormatExtensions() + ")"),
          textOption({"--format"}, "NAME", "write this format whatever the extension (" + exportFormatNames() + ")",
                     &o.format),
          required(schemeRow(o, "the scheme")),
          levelsRow(o, {"--level", "--levels"}),
          textOption({"--units"}, "UNIT", "the length unit STEP and IGES name (mm, m, inch; default mm); coordinates are "
                                          "not scaled",
                     &o.units),
          intOption({"--samples"}, "N", "tessellations (ply, glb): segments along each patch edge (default 8)",
                    &o.samples, 1, 64),
          flagOption({"--uniform"}, "refine every face (default: feature-adaptive, as view and render)", &o.uniform),
          uniformFirstStepRow(o),
          memoryBudgetRow(o)};
}

// The row of surface_export.h's table that writes o.output: --format, else the extension.
const ExportFormat& chosenExportFormat(const CommonOptions& o) {
  if (!o.format.empty()) {
    if (const ExportFormat* format = exportFormatNamed(o.format)) return *format;
    throw UsageError{"--format expects one of " + exportFormatNames() + ", got '" + o.format + "'"};
  }
  if (const ExportFormat* format = exportFormatForPath(o.output)) return *format;
  throw UsageError{"cannot tell the format of '" + o.output + "': name it " + exportFormatExtensions() +
                   " or give --format"};
}

LengthUnit chosenLengthUnit(const CommonOptions& o) {
  for (const LengthUnitInfo& unit : lengthUnits())
    if (o.units == unit.name) return unit.unit;
  std::string names;
  for (const LengthUnitInfo& unit : lengthUnits()) names += std::string(names.empty() ? "" : ", ") + unit.name;
  throw UsageError{"--units expects one of " + names + ", got '" + o.units + "'"};
}

int runExport(CommonOptions& o) {
  checkFirstStep(o);
  const ExportFormat& format = chosenExportFormat(o);
  ExportSettings settings;
  settings.source = o.input;
  settings.units = chosenLengthUnit(o);
  settings.samples = o.samples;
  settings.memoryBudget = o.memoryBudget;
  settings.level = o.levels;
  settings.schemeLabel = schemeName(o.scheme);
  PolyMesh mesh = loadInput(o.input);
  if (format.curvature) requireCurvatureExtent(mesh, o.input);
  // The adaptive path's hard face limit leaves room over its estimate (an extrapolation past level 6).
  const size_t maxFaces = checkMemoryBudget(mesh, o, !o.uniform) * (o.uniform ? 1 : 2);
  const PatchSet set = exportPatchSet(mesh, {o.scheme, o.levels, o.uniformFirstStep}, o.input, o.uniform, maxFaces);
  const std::string summary = format.write(o.output, set, settings);
  std::printf("%s: %s; %s refinement\n", o.output.c_str(), summary.c_str(), o.uniform ? "uniform" : "feature-adaptive");
  return 0;
}

// [SECTION] continuity

OptionTable continuityTable(CommonOptions& o) {
  return {inputRow(o),
          required(schemeRow(o, "the scheme")),
          levelsRow(o, {"--level", "--levels"}),
          intOption({"--samples"}, "K", "points compared along each patch side (default 8)", &o.samples, 1, 64),
          uniformFirstStepRow(o),
          memoryBudgetRow(o),
          jsonRow(&o.json)};
}

// The report as JSON (docs/commands.md, continuity); it refuses a non-finite number.
std::string continuityJson(const CommonOptions& o, const ContinuityReport& report) {
  JsonWriter w(o.input);
  w.beginObject().key("seams").beginArray();
  for (const SeamStats& s : report.seams)
    w.beginObject()
        .field("kind", seamKindName(s.kind))
        .field("count", s.count)
        .field("t_junctions", s.tJunctions)
        .field("max_position_gap", s.maxPositionGap)
        .field("max_normal_angle", s.maxNormalAngle)
        .field("max_curvature_jump", s.maxCurvatureJump())
        .field("max_gaussian_jump", s.maxGaussianJump)
        .field("max_mean_jump", s.maxMeanJump)
        .endObject();
  w.endArray().field("boundary_sides", report.boundarySides).field("max_abs_gaussian", report.maxAbsGaussian);
  w.field("max_abs_mean", report.maxAbsMean).field("box_diagonal", report.boxDiagonal).field("samples", o.samples);
  w.field("scheme", cliSchemeName(o.scheme, o.uniformFirstStep));
  return w.field("level", o.levels).endObject().str();
}

void printContinuity(const CommonOptions& o, const ContinuityReport& report) {
  std::printf("%s, %s level %d: continuity across the seams of the limit surface (feature-adaptive patches)\n",
              o.input.c_str(), cliSchemeName(o.scheme, o.uniformFirstStep).c_str(), o.levels);
  std::printf("  gap: relative to the box diagonal %.6g; K, H jumps: relative to max|K| %.6g, max|H| %.6g\n",
              report.boxDiagonal, report.maxAbsGaussian, report.maxAbsMean);
  std::printf("  %-12s %7s %6s %11s %11s %11s %11s %11s\n", "kind", "seams", "T-jn", "max gap", "normal rad",
              "normal deg", "max dK", "max dH");
  for (const SeamStats& s : report.seams)
    std::printf("  %-12s %7zu %6zu %11.3g %11.3g %11.3g %11.3g %11.3g\n", seamKindName(s.kind), s.count, s.tJunctions,
                s.maxPositionGap, s.maxNormalAngle, s.maxNormalAngle * 180.0 / M_PI, s.maxGaussianJump, s.maxMeanJump);
  std::printf("  boundary sides (no partner): %zu\n", report.boundarySides);
}

int runContinuity(CommonOptions& o) {
  checkFirstStep(o);
  PolyMesh mesh = loadInput(o.input);
  requireCurvatureExtent(mesh, o.input);
  // The patches `export` writes (feature-adaptive), with export's face limit.
  const size_t maxFaces = checkMemoryBudget(mesh, o, true) * 2;
  const PatchSet set = exportPatchSet(mesh, {o.scheme, o.levels, o.uniformFirstStep}, o.input, false, maxFaces);
  ContinuityOptions options;
  options.samplesPerSide = o.samples;
  const ContinuityReport report = measureContinuity(set, options);
  const std::string json = continuityJson(o, report);  // also for text: it refuses a non-finite number
  if (o.json) std::cout << json << "\n";
  else printContinuity(o, report);
  return 0;
}

// The conversions `convert` makes, one flag each and exactly one a call: what the flag means and
// what the conversion prints once the mesh is written.
struct MeshConversion {
  const char* flag;
  const char* help;
  bool CommonOptions::*chosen;
  void (*run)(const CommonOptions& o, const PolyMesh& mesh);
};

void runEvToPolar(const CommonOptions& o, const PolyMesh& mesh) {
  const PolarConversion conversion = convertExtraordinaryToPolar(mesh, o.pentagons, o.input);
  saveObj(o.output, conversion.mesh, o.input);
  std::printf("%s: %zu extraordinary vertices turned into %s polar configurations (Fig. 14(%s))", o.output.c_str(),
              conversion.converted.size(), o.pentagons ? "n-valent" : "2n-valent", o.pentagons ? "c" : "a");
  if (!conversion.skipped.empty())
    std::printf("; %zu skipped: their regions touch a converted one (first: vertex %d)", conversion.skipped.size(),
                conversion.skipped.front());
  std::printf("\n");
}

void runNgonToFan(const CommonOptions& o, const PolyMesh& mesh) {
  const FanConversion conversion = convertNgonsToFans(mesh);
  saveObj(o.output, conversion.mesh, o.input);
  const size_t count = conversion.faces.size();
  std::printf("%s: %zu face%s with %d or more sides turned into triangle fans around new centre vertices", o.output.c_str(),
              count, count == 1 ? "" : "s", kMinFanSides);
  if (count == 1) std::printf(" (vertex %d)", conversion.centres.front());
  if (count > 1) std::printf(" (vertices %d..%d)", conversion.centres.front(), conversion.centres.back());
  std::printf("\n");
}

const MeshConversion kMeshConversions[] = {
    {"--ev-to-polar", "extraordinary vertices into polar configurations (paper Fig. 14)", &CommonOptions::evToPolar,
     runEvToPolar},
    {"--ngon-to-fan", "faces of 5 or more sides into triangle fans around their centroids (Blender's cap fill; "
                      "a cylinder's caps become poles)",
     &CommonOptions::ngonToFan, runNgonToFan},
};

OptionTable convertTable(CommonOptions& o) {
  OptionTable table{inputRow(o), outputRow(&o.output, "OUT.obj", "the converted mesh (OBJ)")};
  for (const MeshConversion& conversion : kMeshConversions)
    table.push_back(flagOption({conversion.flag}, conversion.help, &(o.*conversion.chosen)));
  table.push_back(flagOption({"--pentagons"}, "with --ev-to-polar: n-valent poles ringed by pentagons (Fig. 14c; default "
                                              "2n-valent, 14a)",
                             &o.pentagons));
  return table;
}

int runConvert(CommonOptions& o) {
  const MeshConversion* chosen = nullptr;
  std::string flags;
  for (const MeshConversion& conversion : kMeshConversions) {
    flags += std::string(flags.empty() ? "" : " or ") + conversion.flag;
    if (!(o.*conversion.chosen)) continue;
    if (chosen) throw UsageError{std::string("give one conversion a call: ") + chosen->flag + " or " + conversion.flag};
    chosen = &conversion;
  }
  if (!chosen) throw UsageError{"needs a conversion: " + flags};
  if (o.pentagons && !o.evToPolar) throw UsageError{"--pentagons applies to --ev-to-polar"};
  chosen->run(o, loadInput(o.input));
  return 0;
}

// [SECTION] info

OptionTable infoTable(CommonOptions& o) { return {inputRow(o), jsonRow(&o.json)}; }

// The text report's poles and rejected candidates.
void printInfoPoles(const MeshReport& r) {
  std::printf("poles: %zu\n", r.poles.size());
  if (r.poles.empty() && r.fanFaces > 0)
    std::printf("  %d faces of %d or more sides: convert --ngon-to-fan makes each a triangle fan, a pole where quads "
                "ring it (a cylinder's caps)\n",
                r.fanFaces, kMinFanSides);
  for (const PolarConfig& c : r.poles) {
    std::printf("  vertex %d: valence %d, %d link%s (%d regular), ends at %s", c.pole, c.valence, c.linkCount,
                c.linkCount == 1 ? "" : "s", c.regularLinks, outerName(c.outer));
    if (c.oppositePole >= 0) std::printf(" %d", c.oppositePole);
    std::printf("\n");
    for (const SchemeTraits& s : schemeTable())  // the polar schemes first, Catmull-Clark last
      if (s.polar()) std::printf("    %-4s %s\n", s.name, schemeAction(s.scheme, c, r.radialMesh).c_str());
    std::printf("    %-4s %s\n", schemeName(Scheme::CatmullClark), schemeAction(Scheme::CatmullClark, c, r.radialMesh).c_str());
  }
  if (r.rejected.empty()) return;
  std::printf("rejected pole candidates: %zu (reasons:", r.rejected.size());
  const char* separator = " ";
  for (const auto& [rejection, count] : r.rejectedPerReason) {
    std::printf("%s%d %s", separator, count, polarRejectionWords(rejection));
    separator = "; ";
  }
  std::printf("); refined by Catmull-Clark in every scheme\n");
  // Grouped by reason, the nearest candidates first (a cap's fan centre before the vertices of a
  // triangulated surface); a triangle mesh has a candidate at nearly every vertex: --json lists all.
  for (const RejectedGroup& group : groupRejectedCandidates(r.rejected)) {
    const PolarConfig& nearest = r.rejected[group.members.front()];
    const PolarConfig& farthest = r.rejected[group.members.back()];
    std::printf("  %s: %zu candidate%s, valence %d", polarRejectionWords(group.rejection), group.members.size(),
                group.members.size() == 1 ? "" : "s", nearest.valence);
    if (farthest.valence != nearest.valence) std::printf(" down to %d", farthest.valence);
    std::printf("\n");
    const size_t shown = std::min(group.members.size(), kRejectedListedPerReason);
    for (size_t k = 0; k < shown; ++k) {
      const PolarConfig& c = r.rejected[group.members[k]];
      std::printf("    vertex %d (valence %d): %s\n", c.pole, c.valence, c.reason.c_str());
    }
    if (group.members.size() > shown)
      std::printf("    ... %zu more (info --json lists every one)\n", group.members.size() - shown);
  }
}

void printInfoText(const std::string& file, const PolyMesh& mesh, const MeshTopology& topo, const ManifoldSplit& split,
                   const MeshReport& r) {
  std::printf("%s: %d vertices, %d faces (%d triangles, %d quads, %d polygons), %d edges, %d boundary loop%s\n",
              file.c_str(), r.used, mesh.faceCount(), r.triangles, r.quads, r.polygons, topo.edgeCount, r.loops,
              r.loops == 1 ? "" : "s");
  if (topo.vertexCount - r.copies > r.used) std::printf("  %d unreferenced vertices ignored\n", topo.vertexCount - r.copies - r.used);
  if (r.holeFaces > 0)
    std::printf("holes: %d faces ('t hole' or 'interpolateboundary 0'): refined, no surface there\n", r.holeFaces);
  if (!split.empty())
    std::printf("non-manifold: %zu edges, %zu vertices; refined as OpenSubdiv does (made infinitely sharp: creases and corners),"
                " the mesh split along them (%d vertex copies; edges and boundary loops above count the split mesh)\n",
                split.nonManifoldEdges, split.nonManifoldVertices, r.copies);
  printInfoPoles(r);
  std::printf("extraordinary vertices (Catmull-Clark): %zu\n", r.extraordinary.size());
  for (const Extraordinary& x : r.extraordinary)
    std::printf("  vertex %d: valence %d%s%s\n", x.vertex, x.valence, x.boundary ? " (boundary)" : "",
                x.pole ? " — a pole: polar schemes refine it, cc treats it as extraordinary" : " — Catmull-Clark in every scheme");
  if (r.triangles + r.polygons > 0)
    std::printf("non-quad faces: %d (their face points become extraordinary vertices after one Catmull-Clark step)\n",
                r.triangles + r.polygons);
}

int runInfo(CommonOptions& o) {
  const PolyMesh input = loadInput(o.input);
  ManifoldSplit split;  // a non-manifold input: its poles are the split mesh's (manifold_split.h)
  MeshTopology topo;
  const PolyMesh& mesh = refinableMesh(input, split, topo, o.input);
  const MeshReport report = reportMesh(input, mesh, topo);
  if (o.json) std::cout << meshInfoJson(o.input, mesh, topo, split, report) << "\n";
  else printInfoText(o.input, mesh, topo, split, report);
  return 0;
}

// [SECTION] pole

OptionTable poleTable(CommonOptions& o) {
  // Any scheme parses (--uniform-first-step is judged first); runPole refuses a scheme without poles.
  return {inputRow(o), schemeRow(o, "the polar scheme, default c2ps", polarScheme),
          uniformFirstStepRow(o),
          intOption({"--rings"}, "M", "curvature over spline rings 1..M (1..20)", &o.rings, 1, 20), jsonRow(&o.json)};
}

// One pole's text line (and with --rings its ring table). Why K and H are missing: no tangent
// plane (any scheme), or BPS's expansion, which stops at the tangent plane; where K depends on the
// direction (RTS), over which range on the last ring.
void printPole(const CommonOptions& o, const RefinedLevel& level, size_t k, const PoleDifferential& d,
               const std::vector<RingCurvature>& ringStats, bool directional) {
  const SchemeTraits& traits = schemeTraits(o.scheme);
  std::string note;
  if (d.normal == Point(0.0)) note = " (no tangent plane: p1 x p2 = 0, normal and curvature not defined)";
  else if (!d.curvatureDefined && traits.taylorOrder < 2)
    note = " (curvature not defined: " + std::string(traits.label) + " is C1 at the pole)";
  if (directional && d.curvatureDefined && !ringStats.empty()) {
    const RingCurvature& last = ringStats.back();
    char range[200];
    std::snprintf(range, sizeof range,
                  " (Taylor (32); %s is not C2 for finite n: K depends on the direction, on ring %d K in [%.6g, %.6g])",
                  traits.label, last.m, last.minK, last.maxK);
    note += range;
  }
  // Where the JSON has null, the text says "undefined" (the note above says why).
  const auto defined = [&](double value, const char* format) {
    char text[64];
    std::snprintf(text, sizeof text, format, value);
    return d.curvatureDefined ? std::string(text) : std::string("undefined");
  };
  std::printf("vertex %d (valence %d): limit (%.9g, %.9g, %.9g) normal (%.6f, %.6f, %.6f) K %s H %s%s\n",
              level.poles[k].pole, level.poles[k].valence, d.limit.x, d.limit.y, d.limit.z, d.normal.x, d.normal.y,
              d.normal.z, defined(d.gaussian, "%.9g").c_str(), defined(d.mean, "%.9g").c_str(), note.c_str());
  if (o.rings <= 0) return;
  std::printf("  ring  valence  max|K-K0|     K min .. max                 max|H-H0|\n");
  for (const RingCurvature& r : ringStats)
    std::printf("  %4d  %7d  %-12s  %-12.6g .. %-12.6g  %-12s\n", r.m, r.valence, defined(r.maxAbsDeltaK, "%.4g").c_str(),
                r.minK, r.maxK, defined(r.maxAbsDeltaH, "%.4g").c_str());
}

int runPole(CommonOptions& o) {
  checkFirstStep(o);
  if (!polarScheme({o.scheme, o.uniformFirstStep}))
    throw UsageError{"pole analysis needs --scheme " + schemeNames(polarScheme, ", ")};
  // RTS is not C2 for finite n: its K keeps depending on the direction. Its text report gives the
  // range over ring 8 at least, rather than one K as if it were defined.
  const SchemeTraits& traits = schemeTraits(o.scheme);
  const bool directional = traits.taylorOrder == 2 && !traits.curvatureContinuous;
  const int rings = directional && !o.json ? std::max(o.rings, 8) : o.rings;
  // The report's tree is made first, text or not: it refuses a non-finite number before anything is printed.
  const PoleReport report = makePoleReport(loadInput(o.input), o.input, {o.scheme, o.uniformFirstStep}, rings);
  const RefinedLevel& level = report.refinement.level(0);
  if (o.json) std::cout << reportJson(report.value) << "\n";
  else if (level.poles.empty()) std::printf("no refinable poles\n");
  else
    for (size_t k = 0; k < level.poles.size(); ++k)
      printPole(o, level, k, report.poles[k].differential, report.poles[k].rings, directional);
  return 0;
}

// [SECTION] bench

OptionTable benchTable(CommonOptions& o) {
  return {inputRow(o),
          schemeRow(o),
          levelsRow(o, {"--levels", "--level"}),
          intOption({"--reps"}, "N", "repetitions; medians are reported (1..1000, default 5)", &o.reps, 1, 1000),
          uniformFirstStepRow(o),
          memoryBudgetRow(o),
          flagOption({"--adaptive"}, "the feature-adaptive path of view, render and export", &o.adaptive),
          flagOption({"--edit"}, "with --adaptive: time one moved vertex's update", &o.edit),
          flagOption({"--vs-opensubdiv"}, "OpenSubdiv 3.5 in the same run (uniform: its points checked against ours; "
                     "--adaptive: its RefineAdaptive + PatchTableFactory timed beside ours, patches counted)", &o.vsOpenSubdiv),
          jsonRow(&o.json)};
}

// Bytes the positions pass must move at least, all levels: each level's parent points read once,
// child points written once, and the index tables the point rules stream (catmull_clark.cpp:
// faces, edges' ends and faces, vertex rings). Gathers of neighbours are not counted again.
double positionsTrafficBytes(const Refinement& refinement) {
  double bytes = 0;
  for (int m = 1; m < refinement.levelCount(); ++m) {
    const RefinedLevel& parent = refinement.level(m - 1);
    const MeshTopology& t = parent.topology;
    const size_t indices = parent.mesh.faceStart.size() + parent.mesh.faceVerts.size() + t.edgeVerts.size() +
                           t.edgeFaces.size() + t.vertexEdgeStart.size() + t.vertexEdges.size() + t.vertexFaceStart.size() +
                           t.vertexFaces.size();
    bytes += double(indices) * sizeof(Index) + 2.0 * double(t.vertexCount) * sizeof(uint8_t);
    bytes += double(parent.mesh.points.size() + refinement.level(m).mesh.points.size()) * sizeof(Point);
  }
  return bytes;
}

// Bytes of one level's arrays: points, faces, face parents and every topology table it holds.
double levelBytes(const RefinedLevel& level) {
  const MeshTopology& t = level.topology;
  double bytes = double(level.mesh.points.size()) * sizeof(Point) + double(t.vertexOnBoundary.size() + t.vertexUsed.size());
  for (const std::vector<Index>* table : {&level.mesh.faceStart, &level.mesh.faceVerts, &level.faceParent, &t.cornerEdge,
                                          &t.cornerFace, &t.edgeVerts, &t.edgeFaces, &t.vertexFaceStart, &t.vertexFaces,
                                          &t.vertexEdgeStart, &t.vertexEdges, &t.vertexCorners})
    bytes += double(table->size()) * sizeof(Index);
  return bytes;
}

// The arrays a refinement holds (every level: a library user reads any of them), as built.
double refinementBytes(const Refinement& refinement) {
  double bytes = 0;
  for (int m = 0; m < refinement.levelCount(); ++m) bytes += levelBytes(refinement.level(m));
  return bytes;
}

// bench --adaptive: the feature-adaptive path of view, render and export (adaptive_refiner.h).
// topology_ms = construction - positions; positions_ms = updatePositions; patches_ms = extraction;
// --edit adds edit_ms: one base vertex moved, then the points of every level and the patches'
// control points recomputed on the kept hierarchy (updatePositions + refreshPatches).
// The viewer's level steps on one kept refinement and LevelPatchCache (levels >= 1):
// level_up_ms = level L-1 shown, extend(1) + the patch set of L; level_down_ms = back to L-1;
// level_up_again_ms = to L once more (all of it cached).
// The viewer's own step (surface_pipeline.h): level L-1 shown, level L's whole surface made ahead
// while idle (made_ahead_ms: prepareLevel, refinement, patches and curvature samples), then the step
// (level_up_made_ahead_ms: buildSurface handing it out; the GPU upload is not in it).
// --vs-opensubdiv: OpenSubdiv's RefineAdaptive + PatchTableFactory beside it (AdaptivePeer), its
// numbers in "peer", the ratios and patches_agree at the top level (docs/performance.md).

// What the adaptive bench measured, repetition by repetition, and the peer's timing.
struct AdaptiveBench {
  std::vector<double> build, positions, patches, edits, levelUp, levelDown, levelUpAgain, madeAhead, levelUpMadeAhead;
  std::string viewerStepRefusal;  // why the viewer's step is not timed (the viewer would refuse it)
  size_t patchCount = 0, totalFaces = 0, finestFaces = 0, polesRefined = 0;
  std::vector<size_t> levelFaces;
  double peakRssMb = 0.0;
  double topologyMs = 0, positionsMs = 0, patchesMs = 0;
  bool compared = false, peerFailed = false;
  std::string comparison;
  AdaptivePeerTiming theirs;
};

// One repetition of our path: the refinement, its patches and --edit's update.
void timeAdaptiveRefinement(const CommonOptions& o, const PolyMesh& mesh, int rep, size_t budgetFaces, AdaptiveBench& b) {
  auto t0 = std::chrono::steady_clock::now();
  AdaptiveRefinement refinement(mesh, {o.scheme, o.levels, o.uniformFirstStep}, o.input, budgetFaces);
  b.build.push_back(millisecondsSince(t0));
  t0 = std::chrono::steady_clock::now();
  refinement.updatePositions(mesh.points);
  b.positions.push_back(millisecondsSince(t0));
  t0 = std::chrono::steady_clock::now();
  PatchSources sources;
  PatchSet set = extractPatches(refinement, &sources);
  b.patches.push_back(millisecondsSince(t0));
  b.patchCount = set.patches.size();
  // The path's own peak: before the level steps keep more refinements and surfaces alive.
  if (rep == 0) b.peakRssMb = peakResidentMegabytes();
  b.totalFaces = refinement.totalFaces();
  b.finestFaces = size_t(refinement.level(refinement.levelCount() - 1).mesh.faceCount());
  b.polesRefined = refinement.level(0).poles.size();
  b.levelFaces.clear();
  for (int m = 0; m < refinement.levelCount(); ++m) b.levelFaces.push_back(size_t(refinement.level(m).mesh.faceCount()));
  if (!o.edit) return;
  // Drag vertex 0 by 1% of the first edge's length, as the viewer does per frame.
  std::vector<Point> moved = mesh.points;
  moved[0] += 0.01 * (mesh.points[size_t(mesh.faceVerts[1])] - mesh.points[size_t(mesh.faceVerts[0])]);
  t0 = std::chrono::steady_clock::now();
  refinement.updatePositions(moved);
  refreshPatches(refinement, sources, set);
  b.edits.push_back(millisecondsSince(t0));
}

// The level steps on one kept refinement and LevelPatchCache (levels >= 1).
void timeLevelSteps(const CommonOptions& o, const PolyMesh& mesh, size_t budgetFaces, AdaptiveBench& b) {
  AdaptiveRefinement stepped(mesh, RefineOptions{o.scheme, o.levels - 1, o.uniformFirstStep}, o.input, budgetFaces);
  LevelPatchCache cache;
  PatchSources stepSources;
  cache.patchSet(stepped, o.levels - 1, &stepSources);  // what the view showed
  auto t0 = std::chrono::steady_clock::now();
  stepped.extend(1, budgetFaces);
  cache.patchSet(stepped, o.levels, &stepSources);
  b.levelUp.push_back(millisecondsSince(t0));
  t0 = std::chrono::steady_clock::now();
  cache.patchSet(stepped, o.levels - 1, &stepSources);
  b.levelDown.push_back(millisecondsSince(t0));
  t0 = std::chrono::steady_clock::now();
  cache.patchSet(stepped, o.levels, &stepSources);
  b.levelUpAgain.push_back(millisecondsSince(t0));
}

// The viewer's own step (surface_pipeline.h): level L made ahead while L-1 is shown, then the step.
// The viewer offers fewer levels than the bench refines (its level cap, its bytes a face): where it
// would refuse these, the bench says so instead of timing them.
void timeViewerStep(const CommonOptions& o, const Model& model, const std::string& scheme, size_t viewFaceBudget,
                    AdaptiveBench& b) {
  if (!b.viewerStepRefusal.empty()) return;
  const SurfaceKey shownKey{model.generation, *parseSchemeChoice(scheme), o.levels - 1, model.points};
  SurfaceKey nextKey = shownKey;
  nextKey.level = o.levels;
  b.viewerStepRefusal = checkFaceBudget(model, nextKey, viewFaceBudget);
  if (!b.viewerStepRefusal.empty()) return;
  const std::shared_ptr<const BuiltSurface> shown = buildSurface(model, shownKey, viewFaceBudget);
  auto t0 = std::chrono::steady_clock::now();
  if (!prepareLevel(*shown->hierarchy, model, nextKey, viewFaceBudget)) {
    b.viewerStepRefusal = "level " + std::to_string(o.levels) + " could not be made ahead (memory)";
    return;
  }
  b.madeAhead.push_back(millisecondsSince(t0));
  t0 = std::chrono::steady_clock::now();
  const std::shared_ptr<const BuiltSurface> next = buildSurface(model, nextKey, viewFaceBudget, shown->hierarchy);
  b.levelUpMadeAhead.push_back(millisecondsSince(t0));
}

// --vs-opensubdiv: the peer's result where it computed the same surface; no OpenSubdiv (or it
// refused the mesh) fails the command, as the uniform bench's peer; too many levels only says so.
void compareWithAdaptivePeer(const CommonOptions& o, std::optional<AdaptivePeer>& peer, bool peerWanted, AdaptiveBench& b) {
  if (peer && !peer->unavailable().empty() && (peerWanted || o.levels <= AdaptivePeer::kMaxLevels)) {
    b.comparison = "no peer: " + peer->unavailable();
    b.peerFailed = o.levels <= AdaptivePeer::kMaxLevels;
  } else if (peer && peerWanted) {
    b.theirs = peer->result();
    b.compared = true;
    b.comparison = "same surface: Catmull-Clark, OpenSubdiv's RefineAdaptive + PatchTableFactory (B-spline end caps)";
  }
}

// Ours against OpenSubdiv's: topology, positions and patches together.
double adaptiveSpeedup(const AdaptiveBench& b) {
  const AdaptivePeerTiming& t = b.theirs;
  return (t.topologyMs + t.positionsMs + t.patchesMs) / std::max(b.topologyMs + b.positionsMs + b.patchesMs, 1e-9);
}

std::string adaptiveBenchJson(const CommonOptions& o, const std::string& scheme, const Model& model, const AdaptiveBench& b) {
  const AdaptivePeerTiming& theirs = b.theirs;
  JsonWriter w(o.input);
  w.beginObject().field("file", o.input).field("scheme", scheme).field("levels", o.levels).field("adaptive", true);
  w.field("reps", o.reps).field("topology_ms", b.topologyMs).field("positions_ms", b.positionsMs);
  w.field("patches_ms", b.patchesMs).field("patches", b.patchCount).field("total_faces", b.totalFaces);
  w.field("finest_faces", b.finestFaces);
  if (o.edit) w.field("edit_ms", median(b.edits));
  if (o.levels >= 1)
    w.field("level_up_ms", median(b.levelUp)).field("level_down_ms", median(b.levelDown)).field("level_up_again_ms", median(b.levelUpAgain));
  if (o.levels >= 1 && b.viewerStepRefusal.empty())
    w.field("made_ahead_ms", median(b.madeAhead)).field("level_up_made_ahead_ms", median(b.levelUpMadeAhead));
  else if (o.levels >= 1)
    w.key("made_ahead_ms").null().key("level_up_made_ahead_ms").null().field("viewer_step", b.viewerStepRefusal);
  w.field("peak_rss_mb", b.peakRssMb);
  // Memory a refined face and a patch cost at the peak (the whole process's peak over either count),
  // and the deepest level of this scheme a view's memory budget (640 MB) admits on the model.
  w.field("peak_bytes_per_face", b.peakRssMb * 1048576.0 / double(std::max<size_t>(b.totalFaces, 1)));
  w.field("peak_bytes_per_patch", b.peakRssMb * 1048576.0 / double(std::max<size_t>(b.patchCount, 1)));
  w.field("view_deepest_level", deepestLevel(model, *parseSchemeChoice(scheme), kDefaultFaceBudget));
  w.key("level_faces").beginArray();
  for (size_t faces : b.levelFaces) w.value(faces);
  w.endArray();
  if (o.vsOpenSubdiv) {
    if (b.compared) {
      w.key("peer").beginObject().field("name", theirs.name);
      w.field("what",
              "Far::TopologyRefiner::RefineAdaptive (useInfSharpPatch) + Far::PatchTableFactory (ENDCAP_BSPLINE_BASIS) + "
              "Far::PrimvarRefiner and the local point stencils");
      w.field("topology_ms", theirs.topologyMs).field("positions_ms", theirs.positionsMs);
      w.field("patches_ms", theirs.patchesMs).field("patches", theirs.patches).field("total_faces", theirs.totalFaces);
      w.field("total_vertices", theirs.totalVertices).field("local_points", theirs.localPoints);
      w.key("level_faces").beginArray();
      for (size_t faces : theirs.levelFaces) w.value(faces);
      w.endArray();
      if (theirs.peakRssMb > 0) w.field("peak_rss_mb", theirs.peakRssMb);
      w.endObject();
    }
    w.field("compared", b.compared).field("comparison", b.comparison);
    if (b.compared) {
      w.field("topology_speedup", theirs.topologyMs / std::max(b.topologyMs, 1e-9))
          .field("patches_speedup", theirs.patchesMs / std::max(b.patchesMs, 1e-9));
      w.field("positions_speedup", theirs.positionsMs / std::max(b.positionsMs, 1e-9))
          .field("speedup", adaptiveSpeedup(b))
          .field("faces_ratio", double(b.totalFaces) / double(std::max<size_t>(theirs.totalFaces, 1)));
      w.field("patches_agree", theirs.patches == b.patchCount);
    }
  }
  w.endObject();
  return w.str();
}

void printAdaptiveBench(const CommonOptions& o, const std::string& scheme, const AdaptiveBench& b) {
  const AdaptivePeerTiming& theirs = b.theirs;
  std::printf("%s %s level %d (adaptive): topology %.3f ms, positions %.3f ms, patches %.3f ms; %zu patches, %zu faces in "
              "all levels; peak RSS %.1f MB\n",
              o.input.c_str(), scheme.c_str(), o.levels, b.topologyMs, b.positionsMs, b.patchesMs, b.patchCount, b.totalFaces,
              b.peakRssMb);
  if (o.edit) std::printf("edit (one base vertex moved -> new patches): %.3f ms\n", median(b.edits));
  if (o.levels >= 1)
    std::printf("level steps on the kept hierarchy: %d -> %d %.3f ms, back %.3f ms, again %.3f ms\n", o.levels - 1,
                o.levels, median(b.levelUp), median(b.levelDown), median(b.levelUpAgain));
  if (o.levels >= 1 && b.viewerStepRefusal.empty())
    std::printf("the viewer's step: level %d made ahead while idle %.3f ms, then the step %.3f ms (upload not counted)\n",
                o.levels, median(b.madeAhead), median(b.levelUpMadeAhead));
  else if (o.levels >= 1)
    std::printf("the viewer's step: not timed (%s)\n", b.viewerStepRefusal.c_str());
  if (b.compared)
    std::printf("%s adaptive: topology %.3f ms, positions %.3f ms, patches %.3f ms; %zu patches (%s), %zu faces in all "
                "levels (ours %.2fx); speed-up %.2fx (topology), %.2fx (positions), %.2fx (patches), %.2fx (all)\n",
                theirs.name.c_str(), theirs.topologyMs, theirs.positionsMs, theirs.patchesMs, theirs.patches,
                theirs.patches == b.patchCount ? "agree" : ("DIFFER: ours " + std::to_string(b.patchCount)).c_str(),
                theirs.totalFaces, double(b.totalFaces) / double(std::max<size_t>(theirs.totalFaces, 1)),
                theirs.topologyMs / std::max(b.topologyMs, 1e-9), theirs.positionsMs / std::max(b.positionsMs, 1e-9),
                theirs.patchesMs / std::max(b.patchesMs, 1e-9), adaptiveSpeedup(b));
  else if (o.vsOpenSubdiv)
    std::printf("vs OpenSubdiv adaptive: not compared (%s)\n", b.comparison.c_str());
}

int runAdaptiveBench(const CommonOptions& o, const PolyMesh& mesh) {
  const size_t budgetFaces = size_t(double(memoryBudgetBytes(o)) / double(kBytesPerUniformFace));
  const size_t viewFaceBudget = size_t(double(memoryBudgetBytes(o)) / kBytesPerAdaptiveFace);
  const std::string scheme = cliSchemeName(o.scheme, o.uniformFirstStep);
  const Model model = makeModel(std::make_shared<const PolyMesh>(mesh), o.input, 1);
  AdaptiveBench b;
  // --vs-opensubdiv: OpenSubdiv's own feature-adaptive path (bench_peer.h), alternated with ours
  // repetition by repetition (ours first on even repetitions, the peer first on odd ones) so that a
  // noisy machine's drift falls on both. It computes Catmull-Clark only: run where this run's
  // surface is the same (cc, or a polar scheme that refines no pole of this mesh), known after
  // our first repetition.
  std::optional<AdaptivePeer> peer;
  if (o.vsOpenSubdiv) peer.emplace(mesh, o.levels);
  bool peerWanted = false;
  auto runPeer = [&] {
    if (peer && peerWanted && peer->unavailable().empty()) peer->run();
  };
  for (int rep = 0; rep < o.reps; ++rep) {
    if (rep % 2 == 1) runPeer();
    timeAdaptiveRefinement(o, mesh, rep, budgetFaces, b);
    if (o.levels >= 1) {
      timeLevelSteps(o, mesh, budgetFaces, b);
      timeViewerStep(o, model, scheme, viewFaceBudget, b);
    }
    if (rep == 0 && peer) {
      if (schemeTraits(o.scheme).polar() && b.polesRefined > 0)
        b.comparison = "different surfaces: " + scheme + " refines " + std::to_string(b.polesRefined) + " pole" +
                       (b.polesRefined == 1 ? "" : "s") + " by its own rules, OpenSubdiv computes Catmull-Clark only";
      else
        peerWanted = true;
    }
    if (rep % 2 == 0) runPeer();
  }
  b.positionsMs = median(b.positions), b.topologyMs = std::max(0.0, median(b.build) - b.positionsMs);
  b.patchesMs = median(b.patches);
  compareWithAdaptivePeer(o, peer, peerWanted, b);
  const std::string json = adaptiveBenchJson(o, scheme, model, b);  // also for text: it refuses a non-finite number
  if (o.json) std::cout << json << "\n";
  else printAdaptiveBench(o, scheme, b);
  if (b.peerFailed) {
    std::fprintf(stderr, "polarview: bench --adaptive --vs-opensubdiv: %s\n", b.comparison.c_str());
    return 2;
  }
  return 0;
}

// What the uniform bench measured (medians over the repetitions) and what it compares against.
struct UniformBench {
  std::vector<double> build, positions, patches;
  size_t outVertices = 0, outFaces = 0, patchCount = 0, polesRefined = 0;
  double trafficBytes = 0, outputBytes = 0, finestBytes = 0, refinePeakRssMb = 0, peakRssMb = 0;
  double topologyMs = 0, positionsMs = 0, coldTopologyMs = 0, triadGbs = 0, positionsGbs = 0;
  std::optional<PeerTiming> peer;
  bool compared = false;
  std::string comparison, peerWhat = "OpenSubdiv Catmull-Clark (a different surface: not compared)";
  double topologySpeedup = 0, positionsSpeedup = 0, speedup = 0;
  bool checked = false, equal = false;  // --vs-opensubdiv: the finest points against the peer's
  double maxDifference = 0;
};

// The repetitions: topology as `refine` builds it (and OpenSubdiv's RefineUniform), no vertex rings
// at the finest level; the patches need them, so patches_ms includes making them. `kept` gets the
// last repetition's refinement (for --vs-opensubdiv's check).
void timeUniformRefinement(const CommonOptions& o, const PolyMesh& mesh, UniformBench& b, std::optional<Refinement>& kept) {
  RefineOptions options{o.scheme, o.levels, o.uniformFirstStep};
  options.finestVertexRings = false;
  for (int rep = 0; rep < o.reps; ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    Refinement refinement(mesh, options, o.input);
    b.build.push_back(millisecondsSince(t0));
    t0 = std::chrono::steady_clock::now();
    refinement.updatePositions(mesh.points);
    b.positions.push_back(millisecondsSince(t0));
    if (rep == 0) {  // the refinement as `refine` has it: its own peak and its arrays
      b.refinePeakRssMb = peakResidentMegabytes();
      b.outputBytes = refinementBytes(refinement);
      b.finestBytes = levelBytes(refinement.finest());
    }
    t0 = std::chrono::steady_clock::now();
    refinement.completeFinestTopology();
    PatchSet set = extractPatches(refinement);
    b.patches.push_back(millisecondsSince(t0));
    b.outVertices = refinement.finest().mesh.points.size();
    b.outFaces = size_t(refinement.finest().mesh.faceCount());
    b.patchCount = set.patches.size();
    b.polesRefined = refinement.level(0).poles.size();
    b.trafficBytes = positionsTrafficBytes(refinement);
    if (o.vsOpenSubdiv && rep + 1 == o.reps) kept.emplace(std::move(refinement));
  }
}

// The peer computes Catmull-Clark only: timings compare only where this run computed the same
// surface (cc, or a scheme that refines no pole of this mesh), checked by equal face counts.
void compareWithPeer(const CommonOptions& o, const std::string& scheme, UniformBench& b) {
  if (!b.peer) {
    b.comparison = "no peer: built without OpenSubdiv (or it refused the mesh)";
  } else if (schemeTraits(o.scheme).polar() && b.polesRefined > 0) {
    b.comparison = "different surfaces: " + scheme + " refines " + std::to_string(b.polesRefined) + " pole" +
                   (b.polesRefined == 1 ? "" : "s") + " by its own rules, OpenSubdiv computes Catmull-Clark only";
  } else if (b.peer->outFaces != b.outFaces) {
    b.comparison = "not compared: Catmull-Clark both, but the face counts differ (" + std::to_string(b.outFaces) + " vs " +
                   std::to_string(b.peer->outFaces) + ")";
    b.peerWhat = "OpenSubdiv Catmull-Clark (face counts differ: not compared)";
  } else {
    b.compared = true;
    b.comparison = "same surface: Catmull-Clark, equal face counts";
    b.peerWhat = "OpenSubdiv Catmull-Clark (the same surface: compared)";
  }
  if (b.compared) {
    b.topologySpeedup = b.peer->topologyMs / std::max(b.topologyMs, 1e-9);
    b.positionsSpeedup = b.peer->positionsMs / std::max(b.positionsMs, 1e-9);
    b.speedup = (b.peer->topologyMs + b.peer->positionsMs) / std::max(b.topologyMs + b.positionsMs, 1e-9);
  }
}

// --vs-opensubdiv: the finest points must equal OpenSubdiv's (double weights) to round-off,
// relative to the mesh's size.
void checkPeerPoints(const CommonOptions& o, const PolyMesh& mesh, UniformBench& b) {
  b.checked = o.vsOpenSubdiv && b.compared && b.peer->checked;
  double size = 1.0;
  if (b.checked) {
    Point lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const Point& p : mesh.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    size = std::max(size, glm::length(hi - lo));
  }
  b.maxDifference = b.checked ? b.peer->maxDifference : 0.0;
  b.equal = b.checked && b.maxDifference <= 1e-12 * size;
}

std::string uniformBenchJson(const CommonOptions& o, const std::string& scheme, const UniformBench& b) {
  JsonWriter w(o.input);
  w.beginObject().field("file", o.input).field("scheme", scheme).field("levels", o.levels);
  w.field("reps", o.reps).field("topology_ms", b.topologyMs).field("positions_ms", b.positionsMs);
  w.field("cold_topology_ms", b.coldTopologyMs).field("cold_over_warm", b.coldTopologyMs / std::max(b.topologyMs, 1e-9));
  w.field("patches_ms", median(b.patches)).field("out_vertices", b.outVertices).field("out_faces", b.outFaces);
  // Memory (docs/performance.md): the refinement's peak against the arrays it holds, all levels.
  w.field("patches", b.patchCount).field("peak_rss_mb", b.refinePeakRssMb).field("peak_rss_with_patches_mb", b.peakRssMb);
  w.field("output_mb", b.outputBytes / (1 << 20))
      .field("peak_over_output", b.refinePeakRssMb * (1 << 20) / std::max(b.outputBytes, 1.0));
  w.field("output_bytes_per_vertex", b.outputBytes / double(std::max<size_t>(b.outVertices, 1)));
  w.field("finest_mb", b.finestBytes / (1 << 20));
  w.field("positions_gbs", b.positionsGbs).field("triad_gbs", b.triadGbs).field("positions_over_triad", b.positionsGbs / b.triadGbs);
  if (b.peer) {
    w.key("peer").beginObject().field("what", b.peerWhat).field("name", b.peer->name).field("topology_ms", b.peer->topologyMs);
    w.field("positions_ms", b.peer->positionsMs).field("out_vertices", b.peer->outVertices).field("out_faces", b.peer->outFaces);
    if (b.peer->peakRssMb > 0 && !o.vsOpenSubdiv) w.field("peak_rss_mb", b.peer->peakRssMb);  // (the check keeps ours alive)
    w.endObject();
  }
  w.field("compared", b.compared).field("comparison", b.comparison);
  if (b.compared)
    w.field("topology_speedup", b.topologySpeedup).field("positions_speedup", b.positionsSpeedup).field("speedup", b.speedup);
  if (o.vsOpenSubdiv) {
    w.key("vs_opensubdiv").beginObject().field("checked", b.checked);
    if (b.checked) w.field("equal", b.equal).field("max_difference", b.maxDifference);
    else w.field("why", b.compared ? "no points from the peer" : b.comparison);
    w.endObject();
  }
  w.endObject();
  return w.str();
}

void printUniformBench(const CommonOptions& o, const std::string& scheme, const UniformBench& b) {
  std::printf("%s %s level %d: topology %.3f ms (cold %.3f ms), positions %.3f ms, patches %.3f ms; %zu vertices, %zu faces, "
              "%zu patches; peak RSS %.1f MB refining (arrays held: %.1f MB, all levels), %.1f MB with the patches\n",
              o.input.c_str(), scheme.c_str(), o.levels, b.topologyMs, b.coldTopologyMs, b.positionsMs, median(b.patches),
              b.outVertices, b.outFaces, b.patchCount, b.refinePeakRssMb, b.outputBytes / (1 << 20), b.peakRssMb);
  std::printf("positions %.2f GB/s, triad %.2f GB/s (%.0f%%)\n", b.positionsGbs, b.triadGbs, 100.0 * b.positionsGbs / b.triadGbs);
  if (b.peer)
    std::printf("%s — %s: topology %.3f ms, positions %.3f ms; %zu vertices, %zu faces\n", b.peer->name.c_str(),
                b.peerWhat.c_str(), b.peer->topologyMs, b.peer->positionsMs, b.peer->outVertices, b.peer->outFaces);
  if (b.compared)
    std::printf("%s: speed-up %.2fx (topology), %.2fx (positions), %.2fx (both)\n", b.comparison.c_str(), b.topologySpeedup,
                b.positionsSpeedup, b.speedup);
  else std::printf("%s\n", b.comparison.c_str());
  if (b.checked) std::printf("vs OpenSubdiv: %s (max difference %.3g)\n", b.equal ? "equal" : "DIFFERENT", b.maxDifference);
  else if (o.vsOpenSubdiv) std::printf("vs OpenSubdiv: not checked (%s)\n", b.compared ? "no points from the peer" : b.comparison.c_str());
}

int runBench(CommonOptions& o) {
  checkFirstStep(o);
  if (o.edit && !o.adaptive) throw UsageError{"--edit needs --adaptive"};
  PolyMesh mesh = loadInput(o.input);
  if (o.adaptive) return runAdaptiveBench(o, mesh);
  checkMemoryBudget(mesh, o);
  UniformBench b;
  std::optional<Refinement> kept;  // --vs-opensubdiv: the last repetition's, for the check
  timeUniformRefinement(o, mesh, b, kept);
  b.peakRssMb = peakResidentMegabytes();  // before the peer and the triad allocate
  clearTablePool();  // the peer and the triad start from the memory the process had before
  // The constructor builds topology and computes positions once: topology = build - positions.
  // Repetitions after the first reuse the previous refinement's tables (table_pool.h), as the
  // viewer does when levels change; the first repetition, on fresh memory, is reported apart.
  b.positionsMs = median(b.positions), b.topologyMs = std::max(0.0, median(b.build) - b.positionsMs);
  b.coldTopologyMs = std::max(0.0, b.build.front() - b.positions.front());
  // The check compares Catmull-Clark points only (a polar scheme's poles are not OpenSubdiv's).
  const bool sameRules = !schemeTraits(o.scheme).polar() || b.polesRefined == 0;
  b.peer = benchPeer(mesh, o.levels, o.reps, kept && sameRules ? &*kept : nullptr);
  kept.reset();
  // The roof for positions_gbs, on as many threads as the point rules use on large meshes.
  b.triadGbs = triadGigabytesPerSecond(size_t(128) << 20, threadsFor(size_t(1) << 30), 5);
  b.positionsGbs = b.trafficBytes / (std::max(b.positionsMs, 1e-9) * 1e6);
  const std::string scheme = cliSchemeName(o.scheme, o.uniformFirstStep);
  compareWithPeer(o, scheme, b);
  checkPeerPoints(o, mesh, b);
  const std::string json = uniformBenchJson(o, scheme, b);  // also when printing text: it refuses a non-finite number
  if (o.json) std::cout << json << "\n";
  else printUniformBench(o, scheme, b);
  if (o.vsOpenSubdiv && !b.peer) {
    std::fprintf(stderr, "polarview: bench --vs-opensubdiv: %s\n", b.comparison.c_str());
    return 2;
  }
  return b.checked && !b.equal ? 1 : 0;
}

// `spectrum --vectors`: a vector's entries as a JSON array (real parts; "<key>_im" adds the
// imaginary parts where they are not round-off), or null where the pair has none.
void writeSpectrumVector(JsonWriter& w, const char* key, const std::vector<Complex>& v) {
  w.key(key);
  if (v.empty()) {
    w.null();
    return;
  }
  double top = 0.0, im = 0.0;
  for (const Complex& x : v) top = std::max(top, std::abs(x)), im = std::max(im, std::abs(x.imag()));
  w.beginArray();
  for (const Complex& x : v) w.value(x.real());
  w.endArray();
  if (im <= 1e-12 * top) return;
  w.key((std::string(key) + "_im").c_str()).beginArray();
  for (const Complex& x : v) w.value(x.imag());
  w.endArray();
}

// `spectrum --scheme c2ps`: no stationary matrix, so Lemma 5 and (30) measured instead
// (c2psEigencoefficientScaling).
int printMeasuredSpectrum(const SpectrumReport& r, bool json) {
  if (json) {
    std::cout << reportJson(measuredSpectrumValue(r)) << "\n";
    return 0;
  }
  const int valence = r.valence;
  std::printf("c2ps, valence %d: no stationary matrix (the valence doubles every step). C2PS applied m times to RTS's\n"
              "eigenvectors v_0..v_5 of valence %d (links 0..5), against Lemma 5 (p_h = lambda_k^m delta_hk) and (30):\n"
              "   m  valence  max|p_h - lambda_k^m delta_hk|  max|T^m v_k - lambda_k^m v_k|  x 8^m   on links 0, 1\n",
              valence, valence);
  for (const C2psScalingStep& s : r.steps)
    std::printf("  %2d  %7d  %30.2e  %29.2e  %6.2f  %12.2e\n", s.m, s.valence, s.coefficientError, s.deviation,
                s.deviation * std::ldexp(1.0, 3 * s.m), s.deviationLinks01);
  return 0;
}

// [SECTION] spectrum

struct SpectrumOptions {
  Scheme scheme = Scheme::RTS;
  bool uniform = false;  // never set: the filter refuses the "-u" names
  int valence = -1, count = 8, steps = -1;
  bool json = false, vectors = false, counted = false;
};

OptionTable spectrumTable(SpectrumOptions& o) {
  return {required(schemeRow(&o.scheme, nullptr, &o.uniform, plainScheme,
                             "the scheme (" + schemeNames(plainScheme, "|") + "); c2ps: Lemma 5 and (30) measured")),
          required(intOption({"--valence"}, "N", "the valence (3..64)", &o.valence, 3, 64)),
          actionOption({"--count"}, "K", "how many eigenvalues (1..1000, default 8)",
                       [&o](const std::string& v) { o.count = parseIntArgument("--count", v, 1, 1000), o.counted = true; }),
          flagOption({"--vectors"}, "and their right and left eigenvectors (not c2ps)", &o.vectors),
          intOption({"--steps"}, "M", "c2ps: steps measured on RTS's eigenvectors (1..12, default 8)", &o.steps, 1, 12),
          jsonRow(&o.json)};
}

// The combinations the table cannot refuse: C2PS has no matrix of its own, RTS and BPS a least valence.
void checkSpectrumOptions(const SpectrumOptions& o, bool c2ps) {
  if (c2ps && (o.vectors || o.counted))
    throw UsageError{"C2PS doubles the valence every step, so it has no stationary matrix and no "
                     "eigenvectors of its own (--scheme rts has them); --scheme c2ps takes --steps M"};
  if (!c2ps && o.steps > 0) throw UsageError{"--steps applies to --scheme c2ps"};
  // C2PS is measured on RTS's eigenvectors, so RTS's valence bound applies.
  if (o.valence < spectrumMinValence(o.scheme))
    throw UsageError{std::string(schemeName(o.scheme)) + " is defined for valence >= " +
                     std::to_string(spectrumMinValence(o.scheme)) + " (" +
                     (c2ps ? "it is measured on RTS's eigenvectors" : "its weights alias below") + ")"};
}

// An eigenvalue whose imaginary part is round-off is printed as real.
double visibleImaginary(const Complex& z) { return shownEigenvalue(z).imag(); }

void writeSpectrumJson(const SpectrumReport& r, int valence, bool vectors) {
  JsonWriter w("spectrum");
  w.beginObject().field("scheme", r.name).field("valence", valence).field("size", r.all.size());
  if (vectors) w.field("order", r.order());
  w.key("eigenvalues").beginArray();
  for (size_t k = 0; k < r.shown; ++k) {
    w.beginObject().field("re", r.all[k].value.real()).field("im", visibleImaginary(r.all[k].value));
    w.field("modulus", std::abs(r.all[k].value));
    if (r.all[k].alpha >= 0) w.field("fourier_block", r.all[k].alpha);
    if (vectors) {
      const EigenPair& p = r.pairs[k];
      w.field("mode", fourierModeName(p.mode));
      writeSpectrumVector(w, "right", p.right);
      writeSpectrumVector(w, "left", p.left);
      writeSpectrumVector(w, "right_profile", p.rightProfile);
      writeSpectrumVector(w, "left_profile", p.leftProfile);
      if (p.right.empty()) w.field("note", "zero or defective eigenvalue: no basis of eigenvectors");
      else w.field("residual", eigenPairResidual(r.matrix, p));
    }
    w.endObject();
  }
  w.endArray().endObject();
  std::cout << w.str() << "\n";
}

// A block profile as "[a, b, ...]" (real parts; complex entries as re+imi; round-off as 0).
std::string profileText(const std::vector<Complex>& v) {
  double top = 0.0;
  for (const Complex& x : v) top = std::max(top, std::abs(x));
  auto clean = [top](double x) { return std::abs(x) <= 1e-12 * top ? 0.0 : x; };
  std::string text = "[";
  char number[64];
  for (size_t i = 0; i < v.size(); ++i) {
    if (clean(v[i].imag()) != 0.0) std::snprintf(number, sizeof number, "%.6g%+.6gi", clean(v[i].real()), v[i].imag());
    else std::snprintf(number, sizeof number, "%.6g", clean(v[i].real()));
    text += (i ? ", " : "") + std::string(number);
  }
  return text + "]";
}

void printSpectrumText(const SpectrumReport& r, int valence, bool vectors) {
  std::printf("%s, valence %d: %zu eigenvalues (%s), the %zu largest by modulus:\n", r.name.c_str(), valence, r.all.size(),
              !r.polar ? "1-ring matrix, by Fourier block" : "matrix (13) on links 0..5, by Fourier block", r.shown);
  for (size_t k = 0; k < r.shown; ++k) {
    const double im = visibleImaginary(r.all[k].value);
    std::printf("  %2zu  %.15g%s", k + 1, r.all[k].value.real(), im != 0.0 ? "" : "\n");
    if (im != 0.0) std::printf(" %+.15gi\n", im);
    if (r.all[k].alpha >= 0) std::printf("      (Fourier block %d)\n", r.all[k].alpha);
    if (!vectors) continue;
    const EigenPair& p = r.pairs[k];
    if (p.right.empty()) {
      std::printf("      no eigenvectors: zero or defective eigenvalue\n");
      continue;
    }
    std::printf("      %s mode, residual %.1e\n      right profile %s\n      left profile  %s\n", fourierModeName(p.mode),
                eigenPairResidual(r.matrix, p), profileText(p.rightProfile).c_str(), profileText(p.leftProfile).c_str());
  }
  if (vectors)
    std::printf("profiles v^, w^ of block alpha: v_ij = v^_i omega^(j alpha), w_ij = w^_i omega^(-j alpha) / n, cos and sin\n"
                "modes their real and imaginary parts (paper (14), (26)); the whole vectors with --json\n");
}

int runSpectrum(SpectrumOptions& o) {
  const bool c2ps = spectrumIsMeasured(o.scheme);
  checkSpectrumOptions(o, c2ps);
  const SpectrumReport r =
      makeSpectrumReport({o.scheme, o.valence, size_t(o.count), o.vectors, o.vectors, o.steps > 0 ? o.steps : 8});
  if (c2ps) return printMeasuredSpectrum(r, o.json);
  if (o.json) writeSpectrumJson(r, o.valence, o.vectors);
  else printSpectrumText(r, o.valence, o.vectors);
  return 0;
}

// [SECTION] shape

struct ShapeOptions {
  std::string output;
  shapes::ShapeRequest shape;  // name, height, valence, links (core/mesh/shape_catalog.h)
};

OptionTable shapeTable(ShapeOptions& o) {
  shapes::ShapeRequest& s = o.shape;
  return {required(positionalOption("NAME", shapes::joinNames(shapes::shapeNames(), "|") +
                                    " (valence20, fingertips: the paper's Figs. 12 and 2c, fixed)", &s.name)),
          actionOption({"--valence"}, "N", "the pole's valence (default 12)",
                       [&s](const std::string& v) { s.valence = parseIntArgument("--valence", v, 3, 1 << 20), s.sized = true; }),
          actionOption({"--links"}, "K", "links around the pole (default 6)",
                       [&s](const std::string& v) { s.links = parseIntArgument("--links", v, 1, 1 << 16), s.sized = true; }),
          textOption({"--height"}, "NAME", "the cap over a height function: " + shapes::joinNames(shapes::heightNames(), "|"),
                     &s.height),
          outputRow(&o.output, "OUT.obj", "the mesh (OBJ)")};
}

int runShape(ShapeOptions& o) {
  PolyMesh mesh;
  try {
    mesh = shapes::makeNamedShape(o.shape);
  } catch (const std::invalid_argument& e) {
    throw UsageError{e.what()};
  }
  saveObj(o.output, mesh);
  return 0;
}

}  // namespace

CommandParser refineCommand() { return makeCommandParser(refineTable, runRefine); }
CommandParser exportCommand() { return makeCommandParser(exportTable, runExport); }
CommandParser continuityCommand() { return makeCommandParser(continuityTable, runContinuity); }
CommandParser convertCommand() { return makeCommandParser(convertTable, runConvert); }
CommandParser infoCommand() { return makeCommandParser(infoTable, runInfo); }
CommandParser poleCommand() { return makeCommandParser(poleTable, runPole); }
CommandParser benchCommand() { return makeCommandParser(benchTable, runBench); }
CommandParser shapeCommand() { return makeCommandParser(shapeTable, runShape); }
CommandParser spectrumCommand() { return makeCommandParser(spectrumTable, runSpectrum); }

}  // namespace polarview::cli
