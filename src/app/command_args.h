// What the commands share when reading their arguments (cli_commands, viewer_commands, figures).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace polarview {

// A command-line mistake: printed with the command's usage, exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `text` as an integer in [low, high]; else UsageError "OPTION expects an integer in low..high,
// got 'text'". [O(text)]
int parseIntArgument(const std::string& option, const std::string& text, int low, int high);

// The median of timings (benchmarks report medians: the machines are shared); 0 when empty.
// [O(n log n)]
double median(std::vector<double> values);

}  // namespace polarview
