// OBJ reading and writing: exact round trips, one precise error per kind of bad input.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>

#include "temp_dir.h"
#include "core/mesh/obj_io.h"

using namespace polarview;
namespace fs = std::filesystem;

namespace {

struct TempDir : test::TempDir {
  TempDir() : test::TempDir("polarview_obj_test_") {}
};

// Parses `text`; returns the InputError's line (or -1 when it parsed) and its message.
int errorLine(const std::string& text, std::string* message = nullptr) {
  try {
    parseObjText(text, "bad.obj");
  } catch (const InputError& e) {
    if (message) *message = e.what();
    CHECK(e.file() == "bad.obj");
    return e.line();
  }
  return -1;
}

const char* kTwoQuads =
    "# two quads\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
    "f 1 2 3 4\n"
    "f 2 5 6 3\n";

}  // namespace

TEST_CASE("obj: doubles survive a save/load round trip bit for bit") {
  TempDir dir;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-300, 149);  // the reader stops at 1e150
  PolyMesh mesh;
  for (int i = 0; i < 3000; ++i)
    mesh.points.emplace_back(unit(rng) * std::pow(10.0, exponent(rng)), unit(rng), unit(rng) * 1e-310);
  mesh.points.emplace_back(kMaxObjCoordinate, std::numeric_limits<double>::denorm_min(), -0.0);
  for (Index i = 0; i + 2 < mesh.vertexCount(); i += 3) mesh.addFace({i, i + 1, i + 2});
  mesh.addFace({0, 3, 6, 9, 12});

  const std::string path = (dir.path / "round.obj").string();
  saveObj(path, mesh);
  CHECK_FALSE(fs::exists(path + ".tmp"));
  std::vector<std::string> warnings;
  PolyMesh back = loadObj(path, &warnings);
  REQUIRE(back.vertexCount() == mesh.vertexCount());
  for (Index v = 0; v < mesh.vertexCount(); ++v)
    for (int k = 0; k < 3; ++k) CHECK(std::signbit(back.points[v][k]) == std::signbit(mesh.points[v][k]));
  CHECK(back.points == mesh.points);
  CHECK(back.faceStart == mesh.faceStart);
  CHECK(back.faceVerts == mesh.faceVerts);
  CHECK(warnings.size() == 1);  // the last vertex is not in any face
  CHECK(warnings.front() == "1 unreferenced vertices ignored");
}

TEST_CASE("obj: faces record their line, texture and normal parts are ignored") {
  std::vector<std::string> warnings;
  PolyMesh m = parseObjText(
      "mtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0 1.0\nv 0 1 0 0.5 0.5 0.5\nvt 0 0\nvn 0 0 1\n"
      "g grp\ns off\nusemtl red\n\nf 1/1/1 2/1/1 3//1\n\t f 1 3/1 4 # comment\nl 1 2\np 3\nt crease 2/1/0 1 2 3.0\n",
      "ok.obj", &warnings);
  CHECK(m.vertexCount() == 4);
  CHECK(m.faceCount() == 2);
  CHECK(m.faceLine == std::vector<int>{13, 14});
  CHECK(m.faceVerts == std::vector<Index>{0, 1, 2, 0, 2, 3});
  CHECK(m.points[3] == Point(0, 1, 0));
  CHECK(warnings.size() == 3);  // one each for 'l', 'p' and 't'
}

TEST_CASE("obj: negative indices are relative to the vertices read so far") {
  PolyMesh m = parseObjText("v 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\nv 0 1 0\nf 1 -2 -1\nf -4 -1 3\n", "rel.obj");
  REQUIRE(m.faceCount() == 3);
  CHECK(std::vector<Index>(m.face(0), m.face(0) + 3) == std::vector<Index>{0, 1, 2});
  CHECK(std::vector<Index>(m.face(1), m.face(1) + 3) == std::vector<Index>{0, 2, 3});
  CHECK(std::vector<Index>(m.face(2), m.face(2) + 3) == std::vector<Index>{0, 3, 2});
}

TEST_CASE("obj: a trailing backslash continues a statement, and errors name its first line") {
  PolyMesh m = parseObjText("v 0 0 0\nv 1 0 \\\n 0\nv 1 1 0\nv 0 1 0\nf 1 2 \\ \r\n 3 4\nf 1 4 3\n", "cont.obj");
  REQUIRE(m.faceCount() == 2);
  CHECK(m.faceSize(0) == 4);
  CHECK(m.points[1] == Point(1, 0, 0));
  CHECK(m.faceLine[0] == 6);
  CHECK(m.faceLine[1] == 8);
  try {
    parseObjText("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 \\\n 9\n", "cont.obj");
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("cont.obj:4:") != std::string::npos);
  }
}

TEST_CASE("obj: each kind of bad input names its line") {
  using namespace std::string_literals;  // "..."s keeps embedded NUL bytes
  struct Bad {
    std::string text;
    int line;
    const char* words;
  };
  const Bad cases[] = {
      {"", 0, "empty file"},
      {"# only a comment\n\n", 0, "empty file"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\n", 0, "no faces"},
      {"v 0 0 0\nv 1 0\0 0\nv 0 1 0\nf 1 2 3\n"s, 2, "NUL byte"},
      {"v 0 0 0\nv 1 0 0\n\x01\x02\x7f\x1b\nf 1 2 3\n", 3, "binary"},
      {"v 0 0 0\nv 1 0 0\n\xc3\xa9\xff\xfe garbage\nf 1 2 3\n", 3, "unknown statement"},
      {"v 0 0 0\nv 1 0x 0\nv 0 1 0\nf 1 2 3\n", 2, "malformed number"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 1.2.3\nf 1 2 3\n", 3, "malformed number"},
      {"v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", 2, "coordinate is NaN"},
      {"v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n", 3, "coordinate is infinite"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 1e999\nf 1 2 3\n", 3, "too large"},
      {"v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", 2, "2 coordinates"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 0 3\n", 4, "face index 0"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 3\nf 1 2 912\n", 6, "face index 912 out of range (3 vertices)"},
      {"v 0 0 0\nv 1 0 0\nf 1 2 -3\nv 0 1 0\n", 3, "face index -3 out of range (2 vertices)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n", 4, "too large"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3000000000\n", 4, "too large"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", 4, "malformed face index"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", 4, "face has 2 vertices"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf\n", 5, "face has 0 vertices"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 -2\n", 4, "face repeats vertex 2"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nfrobnicate 1 2 3\nf 1 2 3\n", 4, "unknown statement 'frobnicate'"},
  };
  for (const Bad& bad : cases) {
    const std::string& text = bad.text;
    std::string message;
    CAPTURE(text);
    CHECK(errorLine(text, &message) == bad.line);
    CAPTURE(message);
    CHECK(message.find(bad.words) != std::string::npos);
    if (bad.line > 0) CHECK(message.find("bad.obj:" + std::to_string(bad.line) + ": ") == 0);
  }
}

TEST_CASE("obj: face indices at the limits of 64-bit integers are refused without overflow") {
  struct Bad {
    const char* text;
    int line;
    const char* words;
  };
  // Negating LLONG_MIN was undefined behaviour and let this face through (then a vertex came).
  const Bad cases[] = {
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\nv 1 1 1\n", 4,
       "face index -9223372036854775808 out of range (3 vertices)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775809\n", 4, "out of range (3 vertices)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -2147483648\n", 4, "face index -2147483648 out of range"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", 4, "face index -4 out of range (3 vertices)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9223372036854775807\n", 4, "face index 9223372036854775807 is too large"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 18446744073709551617\n", 4, "is too large"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2147483648\n", 4, "face index 2147483648 is too large"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2147483647\n", 4, "face index 2147483647 out of range (3 vertices)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -0\n", 4, "face index 0"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -\n", 4, "malformed face index"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 --3\n", 4, "malformed face index"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 +3\n", 4, "malformed face index"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3x/1\n", 4, "malformed face index"},
  };
  for (const Bad& bad : cases) {
    std::string message;
    CAPTURE(bad.text);
    CHECK(errorLine(bad.text, &message) == bad.line);
    CAPTURE(message);
    CHECK(message.find(bad.words) != std::string::npos);
  }
  // The extremes that do resolve still work.
  PolyMesh m = parseObjText("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -0001\nf 00001 -2 3/7/9\n", "ok.obj");
  CHECK(m.faceVerts == std::vector<Index>{0, 1, 2, 0, 1, 2});
}

TEST_CASE("obj: coordinates beyond 1e150 are refused, so no result overflows") {
  CHECK(errorLine("v 0 0 0\nv 1 0 0\nv 0 1 1.0000001e150\nf 1 2 3\n") == 3);
  CHECK(errorLine("v 0 0 0\nv -1e151 0 0\nv 0 1 0\nf 1 2 3\n") == 2);
  std::string message;
  CHECK(errorLine("v 1e307 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", &message) == 1);
  CHECK(message == "bad.obj:1: coordinate '1e307' is too large (the limit is 1e150)");
  PolyMesh m = parseObjText("v 1e150 -1e150 0\nv 1 0 0\nv 0 1 1e-320\nf 1 2 3\n", "ok.obj");
  CHECK(m.points[0] == Point(kMaxObjCoordinate, -kMaxObjCoordinate, 0));
}

TEST_CASE("obj: a UTF-8 byte-order mark is skipped; LF, CRLF and a lone CR all end lines") {
  const char* kBom = "\xEF\xBB\xBF";
  PolyMesh bom = parseObjText(std::string(kBom) + kTwoQuads, "bom.obj");
  CHECK(bom.faceCount() == 2);
  CHECK(bom.faceLine == std::vector<int>{8, 9});
  CHECK(parseObjText(std::string(kBom) + "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n", "bom.obj").faceCount() == 1);
  // Only at the very start: elsewhere the bytes are not a statement.
  CHECK(errorLine(std::string("v 0 0 0\n") + kBom + "v 1 0 0\n") == 2);

  // Old Mac (CR only), Windows (CRLF) and a mix give the same mesh and the same line numbers.
  std::string lf = kTwoQuads, cr, crlf, mixed;
  int newline = 0;
  for (char ch : lf) {
    cr += ch == '\n' ? '\r' : ch;
    crlf += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
    mixed += ch == '\n' ? std::string(++newline % 3 == 0 ? "\n" : newline % 3 == 1 ? "\r" : "\r\n") : std::string(1, ch);
  }
  const PolyMesh expected = parseObjText(lf, "lf.obj");
  for (const std::string& text : {cr, crlf, mixed}) {
    CAPTURE(text);
    PolyMesh m = parseObjText(text, "eol.obj");
    CHECK(m.points == expected.points);
    CHECK(m.faceVerts == expected.faceVerts);
    CHECK(m.faceLine == expected.faceLine);
  }
  // Errors in a CR-only file name the right line, binary bytes included.
  CHECK(errorLine("v 0 0 0\rv 1 0 0\rv 0 1 0.0.1\rf 1 2 3\r") == 3);
  CHECK(errorLine("v 0 0 0\rv 1 0 0\r\x01\rf 1 2 3\r") == 3);
  CHECK(errorLine("v 0 0 0\r\nv 1 0 0\r\n\x01\r\nf 1 2 3\r\n") == 3);
  // A continuation backslash works across CR-only lines too.
  CHECK(parseObjText("v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 \\\r2 3\r", "cont.obj").faceLine == std::vector<int>{4});
}

TEST_CASE("obj: random corruption of a valid file never crashes the reader") {
  std::mt19937 rng(2024);
  const std::string valid = kTwoQuads;
  int parsed = 0, rejected = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    std::string text = valid;
    const int edits = 1 + int(rng() % 6);
    for (int e = 0; e < edits; ++e) {
      const size_t at = rng() % text.size();
      switch (rng() % 3) {
        case 0: text[at] = char(rng() % 256); break;
        case 1: text.erase(at, 1 + rng() % 4); break;
        default: text.insert(at, 1, "-0123456789 /\nfv.e#"[rng() % 19]); break;
      }
      if (text.empty()) text = " ";
    }
    try {
      PolyMesh m = parseObjText(text, "fuzz.obj");
      // Anything accepted must be structurally sound.
      for (Index v : m.faceVerts) REQUIRE((v >= 0 && v < m.vertexCount()));
      for (Index f = 0; f < m.faceCount(); ++f) REQUIRE(m.faceSize(f) >= 3);
      for (const Point& p : m.points) REQUIRE((std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)));
      ++parsed;
    } catch (const InputError& e) {
      REQUIRE(std::string(e.what()).rfind("fuzz.obj", 0) == 0);
      ++rejected;
    }
  }
  MESSAGE("corrupted files: ", parsed, " parsed, ", rejected, " rejected");
  CHECK(parsed + rejected == 4000);
  CHECK(rejected > 0);
}

TEST_CASE("obj: unreadable files are InputErrors naming the path") {
  TempDir dir;
  const std::string missing = (dir.path / "missing.obj").string();
  CHECK_THROWS_AS(loadObj(missing), InputError);
  try {
    loadObj(dir.path.string());  // a directory is not a file
    FAIL("a directory was read as an OBJ file");
  } catch (const InputError& e) {
    CHECK(e.file() == dir.path.string());
  }
  std::istringstream stream(kTwoQuads);
  CHECK(parseObj(stream, "s.obj").faceCount() == 2);
}

TEST_CASE("obj: a failed save leaves neither a partial file nor a temp file") {
  TempDir dir;
  PolyMesh mesh = parseObjText(kTwoQuads, "q.obj");
  const std::string intoMissingDir = (dir.path / "no" / "such" / "out.obj").string();
  CHECK_THROWS_AS(saveObj(intoMissingDir, mesh), InputError);
  CHECK_FALSE(fs::exists(intoMissingDir));
  CHECK_FALSE(fs::exists(intoMissingDir + ".tmp"));

  // Replacing an existing file works in one step; the old content is gone, no temp remains.
  const std::string path = (dir.path / "out.obj").string();
  { std::ofstream(path) << "old"; }
  saveObj(path, mesh);
  CHECK(loadObj(path).faceVerts == mesh.faceVerts);
  CHECK_FALSE(fs::exists(path + ".tmp"));

  // A path that is a directory cannot be replaced: error, the directory survives.
  const std::string dirPath = (dir.path / "adir").string();
  fs::create_directories(dirPath + "/child");
  CHECK_THROWS_AS(saveObj(dirPath, mesh), InputError);
  CHECK(fs::is_directory(dirPath));
  CHECK_FALSE(fs::exists(dirPath + ".tmp"));
}

TEST_CASE("obj: a mesh with a non-finite coordinate is never written, and the error names the input") {
  TempDir dir;
  PolyMesh mesh = parseObjText(kTwoQuads, "q.obj");
  const std::string path = (dir.path / "out.obj").string();
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity()}) {
    PolyMesh broken = mesh;
    broken.points[4].y = bad;
    try {
      saveObj(path, broken, "in.obj");
      FAIL("a non-finite coordinate was written");
    } catch (const InputError& e) {
      CHECK(e.file() == "in.obj");
      CHECK(std::string(e.what()).find("non-finite coordinate (vertex 5)") != std::string::npos);
    }
    CHECK(fs::is_empty(dir.path));
  }
  // Without a source name the error names the output.
  mesh.points[0].x = std::numeric_limits<double>::quiet_NaN();
  try {
    saveObj(path, mesh);
    FAIL("a NaN coordinate was written");
  } catch (const InputError& e) {
    CHECK(e.file() == path);
  }
  CHECK(fs::is_empty(dir.path));
}

TEST_CASE("obj: a million-face grid parses quickly and completely") {
  constexpr int n = 1000;  // n x n quads
  std::string text;
  text.reserve(size_t(n + 1) * (n + 1) * 24 + size_t(n) * n * 32);
  char line[96];
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) text.append(line, std::snprintf(line, sizeof line, "v %.6f %.6f 0\n", i / double(n), j / double(n)));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i + 1;
      text.append(line, std::snprintf(line, sizeof line, "f %d %d %d %d\n", a, a + 1, a + n + 2, a + n + 1));
    }
  const auto start = std::chrono::steady_clock::now();
  PolyMesh m = parseObjText(text, "big.obj");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  MESSAGE("parsed ", text.size() / 1e6, " MB, 1M faces in ", seconds, " s");
  CHECK(m.faceCount() == n * n);
  CHECK(m.vertexCount() == (n + 1) * (n + 1));
  CHECK(m.faceLine.back() == (n + 1) * (n + 1) + n * n);
  CHECK(m.points.back() == Point(1, 1, 0));
}
