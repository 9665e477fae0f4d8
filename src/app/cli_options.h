// What the command-line commands share: the options of a command that refines IN.obj (SurfaceArgs)
// and the option rows that fill them (command_args.h), the scheme filters and names, the memory
// budget and the input's loading. Each command has its own options struct (cli_commands.cpp,
// bench_command.cpp), made of SurfaceArgs and what is its own.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "app/command_args.h"
#include "core/mesh/poly_mesh.h"
#include "core/subdiv/scheme.h"
#include "pipeline/patch_export.h"

namespace polarview::cli {

// The options of a command that refines IN.obj: the storage the shared rows below write into.
struct SurfaceArgs {
  std::string input;
  Scheme scheme = Scheme::C2PS;
  bool uniformScheme = false;     // --scheme c2ps-u or rts-u
  bool uniformFlag = false;       // --uniform-first-step
  bool uniformFirstStep = false;  // either of the two (checkFirstStep)
  int levels = -1;
  size_t memoryBudget = 0;  // --memory-budget SIZE in bytes (0: from the available memory)
};

// "2G", "500M", "64k", "123456" (bytes; binary units, case-insensitive, optional trailing B).
size_t parseByteSize(const std::string& flag, const std::string& text);
// The memory a refinement may take: --memory-budget, else memory_budget.h's default.
size_t memoryBudgetBytes(const SurfaceArgs& o);
// memory_budget.h's refusal of o.levels, or the budget as a face count.
size_t checkMemoryBudget(const PolyMesh& mesh, const SurfaceArgs& o, bool adaptive = false);
// What o asks to be refined (pipeline/patch_export.h), uniformly or feature-adaptively.
RefineRequest refineRequest(const SurfaceArgs& o, bool uniform);
// The name a scheme prints as: "c2ps-u" for C2PS with the uniform first step.
std::string cliSchemeName(Scheme scheme, bool uniformFirstStep);

// Which scheme variants a command takes (every one, or those with a property of the scheme table).
using SchemeFilter = bool (*)(const SchemeVariant&);
bool anyScheme(const SchemeVariant&);
bool polarScheme(const SchemeVariant& v);
// spectrum: a scheme-table row as it is (the Section-6 first step is no subdivision matrix of its own).
bool plainScheme(const SchemeVariant& v);
// The names `accepts` takes, from the scheme-choice table: "cc|c2ps|c2ps-u|rts|rts-u|bps".
std::string schemeNames(SchemeFilter accepts, const std::string& separator);

// --scheme S: the scheme table's names, "-u" for the paper's Section-6 variant (the same as
// --uniform-first-step); a name `accepts` refuses is a usage error that lists the ones it takes.
// `help` names them (schemeNames).
OptionRow schemeRow(Scheme* scheme, bool* given, bool* uniform, SchemeFilter accepts, const std::string& help);
// --scheme S for the commands that read IN.obj; `listed`: the schemes the help names.
OptionRow schemeRow(SurfaceArgs& o, const std::string& help = "the scheme, default c2ps", SchemeFilter listed = anyScheme);
OptionRow inputRow(std::string& input);
OptionRow outputRow(std::string* output, const std::string& metavar, const std::string& help);
OptionRow levelsRow(SurfaceArgs& o, std::vector<std::string> names);
// The schemes with the paper's Section-6 variant: "c2ps and rts".
std::string firstStepSchemes();
OptionRow uniformFirstStepRow(SurfaceArgs& o);
OptionRow memoryBudgetRow(SurfaceArgs& o);
// --threads N: the process's thread limit (parallel_for.h setThreadLimit), set as it is parsed.
OptionRow threadsRow();
OptionRow jsonRow(bool* json);

// After parsing: --scheme c2ps-u and --uniform-first-step are one choice. The Section-6 variant
// changes the first step's 2-link of C2PS and RTS only; elsewhere the flag would do nothing.
void checkFirstStep(SurfaceArgs& o);
// Loads the OBJ and prints its warnings on stderr.
PolyMesh loadInput(const std::string& path);

}  // namespace polarview::cli
