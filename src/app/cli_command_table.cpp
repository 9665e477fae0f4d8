// The command line's table of commands (cli_command_table.h).
#include "app/cli_command_table.h"

#include <string>

#include "app/bench_command.h"
#include "app/cli_commands.h"
#include "app/measure_command.h"
#include "pipeline/scheme_choice.h"
#ifdef POLARVIEW_HAVE_VIEWER
#include "app/figure_command.h"
#include "app/viewer_commands.h"
#define POLARVIEW_WINDOW_COMMAND(make) make
#else
#define POLARVIEW_WINDOW_COMMAND(make) nullptr
#endif

namespace polarview {

namespace {

const std::vector<CliCommand> kCommands = {
    {"view", "open the viewer (with --frames: a benchmark)", POLARVIEW_WINDOW_COMMAND(viewCommand), true,
     FailureSubject::None},
    {"render", "1 to 4 views of a model in one PNG, without a window", POLARVIEW_WINDOW_COMMAND(renderCommand), true,
     FailureSubject::None},
    {"figure", "the paper's figures as DIR/figNN.png", POLARVIEW_WINDOW_COMMAND(figureCommand), true,
     FailureSubject::None},
    {"refine", "refine uniformly and write the finest level (OBJ)", cli::refineCommand, false,
     FailureSubject::FirstArgument},
    {"export", "the limit surface as a file: Bezier patches, CAD B-splines or a tessellation", cli::exportCommand, false,
     FailureSubject::FirstArgument},
    {"continuity", "position, normal and curvature jumps across the limit surface's seams", cli::continuityCommand, false,
     FailureSubject::FirstArgument},
    {"convert", "extraordinary vertices into poles (paper Fig. 14), n-gons into triangle fans", cli::convertCommand, false,
     FailureSubject::FirstArgument},
    {"measure", "area, enclosed volume, centroid and inertia of the limit surface", cli::measureCommand, false,
     FailureSubject::FirstArgument},
    {"info", "faces, boundaries, poles and extraordinary vertices of a mesh", cli::infoCommand, false,
     FailureSubject::FirstArgument},
    {"pole", "limit, normal and curvature at each pole, ring by ring", cli::poleCommand, false,
     FailureSubject::FirstArgument},
    {"bench", "time refinement and patches (against OpenSubdiv where it computes the same)", cli::benchCommand, false,
     FailureSubject::FirstArgument},
    {"shape", "write one of the models polarview ships", cli::shapeCommand, false, FailureSubject::Placeholder},
    {"spectrum", "the leading eigenvalues of a scheme's subdivision matrix", cli::spectrumCommand, false,
     FailureSubject::Placeholder},
};

// The scheme names every --scheme takes, from the scheme-choice table.
std::string schemeNote() {
  const auto uniform = [](SchemeChoice c) { return schemeChoiceVariant(c).uniformFirstStep; };
  const auto plain = [&](SchemeChoice c) {
    if (uniform(c)) return false;
    const SchemeVariant v = schemeChoiceVariant(c);
    return schemeTraits(v.scheme).hasUniformFirstStep;
  };
  return "schemes S: " + schemeChoiceNames(", ") + ";\n  " + schemeChoiceNames(", ", uniform) + " are " +
         schemeChoiceNames(" and ", plain) + " with the uniform first step of the paper's Section 6\n"
         "  (also written --scheme S --uniform-first-step, which no other scheme takes)\n";
}

}  // namespace

const std::vector<CliCommand>& cliCommands() { return kCommands; }

const CliCommand* findCommand(const std::string& name) {
  for (const CliCommand& c : kCommands)
    if (name == c.name) return &c;
  return nullptr;
}

// `polarview help`: the commands and their summaries, then every command's options.
std::string helpText() {
  std::string text = "usage: polarview [COMMAND [ARGUMENTS]]   (no command: the viewer on the built-in model)\n\ncommands:\n";
  for (const CliCommand& c : kCommands)
    text += "  " + std::string(c.name) + std::string(12 - std::string(c.name).size(), ' ') + c.summary +
            (c.parser ? "" : " (not in this build)") + "\n";
  text += "  help        this text; `polarview help COMMAND` or `polarview COMMAND --help`: one command's;\n"
          "              `polarview help keys`: the viewer's commands (keys, `view --do` ids)\n";
  for (const CliCommand& c : kCommands)
    if (c.parser) text += "\n" + commandHelp(c.name, c.parser().table());
  return text + "\n" + schemeNote();
}


}  // namespace polarview
