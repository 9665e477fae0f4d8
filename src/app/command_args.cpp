// Argument parsing shared by the commands (see command_args.h).
#include "app/command_args.h"

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

}  // namespace polarview
