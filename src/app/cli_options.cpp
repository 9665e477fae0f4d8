// The options and option rows the command-line commands share (cli_options.h).
#include "app/cli_options.h"

#include <cmath>
#include <exception>
#include <iostream>
#include <optional>

#include "core/mesh/obj_io.h"
#include "core/subdiv/parallel_for.h"
#include "pipeline/memory_budget.h"
#include "pipeline/scheme_choice.h"

namespace polarview::cli {

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
size_t memoryBudgetBytes(const SurfaceArgs& o) { return polarview::memoryBudgetBytes(o.memoryBudget); }

// memory_budget.h's refusal of o.levels, or the budget as a face count.
size_t checkMemoryBudget(const PolyMesh& mesh, const SurfaceArgs& o, bool adaptive) {
  return polarview::checkMemoryBudget(mesh, {o.scheme, o.levels, o.uniformFirstStep}, o.input, o.memoryBudget, adaptive);
}

RefineRequest refineRequest(const SurfaceArgs& o, bool uniform) {
  return RefineRequest::withinMemory({o.scheme, o.levels, o.uniformFirstStep},
                                     uniform ? RefinePath::Uniform : RefinePath::FeatureAdaptive, o.memoryBudget);
}

// The name a scheme prints as: "c2ps-u" for C2PS with the uniform first step.
std::string cliSchemeName(Scheme scheme, bool uniformFirstStep) { return schemeVariantName({scheme, uniformFirstStep}); }


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
OptionRow schemeRow(SurfaceArgs& o, const std::string& help, SchemeFilter listed) {
  return schemeRow(&o.scheme, nullptr, &o.uniformScheme, anyScheme,
                   help + " (" + schemeNames(listed, "|") + ")");
}

OptionRow inputRow(std::string& input) { return required(positionalOption("IN.obj", "the input mesh (OBJ)", &input)); }
OptionRow outputRow(std::string* output, const std::string& metavar, const std::string& help) {
  return required(textOption({"-o", "--output"}, metavar, help, output));
}
OptionRow levelsRow(SurfaceArgs& o, std::vector<std::string> names) {
  return required(intOption(std::move(names), "L", "refinement levels (0..64)", &o.levels, 0, 64));
}
// The schemes with the paper's Section-6 variant (the choices with a uniform first step): "c2ps and
// rts", or as names "c2ps-u, rts-u".
namespace {
bool firstStepVariant(const SchemeVariant& v) { return v.uniformFirstStep; }
}  // namespace
std::string firstStepSchemes() {
  std::string names;
  for (const SchemeTraits& s : schemeTable())
    if (s.hasUniformFirstStep) names += (names.empty() ? "" : " and ") + std::string(s.name);
  return names;
}

OptionRow uniformFirstStepRow(SurfaceArgs& o) {
  return flagOption({"--uniform-first-step"}, "the paper's Section-6 first step (" + firstStepSchemes() + " only; = --scheme " +
                    schemeNames(firstStepVariant, ", ") + ")", &o.uniformFlag);
}
OptionRow memoryBudgetRow(SurfaceArgs& o) {
  return actionOption({"--memory-budget"}, "SIZE", "refuse levels whose estimate needs more (2G, 500M, bytes; default 80% of "
                      "the available memory)", [&o](const std::string& text) { o.memoryBudget = parseByteSize("--memory-budget", text); });
}
OptionRow threadsRow() {
  static int threads = 0;
  OptionRow row = intOption({"--threads"}, "N", "the most threads a pass may use (default: POLARVIEW_THREADS, else the cores, at most "
                            "8; the output is the same)", &threads, 1, 256);
  row.store = [parse = row.store](const std::string& text) {
    parse(text);
    setThreadLimit(unsigned(threads));
  };
  return row;
}
OptionRow jsonRow(bool* json) { return flagOption({"--json"}, "print JSON", json); }

// After parsing: --scheme c2ps-u and --uniform-first-step are one choice. The Section-6 variant
// changes the first step's 2-link of C2PS and RTS only; elsewhere the flag would do nothing.
void checkFirstStep(SurfaceArgs& o) {
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

}  // namespace polarview::cli
