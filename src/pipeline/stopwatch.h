// The viewer's and the commands' timings: milliseconds on the steady clock since `start`.
#pragma once

#include <chrono>

namespace polarview {

inline double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace polarview
