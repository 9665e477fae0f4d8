// OpenSubdiv's regression shapes, read where the workplace keeps them beside the project
// (shared/meshes/opensubdiv; the environment's POLARVIEW_OSD_SHAPES overrides), never copied into
// it. Optional: a test finding no shapes (osdShapeFiles empty) says so and skips (tests/CMakeLists.txt,
// POLARVIEW_OSD_SHAPES_DIR). Their `t` tags are commented out as `#t`.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace polarview::testing {

// The shapes' directory: POLARVIEW_OSD_SHAPES from the environment, else `compiledDefault`.
inline std::filesystem::path osdShapeDirectory(const char* compiledDefault) {
  const char* override = std::getenv("POLARVIEW_OSD_SHAPES");
  return override ? override : compiledDefault;
}

// The .obj files of `dir`, sorted; empty when it is not a directory.
inline std::vector<std::filesystem::path> osdShapeFiles(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  if (!std::filesystem::is_directory(dir)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().extension() == ".obj") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

// A shape's OBJ text; with `tags`, its `#t` lines made `t` lines again.
inline std::string osdShapeText(const std::filesystem::path& file, bool tags) {
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (tags)
    for (size_t at = text.find("\n#t "); at != std::string::npos; at = text.find("\n#t ", at + 1)) text.erase(at + 1, 1);
  return text;
}

}  // namespace polarview::testing
