// The one command-line parser of `polarview`: each command declares its options once, as a table of
// rows (names, value, help, where the value goes); parsing, the usage printed on a usage error and
// `polarview help` / `polarview COMMAND --help` all read that table. One wrapper (runGuarded) turns a
// command's exceptions into its exit code.
#pragma once

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace polarview {

using Args = std::vector<std::string>;

// A command-line mistake: printed with the command's usage, exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `text` as an integer in [low, high]; else UsageError "OPTION expects an integer in low..high,
// got 'text'". [O(text)]
int parseIntArgument(const std::string& option, const std::string& text, int low, int high);

// [SECTION] Option tables

// One row of a command's table: an option ("-o", "--output") or, with no names, the command's
// positional argument (one at most).
struct OptionRow {
  std::vector<std::string> names;  // the first is the one usage and messages use; empty: positional
  std::string metavar;             // the value in usage ("OUT.obj"); empty: a flag, which takes none
  std::string help;                // one line of `help`
  bool required = false;           // shown bare in the synopsis; missing: "needs NAME METAVAR"
  std::function<void(const std::string& value)> store;  // the value ("" for a flag); may throw UsageError
};
using OptionTable = std::vector<OptionRow>;

// Row makers, by where the value goes. A repeated option stores again: the last value wins, except
// where `store` appends (listOption).
OptionRow flagOption(std::vector<std::string> names, std::string help, bool* target, bool value = true);
OptionRow textOption(std::vector<std::string> names, std::string metavar, std::string help, std::string* target);
OptionRow intOption(std::vector<std::string> names, std::string metavar, std::string help, int* target, int low,
                    int high);
OptionRow intOption(std::vector<std::string> names, std::string metavar, std::string help, std::optional<int>* target,
                    int low, int high);
// "A,B,C" appended item by item to `target`, each option given adding to it.
OptionRow listOption(std::vector<std::string> names, std::string metavar, std::string help,
                     std::vector<std::string>* target);
OptionRow actionOption(std::vector<std::string> names, std::string metavar, std::string help,
                       std::function<void(const std::string&)> store);
OptionRow positionalOption(std::string metavar, std::string help, std::string* target);
// --supersample 1|2|4 (render, figure): the image drawn that many times larger, then scaled down.
OptionRow supersampleOption(int* target);
// `row` marked required (missing: a usage error naming it).
OptionRow required(OptionRow row);

// `polarview COMMAND --help` (or -h): parseOptions throws it, runGuarded prints the command's help.
struct HelpRequest {};

// Reads `args` by `table`: an unknown option, a missing value, a second positional argument or a
// missing required row is a UsageError; -h / --help throws HelpRequest. [O(args x table)]
void parseOptions(const OptionTable& table, const Args& args);

// "polarview NAME IN.obj -o OUT.obj [--json] ..." from the rows, wrapped at 100 columns. [O(table)]
std::string commandSynopsis(const std::string& name, const OptionTable& table);
// The synopsis, then one line per row: "  -o, --output OUT.obj   help". [O(table)]
std::string commandHelp(const std::string& name, const OptionTable& table);

// A command: its table (made on storage of its own each call) and its body, which reads the storage
// once the table has parsed the arguments into it.
struct CommandParser {
  std::function<OptionTable()> table;              // for usage and help: throwaway storage
  std::function<int(const Args&)> parseAndRun;     // parse by the table, then the body
};
template <class Options>
CommandParser makeCommandParser(OptionTable (*table)(Options&), int (*body)(Options&)) {
  return {[table] {
            static Options unused;  // the rows' targets; never read
            return table(unused);
          },
          [table, body](const Args& args) {
            Options options;
            parseOptions(table(options), args);
            return body(options);
          }};
}

// What a failure other than bad input or usage names: the first argument (the commands that read
// IN.obj first), "<input>" (shape, spectrum), or nothing (the window commands: their messages name
// their files themselves).
enum class FailureSubject { FirstArgument, Placeholder, None };

// Runs `command` on `args` and returns the exit code: 0 ok; a UsageError prints "polarview: NAME:
// message" and the command's help on stderr and gives 2; an InputError (or with FailureSubject::None
// any exception) "polarview: message" and 1; std::bad_alloc "polarview: FILE: out of memory" and 1;
// other exceptions "polarview: FILE: message" and 1. A HelpRequest prints the help on stdout, 0.
int runGuarded(const std::string& name, const CommandParser& command, const Args& args, FailureSubject subject);

// The median of timings (benchmarks report medians: the machines are shared); 0 when empty.
// [O(n log n)]
double median(std::vector<double> values);

}  // namespace polarview
