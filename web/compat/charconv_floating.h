// Floating-point std::from_chars / std::to_chars for emscripten 3.1.6's libc++ (LLVM 14), which has
// only the integer ones: without these, a double argument picks the deleted bool overload. The web
// build force-includes this header into the core's sources (web/CMakeLists.txt) so that src/ stays
// as the desktop compiles it. Semantics kept where the core relies on them: no leading whitespace
// or '+', no hexadecimal, result_out_of_range on overflow and underflow, shortest round-trip text.
#pragma once

#ifdef __EMSCRIPTEN__
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <system_error>

namespace std {

inline from_chars_result from_chars(const char* first, const char* last, double& value,
                                    chars_format = chars_format::general) {
  if (first == last || *first == '+' || *first == ' ' || *first == '\t' || *first == '\n' || *first == '\r')
    return {first, errc::invalid_argument};
  const std::string text(first, last);
  if (text.find_first_of("xX") != std::string::npos) {
    // from_chars reads "0x1p3" as 0 followed by text: keep that, never strtod's hexadecimal.
    if (text[0] == '0' || ((text[0] == '-') && text.size() > 1 && text[1] == '0')) {
      value = text[0] == '-' ? -0.0 : 0.0;
      return {first + (text[0] == '-' ? 2 : 1), errc()};
    }
  }
  char* end = nullptr;
  errno = 0;
  const double parsed = std::strtod(text.c_str(), &end);
  if (end == text.c_str()) return {first, errc::invalid_argument};
  const char* ptr = first + (end - text.c_str());
  if (errno == ERANGE) return {ptr, errc::result_out_of_range};
  value = parsed;
  return {ptr, errc()};
}

inline to_chars_result to_chars(char* first, char* last, double value, chars_format format, int precision) {
  const char* spec = format == chars_format::scientific ? "%.*e" : format == chars_format::fixed ? "%.*f" : "%.*g";
  const int n = std::snprintf(first, size_t(last - first), spec, precision, value);
  if (n < 0 || n >= last - first) return {last, errc::value_too_large};
  return {first + n, errc()};
}

// Shortest text that reads back to the same double.
inline to_chars_result to_chars(char* first, char* last, double value) {
  char buffer[64];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
    if (std::strtod(buffer, nullptr) == value || precision == 17) break;
  }
  const size_t n = std::strlen(buffer);
  if (n > size_t(last - first)) return {last, errc::value_too_large};
  std::memcpy(first, buffer, n);
  return {first + n, errc()};
}

}  // namespace std
#endif
