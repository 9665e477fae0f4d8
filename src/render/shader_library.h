// ShaderLibrary: loads GLSL files from the shader directory, resolves #include "common/x.glsl",
// compiles and links named programs, and reports errors as FILE:LINE (mapped through includes).
// A failed (re)load keeps the previous program of that name.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace polarview {

// One program: its stage files (relative to the shader dir; empty = stage absent) and #defines.
struct ProgramSpec {
  std::string vertex, tessControl, tessEval, geometry, fragment;
  std::vector<std::string> defines;             // each becomes "#define X" after #version
  std::vector<std::string> feedbackVaryings;    // transform feedback outputs (interleaved)
};

class ShaderLibrary {
 public:
  // Directory: $POLARVIEW_SHADER_DIR if set, else the compile definition POLARVIEW_SHADER_DIR.
  ShaderLibrary();
  explicit ShaderLibrary(std::string directory);
  ~ShaderLibrary();
  ShaderLibrary(const ShaderLibrary&) = delete;
  ShaderLibrary& operator=(const ShaderLibrary&) = delete;

  // Builds (or rebuilds) program `name`. On failure returns false, appends the log to *error and
  // keeps the previous program of that name (if any). Needs a current GL context.
  bool build(const std::string& name, const ProgramSpec& spec, std::string* error);
  // Rebuilds every program from its files; false (and logs) if any failed, those keep the old one.
  bool reloadAll(std::string* error);
  // GL program id of `name`, 0 when it never built.
  unsigned program(const std::string& name) const;
  const std::string& directory() const { return directory_; }

  // Reads `file` and inlines its #include "..." lines (relative to the shader dir), inserting
  // `defines` after #version. `lineMap[k]` = "FILE:LINE" of line k+1 of the result. Throws
  // std::runtime_error for a missing file or an include cycle. (Pure, no GL.)
  std::string preprocess(const std::string& file, const std::vector<std::string>& defines,
                         std::vector<std::string>* lineMap) const;

 private:
  struct Entry {
    ProgramSpec spec;
    unsigned program = 0;
  };
  std::string directory_;
  std::map<std::string, Entry> programs_;
};

// Rewrites a GLSL driver log, replacing the "0:LINE" / "0(LINE)" locations with FILE:LINE from
// lineMap (Mesa and NVIDIA formats). (Pure, no GL.)
std::string mapShaderLog(const std::string& log, const std::vector<std::string>& lineMap);

}  // namespace polarview
