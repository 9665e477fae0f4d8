// polarview: the viewer when run bare, otherwise one of the commands of the command table
// (cli_command_table.h), whose option tables make every usage text and `polarview help`.
#include <malloc.h>

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "app/cli_command_table.h"
#include "app/command_args.h"
#include "core/subdiv/parallel_for.h"
#include "session/command_table.h"

using namespace polarview;

// POLARVIEW_THREADS=N (1..256): the thread limit (parallel_for.h) unless --threads says otherwise.
// Returns false, with the one-line error printed, for a malformed value.
bool applyThreadsVariable() {
  const char* text = std::getenv("POLARVIEW_THREADS");
  if (!text || !*text) return true;
  char* end = nullptr;
  const long threads = std::strtol(text, &end, 10);
  if (*end != '\0' || threads < 1 || threads > 256) {
    std::cerr << "polarview: POLARVIEW_THREADS expects a whole number of threads in 1..256, got '" << text << "'\n";
    return false;
  }
  setThreadLimit(unsigned(threads));
  return true;
}

// Freed arrays stay in the process for the next build (a repetition, a level step, an edit):
// glibc would hand blocks over its threshold back to the system, and each fresh page then costs a
// fault on first touch, which measured as a third of a warm rebuild's time on these machines
// (docs/performance.md, "First touch"). Blocks up to 256 MB come from the heap, and up to 512 MB
// of free heap is kept.
void keepFreedMemory() {
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  mallopt(M_TOP_PAD, 16 << 20);
}

int main(int argc, char** argv) {
  keepFreedMemory();
  if (!applyThreadsVariable()) return 2;
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
