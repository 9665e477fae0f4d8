// ShaderLibrary: include expansion, FILE:LINE error logs, and keeping the previous program.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "render_test_support.h"

namespace polarview {
namespace {

namespace fs = std::filesystem;

// A scratch shader directory with a `common/` subfolder, removed at the end of the test.
struct ScratchShaderDir {
  fs::path root;
  ScratchShaderDir() {
    root = fs::temp_directory_path() / ("polarview_shader_test_" + std::to_string(::getpid()));
    fs::create_directories(root / "common");
  }
  ~ScratchShaderDir() { fs::remove_all(root); }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(root / name) << text;
  }
};

const char* const kGoodVertex =
    "#version 410 core\n"
    "#include \"common/offset.glsl\"\n"
    "layout(location = 0) in vec3 a_position;\n"
    "void main() { gl_Position = vec4(a_position + offsetOf(), 1.0); }\n";
const char* const kFragment =
    "#version 410 core\nout vec4 o_color;\nvoid main() { o_color = vec4(1.0); }\n";

TEST_CASE("shader library: includes are inlined once and every line maps back to FILE:LINE") {
  ScratchShaderDir dir;
  dir.write("common/offset.glsl", "// helper\nvec3 offsetOf() { return vec3(0.0); }\n");
  dir.write("common/twice.glsl", "#include \"common/offset.glsl\"\nfloat two() { return 2.0; }\n");
  dir.write("main.vert", "#version 410 core\n#include \"common/offset.glsl\"\n"
                         "#include \"common/twice.glsl\"\nvoid main() {}\n");
  ShaderLibrary library(dir.root.string());
  std::vector<std::string> lineMap;
  const std::string source = library.preprocess("main.vert", {"PROBE", "N 3"}, &lineMap);
  // One copy of offset.glsl despite two includes; defines right after #version.
  CHECK(source.find("vec3 offsetOf()") == source.rfind("vec3 offsetOf()"));
  CHECK(source.rfind("#version 410 core\n#define PROBE\n#define N 3\n", 0) == 0);
  const std::vector<std::string> expected = {
      "main.vert:1",   "<define PROBE>", "<define N 3>",  "common/offset.glsl:1",
      "common/offset.glsl:2", "common/twice.glsl:2", "main.vert:4"};
  CHECK(lineMap == expected);
  CHECK(std::count(source.begin(), source.end(), '\n') == static_cast<long>(lineMap.size()));
}

TEST_CASE("shader library: a missing include or an include cycle is an error naming the file") {
  ScratchShaderDir dir;
  dir.write("a.glsl", "#include \"b.glsl\"\n");
  dir.write("b.glsl", "#include \"a.glsl\"\n");
  dir.write("c.glsl", "#include \"common/nowhere.glsl\"\n");
  ShaderLibrary library(dir.root.string());
  CHECK_THROWS_WITH(library.preprocess("a.glsl", {}, nullptr), doctest::Contains("cycle at a.glsl"));
  CHECK_THROWS_WITH(library.preprocess("c.glsl", {}, nullptr), doctest::Contains("nowhere.glsl"));
}

TEST_CASE("shader library: driver logs are rewritten to FILE:LINE in Mesa and NVIDIA formats") {
  const std::vector<std::string> lineMap = {"main.vert:1", "common/x.glsl:7", "main.vert:3"};
  CHECK(mapShaderLog("0:2(12): error: bad\n", lineMap) == "common/x.glsl:7: error: bad\n");
  CHECK(mapShaderLog("0(3) : error C1008: undefined\n", lineMap) == "main.vert:3 : error C1008: undefined\n");
  CHECK(mapShaderLog("0:9(1): error: out of range\n", lineMap) == "0:9(1): error: out of range\n");
}

TEST_CASE("shader library: a broken include reports its own FILE:LINE and keeps the old program") {
  test::glContext();
  ScratchShaderDir dir;
  dir.write("common/offset.glsl", "vec3 offsetOf() { return vec3(0.0); }\n");
  dir.write("test.vert", kGoodVertex);
  dir.write("test.frag", kFragment);
  ShaderLibrary library(dir.root.string());
  ProgramSpec spec;
  spec.vertex = "test.vert";
  spec.fragment = "test.frag";
  std::string error;
  REQUIRE_MESSAGE(library.build("test", spec, &error), error);
  const unsigned good = library.program("test");
  CHECK(good != 0);

  // Line 3 of the include is broken: the log must point there, not at the concatenated line.
  dir.write("common/offset.glsl", "// a comment\n// another\nvec3 offsetOf() { return vec3(0.0) }\n");
  error.clear();
  CHECK_FALSE(library.reloadAll(&error));
  CHECK(error.find("common/offset.glsl:3") != std::string::npos);
  CHECK(library.program("test") == good);

  // Fixed again: a new program replaces the old one.
  dir.write("common/offset.glsl", "vec3 offsetOf() { return vec3(1.0); }\n");
  error.clear();
  CHECK(library.reloadAll(&error));
  CHECK(library.program("test") != 0);
}

}  // namespace
}  // namespace polarview
