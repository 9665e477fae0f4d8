// POLARVIEW_CHECK_EQ(a, b): an internal invariant that holds in every build type (assert is gone
// in Release); on failure a std::logic_error naming the place and both values.
#pragma once

#include <sstream>
#include <stdexcept>

namespace polarview::detail {

template <class A, class B>
void checkEqual(const A& a, const B& b, const char* textA, const char* textB, const char* file, int line) {
  if (a == b) return;
  std::ostringstream what;
  what << file << ":" << line << ": internal check " << textA << " == " << textB << " failed (" << a << " vs " << b << ")";
  throw std::logic_error(what.str());
}

}  // namespace polarview::detail

#define POLARVIEW_CHECK_EQ(a, b) ::polarview::detail::checkEqual((a), (b), #a, #b, __FILE__, __LINE__)
