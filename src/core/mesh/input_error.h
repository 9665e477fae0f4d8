// InputError: the one exception type for bad user data (files, meshes, levels).
// Its message is the one-line "FILE:LINE: what is wrong" the CLI prints after "polarview: ".
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace polarview {

class InputError : public std::runtime_error {
 public:
  // line <= 0 means "no line" (the message is then "FILE: what"). 64-bit: files may have more
  // than 2^31 lines.
  InputError(const std::string& file, int64_t line, const std::string& what)
      : std::runtime_error(format(file, line, what)), file_(file), line_(line) {}
  const std::string& file() const { return file_; }
  int64_t line() const { return line_; }

 private:
  static std::string format(const std::string& file, int64_t line, const std::string& what) {
    std::string s = file.empty() ? std::string("<input>") : file;
    if (line > 0) s += ":" + std::to_string(line);
    return s + ": " + what;
  }
  std::string file_;
  int64_t line_;
};

}  // namespace polarview
