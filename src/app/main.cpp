// polarview: the viewer when run bare, otherwise one of the commands of the command table
// (cli_command_table.h), whose option tables make every usage text and `polarview help`.
#include <iostream>
#include <string>
#include <vector>

#include "app/cli_command_table.h"
#include "app/command_args.h"
#include "session/command_table.h"

using namespace polarview;

int main(int argc, char** argv) {
  const std::string name = argc > 1 ? argv[1] : "";
  const Args args(argv + (argc > 1 ? 2 : argc), argv + argc);
  if (name == "-h" || name == "--help" || name == "help") {
    const CliCommand* about = args.empty() ? nullptr : findCommand(args[0]);
    if (!args.empty() && args[0] == "keys") std::cout << commandListText();
    else if (about && about->parser) std::cout << "usage: " << commandHelp(about->name, about->parser().table());
    else std::cout << helpText();
    return 0;
  }
  const CliCommand* command = findCommand(name.empty() ? "view" : name);
  if (!command) {
    std::cerr << "polarview: unknown command '" << name << "'\n" << helpText();
    return 2;
  }
  if (!command->parser) {
    std::cerr << "polarview: built without the viewer (POLARVIEW_BUILD_VIEWER=OFF)\n";
    return 2;
  }
  return runGuarded(command->name, command->parser(), args, command->failures);
}
