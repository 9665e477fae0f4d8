// The command-line option tables (app/command_args.h): parsing by a table, the usage generated from
// it, and the windowless commands' own tables.
#include <doctest/doctest.h>

#include <optional>
#include <string>
#include <vector>

#include "app/cli_command_table.h"
#include "app/cli_commands.h"
#include "app/command_args.h"

using namespace polarview;

namespace {

// A command's storage and its table, as a command declares them.
struct Sample {
  std::string input, output;
  bool json = false, quiet = true;
  int level = -1;
  std::optional<int> count;
  std::vector<std::string> commands;
};

OptionTable sampleTable(Sample& s) {
  return {required(positionalOption("IN.obj", "the input", &s.input)),
          required(textOption({"-o", "--output"}, "OUT.obj", "the output", &s.output)),
          flagOption({"--json"}, "print JSON", &s.json),
          flagOption({"--loud"}, "say more", &s.quiet, false),
          intOption({"--level", "--levels"}, "L", "the level (0..9)", &s.level, 0, 9),
          intOption({"--count"}, "K", "how many (1..5)", &s.count, 1, 5),
          listOption({"--do"}, "CMD[,CMD...]", "commands", &s.commands)};
}

Sample parse(const Args& args) {
  Sample s;
  parseOptions(sampleTable(s), args);
  return s;
}

std::string usageErrorOf(const Args& args) {
  try {
    parse(args);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("option table: values go where their rows say, aliases included") {
  const Sample s = parse({"in.obj", "--levels", "3", "-o", "out.obj", "--json", "--loud", "--count", "5"});
  CHECK(s.input == "in.obj");
  CHECK(s.output == "out.obj");
  CHECK(s.json);
  CHECK_FALSE(s.quiet);
  CHECK(s.level == 3);
  CHECK(s.count == 5);
  CHECK(parse({"--output", "x", "in.obj"}).output == "x");  // the positional argument anywhere
}

TEST_CASE("option table: an unknown option, a missing value or a second positional is a usage error") {
  CHECK(usageErrorOf({"in.obj", "-o", "x", "--frobnicate"}) == "unknown option '--frobnicate'");
  CHECK(usageErrorOf({"in.obj", "-o"}) == "-o needs a value");
  CHECK(usageErrorOf({"in.obj", "-o", "x", "--level"}) == "--level needs a value");
  CHECK(usageErrorOf({"in.obj", "other.obj", "-o", "x"}) == "unexpected argument 'other.obj'");
  // A value that looks like an option is still the value.
  CHECK(parse({"in.obj", "-o", "--json"}).output == "--json");
}

TEST_CASE("option table: a missing required row names itself") {
  CHECK(usageErrorOf({"in.obj"}) == "needs -o OUT.obj");
  CHECK(usageErrorOf({"-o", "x"}) == "needs IN.obj");
}

TEST_CASE("option table: integers are checked against their range, whole") {
  CHECK(usageErrorOf({"in.obj", "-o", "x", "--level", "10"}) == "--level expects an integer in 0..9, got '10'");
  CHECK(usageErrorOf({"in.obj", "-o", "x", "--level", "-1"}) == "--level expects an integer in 0..9, got '-1'");
  CHECK(usageErrorOf({"in.obj", "-o", "x", "--levels", "2x"}) == "--level expects an integer in 0..9, got '2x'");
  CHECK(usageErrorOf({"in.obj", "-o", "x", "--count", "0"}) == "--count expects an integer in 1..5, got '0'");
  for (int level = 0; level <= 9; ++level) CHECK(parse({"in.obj", "-o", "x", "--level", std::to_string(level)}).level == level);
}

TEST_CASE("option table: a repeated option stores again; a list option appends") {
  const Sample s = parse({"in.obj", "-o", "a", "-o", "b", "--level", "1", "--level", "2", "--do", "x,y", "--do", "z"});
  CHECK(s.output == "b");
  CHECK(s.level == 2);
  CHECK(s.commands == std::vector<std::string>{"x", "y", "z"});
}

TEST_CASE("option table: -h and --help ask for the help, wherever they stand") {
  CHECK_THROWS_AS(parse({"--help"}), HelpRequest);
  CHECK_THROWS_AS(parse({"in.obj", "-h"}), HelpRequest);
}

TEST_CASE("option table: the generated usage lists every row, required ones bare") {
  Sample s;
  const OptionTable table = sampleTable(s);
  const std::string help = commandHelp("sample", table);
  const std::string synopsis = commandSynopsis("sample", table);
  CHECK(synopsis.rfind("polarview sample IN.obj -o OUT.obj [--json]", 0) == 0);
  for (const OptionRow& row : table) {
    CHECK_MESSAGE(help.find(row.help) != std::string::npos, row.help);
    for (const std::string& name : row.names) CHECK_MESSAGE(help.find(name) != std::string::npos, name);
    if (!row.names.empty() && !row.required)
      CHECK_MESSAGE(synopsis.find("[" + row.names.front()) != std::string::npos, row.names.front());
  }
}

TEST_CASE("commands: every windowless command's help names each of its rows, and refuses an unknown option") {
  int windowless = 0;
  for (const CliCommand& row : cliCommands()) {
    CHECK_MESSAGE(bool(row.parser) != row.needsViewer, row.name);  // this test build has no viewer
    if (!row.parser) continue;
    ++windowless;
    const CommandParser command = row.parser();
    const OptionTable table = command.table();
    const std::string help = commandHelp("c", table);
    for (const OptionRow& row : table) {
      for (const std::string& name : row.names) CHECK_MESSAGE(help.find(name) != std::string::npos, name);
      CHECK_MESSAGE(help.find(row.metavar) != std::string::npos, row.metavar);
    }
    CHECK_THROWS_AS(command.parseAndRun({"--frobnicate"}), UsageError);
    CHECK_THROWS_AS(command.parseAndRun({"--help"}), HelpRequest);
  }
  CHECK(windowless >= 9);
}

TEST_CASE("commands: --scheme lists come from the scheme table, and a command takes only its subset") {
  const std::string pole = commandHelp("pole", cli::poleCommand().table());
  CHECK(pole.find("c2ps|c2ps-u|rts|rts-u|bps") != std::string::npos);
  const std::string spectrum = commandHelp("spectrum", cli::spectrumCommand().table());
  CHECK(spectrum.find("(cc|c2ps|rts|bps)") != std::string::npos);
  CHECK_THROWS_WITH_AS(cli::spectrumCommand().parseAndRun({"--scheme", "rts-u", "--valence", "6"}),
                       "--scheme rts-u: this command takes cc, c2ps, rts, bps", UsageError);
}
