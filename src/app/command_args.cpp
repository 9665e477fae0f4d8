// Argument parsing shared by the commands (see command_args.h).
#include "app/command_args.h"

#include <algorithm>

namespace polarview {

int parseIntArgument(const std::string& option, const std::string& text, int low, int high) {
  size_t used = 0;
  long value = 0;
  try {
    value = std::stol(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || value < low || value > high)
    throw UsageError(option + " expects an integer in " + std::to_string(low) + ".." + std::to_string(high) + ", got '" +
                     text + "'");
  return int(value);
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace polarview
