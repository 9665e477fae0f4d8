// The command line's commands, one table: each row's name, summary, option table and body, whether
// it opens a window (left out of a build without the viewer) and what its failures name. main.cpp
// runs them; `polarview help` and every command's usage are generated from it; tests walk it.
// A new command is its parser (cli_commands.h or a file of its own) and a row here.
#pragma once

#include <string>
#include <vector>

#include "app/command_args.h"

namespace polarview {

// One command: its name, what it does (for `help`), its option table and body, whether it opens
// a window (such commands are left out of a build without the viewer), and what its failures name.
struct CliCommand {
  const char* name;
  const char* summary;
  CommandParser (*parser)();  // null: a window command in a build without the viewer
  bool needsViewer;
  FailureSubject failures;
};

const std::vector<CliCommand>& cliCommands();
// The row named `name`, or nullptr.
const CliCommand* findCommand(const std::string& name);
// `polarview help`: the commands and their summaries, then every command's options.
std::string helpText();

}  // namespace polarview
