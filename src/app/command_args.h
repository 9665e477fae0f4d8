// What the commands share when reading their arguments (cli_commands, viewer_commands, figures).
#pragma once

#include <iostream>
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

// Runs a command's body: a UsageError prints "polarview: NAME: message" and the usage and gives 2,
// any other exception "polarview: message" and 1; `finally` runs either way (e.g. glfwTerminate).
template <class Body, class Finally>
int runCommand(const char* name, const char* usage, Body&& body, Finally&& finally) {
  int code = 0;
  try {
    code = body();
  } catch (const UsageError& e) {
    std::cerr << "polarview: " << name << ": " << e.what() << "\n" << usage;
    code = 2;
  } catch (const std::exception& e) {
    std::cerr << "polarview: " << e.what() << "\n";
    code = 1;
  }
  finally();
  return code;
}

// The median of timings (benchmarks report medians: the machines are shared); 0 when empty.
// [O(n log n)]
double median(std::vector<double> values);

}  // namespace polarview
