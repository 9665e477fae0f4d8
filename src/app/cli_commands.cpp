#include "app/cli_commands.h"
#include "app/cli_options.h"
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
#include "pipeline/model.h"
#include "pipeline/surface_key.h"
#include "pipeline/level_limits.h"
#include "pipeline/surface_build.h"
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

// Each command's options: the storage its option table writes into.
struct RefineArgs : SurfaceArgs {
  std::string output;
};
struct ExportArgs : SurfaceArgs {
  std::string output;
  std::string format, units = "mm";  // --format NAME --units UNIT
  int samples = 8;                   // --samples N
  bool uniform = false;              // --uniform
};
struct ContinuityArgs : SurfaceArgs {
  int samples = 8;  // --samples K
  bool json = false;
};
struct ConvertArgs {
  std::string input, output;
  bool evToPolar = false, pentagons = false;  // --ev-to-polar [--pentagons]
  bool ngonToFan = false;                     // --ngon-to-fan
};
struct InfoArgs {
  std::string input;
  bool json = false;
};
struct PoleArgs : SurfaceArgs {
  int rings = 0;  // --rings M
  bool json = false;
};


// [SECTION] refine, export, convert

OptionTable refineTable(RefineArgs& o) {
  return {inputRow(o.input), outputRow(&o.output, "OUT.obj", "the finest level's mesh (OBJ)"), schemeRow(o),
          levelsRow(o, {"--levels", "--level"}), uniformFirstStepRow(o), memoryBudgetRow(o), threadsRow()};
}

int runRefine(RefineArgs& o) {
  checkFirstStep(o);
  PolyMesh mesh = loadInput(o.input);
  saveObj(o.output, makeRefinedMesh(mesh, o.input, refineRequest(o, true)), o.input);
  return 0;
}

OptionTable exportTable(ExportArgs& o) {
  return {inputRow(o.input),
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
          memoryBudgetRow(o), threadsRow()};
}

// The row of surface_export.h's table that writes o.output: --format, else the extension.
const ExportFormat& chosenExportFormat(const ExportArgs& o) {
  if (!o.format.empty()) {
    if (const ExportFormat* format = exportFormatNamed(o.format)) return *format;
    throw UsageError{"--format expects one of " + exportFormatNames() + ", got '" + o.format + "'"};
  }
  if (const ExportFormat* format = exportFormatForPath(o.output)) return *format;
  throw UsageError{"cannot tell the format of '" + o.output + "': name it " + exportFormatExtensions() +
                   " or give --format"};
}

LengthUnit chosenLengthUnit(const ExportArgs& o) {
  for (const LengthUnitInfo& unit : lengthUnits())
    if (o.units == unit.name) return unit.unit;
  std::string names;
  for (const LengthUnitInfo& unit : lengthUnits()) names += std::string(names.empty() ? "" : ", ") + unit.name;
  throw UsageError{"--units expects one of " + names + ", got '" + o.units + "'"};
}

int runExport(ExportArgs& o) {
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
  const PatchSet set = makePatchSet(mesh, o.input, refineRequest(o, o.uniform));
  const std::string summary = exportSummary(writeSurfaceFile(o.output, set, format, settings));
  std::printf("%s: %s; %s refinement\n", o.output.c_str(), summary.c_str(), o.uniform ? "uniform" : "feature-adaptive");
  return 0;
}

// [SECTION] continuity

OptionTable continuityTable(ContinuityArgs& o) {
  return {inputRow(o.input),
          required(schemeRow(o, "the scheme")),
          levelsRow(o, {"--level", "--levels"}),
          intOption({"--samples"}, "K", "points compared along each patch side (default 8)", &o.samples, 1, 64),
          uniformFirstStepRow(o),
          memoryBudgetRow(o), threadsRow(),
          jsonRow(&o.json)};
}

// The report as JSON (docs/commands.md, continuity); it refuses a non-finite number.
std::string continuityJson(const ContinuityArgs& o, const ContinuityReport& report) {
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

void printContinuity(const ContinuityArgs& o, const ContinuityReport& report) {
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

int runContinuity(ContinuityArgs& o) {
  checkFirstStep(o);
  PolyMesh mesh = loadInput(o.input);
  requireCurvatureExtent(mesh, o.input);
  const PatchSet set = makePatchSet(mesh, o.input, refineRequest(o, false));  // the patches `export` writes
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
  bool ConvertArgs::*chosen;
  void (*run)(const ConvertArgs& o, const PolyMesh& mesh);
};

void runEvToPolar(const ConvertArgs& o, const PolyMesh& mesh) {
  const PolarConversion conversion = convertExtraordinaryToPolar(mesh, o.pentagons, o.input);
  saveObj(o.output, conversion.mesh, o.input);
  std::printf("%s: %zu extraordinary vertices turned into %s polar configurations (Fig. 14(%s))", o.output.c_str(),
              conversion.converted.size(), o.pentagons ? "n-valent" : "2n-valent", o.pentagons ? "c" : "a");
  if (!conversion.skipped.empty())
    std::printf("; %zu skipped: their regions touch a converted one (first: vertex %d)", conversion.skipped.size(),
                conversion.skipped.front());
  std::printf("\n");
}

void runNgonToFan(const ConvertArgs& o, const PolyMesh& mesh) {
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
    {"--ev-to-polar", "extraordinary vertices into polar configurations (paper Fig. 14)", &ConvertArgs::evToPolar,
     runEvToPolar},
    {"--ngon-to-fan", "faces of 5 or more sides into triangle fans around their centroids (Blender's cap fill; "
                      "a cylinder's caps become poles)",
     &ConvertArgs::ngonToFan, runNgonToFan},
};

OptionTable convertTable(ConvertArgs& o) {
  OptionTable table{inputRow(o.input), outputRow(&o.output, "OUT.obj", "the converted mesh (OBJ)")};
  for (const MeshConversion& conversion : kMeshConversions)
    table.push_back(flagOption({conversion.flag}, conversion.help, &(o.*conversion.chosen)));
  table.push_back(flagOption({"--pentagons"}, "with --ev-to-polar: n-valent poles ringed by pentagons (Fig. 14c; default "
                                              "2n-valent, 14a)",
                             &o.pentagons));
  return table;
}

int runConvert(ConvertArgs& o) {
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

OptionTable infoTable(InfoArgs& o) { return {inputRow(o.input), jsonRow(&o.json)}; }

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

int runInfo(InfoArgs& o) {
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

OptionTable poleTable(PoleArgs& o) {
  // Any scheme parses (--uniform-first-step is judged first); runPole refuses a scheme without poles.
  return {inputRow(o.input), schemeRow(o, "the polar scheme, default c2ps", polarScheme),
          uniformFirstStepRow(o),
          intOption({"--rings"}, "M", "curvature over spline rings 1..M (1..20)", &o.rings, 1, 20), jsonRow(&o.json)};
}

// One pole's text line (and with --rings its ring table). Why K and H are missing: no tangent
// plane (any scheme), or BPS's expansion, which stops at the tangent plane; where K depends on the
// direction (RTS), over which range on the last ring.
void printPole(const PoleArgs& o, const RefinedLevel& level, size_t k, const PoleDifferential& d,
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

int runPole(PoleArgs& o) {
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
CommandParser shapeCommand() { return makeCommandParser(shapeTable, runShape); }
CommandParser spectrumCommand() { return makeCommandParser(spectrumTable, runSpectrum); }

}  // namespace polarview::cli
