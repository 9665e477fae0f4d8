// Shader files -> GL programs, with #include and FILE:LINE error logs (see shader_library.h).
#include "render/shader_library.h"

#include <glad/gl.h>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

namespace polarview {
namespace {

std::string defaultShaderDirectory() {
  if (const char* env = std::getenv("POLARVIEW_SHADER_DIR"); env && *env) return env;
#ifdef POLARVIEW_SHADER_DIR
  return POLARVIEW_SHADER_DIR;
#else
  return "shaders";
#endif
}

std::string readTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open shader file " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Recursive include expansion; each file is included once (like #pragma once).
void expand(const std::string& directory, const std::string& file,
            const std::vector<std::string>& defines, std::vector<std::string>& stack,
            std::set<std::string>& included, std::string& out, std::vector<std::string>& lineMap) {
  for (const auto& open : stack)
    if (open == file) throw std::runtime_error("shader include cycle at " + file);
  if (!included.insert(file).second) return;
  stack.push_back(file);
  std::istringstream in(readTextFile(directory + "/" + file));
  static const std::regex includeLine(R"(^\s*#\s*include\s*"([^"]+)\"\s*$)");
  std::string line;
  int lineNumber = 0;
  while (std::getline(in, line)) {
    ++lineNumber;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::smatch match;
    if (std::regex_match(line, match, includeLine)) {
      expand(directory, match[1].str(), defines, stack, included, out, lineMap);
      continue;
    }
    out += line;
    out += '\n';
    lineMap.push_back(file + ":" + std::to_string(lineNumber));
    // Defines go right after #version (only the top-level file has one).
    if (stack.size() == 1 && line.rfind("#version", 0) == 0) {
      for (const auto& define : defines) {
        out += "#define " + define + "\n";
        lineMap.push_back("<define " + define + ">");
      }
    }
  }
  stack.pop_back();
}

GLuint compileStage(GLenum stage, const std::string& source, const std::vector<std::string>& lineMap,
                    const std::string& file, std::string* error) {
  GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok) return shader;
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  if (error) *error += "compiling " + file + ":\n" + mapShaderLog(log.c_str(), lineMap) + "\n";
  glDeleteShader(shader);
  return 0;
}

}  // namespace

std::string mapShaderLog(const std::string& log, const std::vector<std::string>& lineMap) {
  // Mesa: "0:12(5): error" ; NVIDIA: "0(12) : error".
  static const std::regex location(R"((\d+):(\d+)\((\d+)\)|(\d+)\((\d+)\))");
  std::string out;
  auto begin = log.cbegin();
  std::smatch match;
  while (std::regex_search(begin, log.cend(), match, location)) {
    out.append(begin, match[0].first);
    const int line = std::stoi(match[2].matched ? match[2].str() : match[5].str());
    if (line >= 1 && static_cast<size_t>(line) <= lineMap.size())
      out += lineMap[static_cast<size_t>(line) - 1];
    else
      out += match[0].str();
    begin = match[0].second;
  }
  out.append(begin, log.cend());
  return out;
}

ShaderLibrary::ShaderLibrary() : directory_(defaultShaderDirectory()) {}
ShaderLibrary::ShaderLibrary(std::string directory) : directory_(std::move(directory)) {}

ShaderLibrary::~ShaderLibrary() {
  for (auto& [name, entry] : programs_)
    if (entry.program) glDeleteProgram(entry.program);
}

std::string ShaderLibrary::preprocess(const std::string& file,
                                      const std::vector<std::string>& defines,
                                      std::vector<std::string>* lineMap) const {
  std::vector<std::string> stack, map;
  std::set<std::string> included;
  std::string out;
  expand(directory_, file, defines, stack, included, out, map);
  if (lineMap) *lineMap = std::move(map);
  return out;
}

bool ShaderLibrary::build(const std::string& name, const ProgramSpec& spec, std::string* error) {
  std::string log;
  const std::pair<GLenum, const std::string*> stages[] = {
      {GL_VERTEX_SHADER, &spec.vertex},         {GL_TESS_CONTROL_SHADER, &spec.tessControl},
      {GL_TESS_EVALUATION_SHADER, &spec.tessEval}, {GL_GEOMETRY_SHADER, &spec.geometry},
      {GL_FRAGMENT_SHADER, &spec.fragment}};
  std::vector<GLuint> shaders;
  bool ok = true;
  // Compile every present stage (all of them, so one pass reports every broken file).
  for (const auto& [stage, file] : stages) {
    if (file->empty()) continue;
    try {
      std::vector<std::string> lineMap;
      const std::string source = preprocess(*file, spec.defines, &lineMap);
      const GLuint shader = compileStage(stage, source, lineMap, *file, &log);
      if (shader) shaders.push_back(shader); else ok = false;
    } catch (const std::exception& e) {
      log += std::string(e.what()) + "\n";
      ok = false;
    }
  }
  GLuint program = 0;
  if (ok) {
    program = glCreateProgram();
    for (GLuint shader : shaders) glAttachShader(program, shader);
    if (!spec.feedbackVaryings.empty()) {
      std::vector<const char*> names;
      for (const auto& varying : spec.feedbackVaryings) names.push_back(varying.c_str());
      glTransformFeedbackVaryings(program, static_cast<GLsizei>(names.size()), names.data(),
                                  GL_INTERLEAVED_ATTRIBS);
    }
    glLinkProgram(program);
    GLint linked = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) {
      GLint length = 0;
      glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
      std::string linkLog(static_cast<size_t>(std::max(length, 1)), '\0');
      glGetProgramInfoLog(program, length, nullptr, linkLog.data());
      log += "linking program " + name + ":\n" + std::string(linkLog.c_str()) + "\n";
      glDeleteProgram(program);
      program = 0;
      ok = false;
    }
  }
  for (GLuint shader : shaders) glDeleteShader(shader);

  // Keep the previous program on failure; remember the spec either way for reloadAll().
  Entry& entry = programs_[name];
  entry.spec = spec;
  if (ok) {
    if (entry.program) glDeleteProgram(entry.program);
    entry.program = program;
  } else if (error) {
    *error += log;
  }
  return ok;
}

bool ShaderLibrary::reloadAll(std::string* error) {
  bool ok = true;
  std::vector<std::pair<std::string, ProgramSpec>> specs;
  for (const auto& [name, entry] : programs_) specs.emplace_back(name, entry.spec);
  for (const auto& [name, spec] : specs) ok = build(name, spec, error) && ok;
  return ok;
}

unsigned ShaderLibrary::program(const std::string& name) const {
  auto it = programs_.find(name);
  return it == programs_.end() ? 0u : it->second.program;
}

}  // namespace polarview
