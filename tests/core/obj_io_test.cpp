// OBJ reading and writing: exact round trips, one precise error per kind of bad input.
#include <doctest/doctest.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>

#include "temp_dir.h"
#include "core/mesh/obj_io.h"

using namespace polarview;
namespace fs = std::filesystem;

namespace {

struct TempDir : test::TempDir {
  TempDir() : test::TempDir("polarview_obj_test_") {}
};

// Parses `text`; returns the InputError's line (or -1 when it parsed) and its message.
int64_t errorLine(const std::string& text, std::string* message = nullptr) {
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
  CHECK(m.faceLine == std::vector<int64_t>{13, 14});
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
      {"# only a comment\n\n", 0, "no vertices or faces"},
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
  CHECK(bom.faceLine == std::vector<int64_t>{8, 9});
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
  CHECK(parseObjText("v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 \\\r2 3\r", "cont.obj").faceLine == std::vector<int64_t>{4});
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

// [SECTION] t tags (OpenSubdiv's crease, corner, hole and option tags)

namespace {

// kTwoQuads' edges: 0-1, 1-2, 2-3, 3-0, 1-4, 4-5, 5-2 (0-based, as tags number them); 0-2 is a diagonal.
constexpr int kTwoQuadsLines = 9;

}  // namespace

TEST_CASE("obj: t tags give creases, corners, holes and options, merged as OpenSubdiv applies them") {
  std::vector<std::string> warnings;
  const PolyMesh m = parseObjText(std::string(kTwoQuads) +
                                      "t crease 2/1/0 1 0 2.5\n"
                                      "t crease 4/1/0 1 2 4 5 10\n"           // two edges, one sharpness
                                      "t crease 4/2/0 2 3 \\\n 5 2 0.1 7\n"   // one sharpness per edge, continued
                                      "t crease 2/1/0 2 1 0.75   # a later tag overrides\n"
                                      "t crease 2/1/0 4 5 0\n"                // sharpness 0: no crease
                                      "t corner 2/1/0 3 0 1.5\n"
                                      "t corner 2/2/0 4 3 +3 1e-3\n"
                                      "t hole 2/0/0 1 1\n"
                                      "t interpolateboundary 1/0/0 1\n"
                                      "t creasemethod 0/0/1 chaikin\n"
                                      "t smoothtriangles 0/0/1 smooth\n",
                                  "tags.obj", &warnings);
  CHECK(m.faceCount() == 2);
  CHECK(m.tags.creases == std::vector<CreaseEdge>{{0, 1, 2.5}, {1, 2, 0.75}, {2, 3, 0.1}, {2, 5, 7.0}});
  CHECK(m.tags.corners == std::vector<CornerVertex>{{0, 1.5}, {3, 1e-3}, {4, 3.0}});
  CHECK(m.tags.holes == std::vector<Index>{1});
  CHECK(m.tags.boundary == BoundaryInterpolation::EdgeAndCorner);
  CHECK(m.tags.creaseMethod == CreaseMethod::Chaikin);
  CHECK(m.tags.triangles == TriangleSubdivision::Smooth);
  CAPTURE(warnings);
  REQUIRE(warnings.size() == 3);  // creasemethod applies with the creases, holes in every scheme
  CHECK(warnings[0] == "4 crease edges and 3 corners ('t' tags): Catmull-Clark's rules apply them in every scheme (a pole "
                       "they touch is left to Catmull-Clark; faces at semi-sharp features are refined to the last level), "
                       "except RTS/BPS's radial refinement of caps and globes");
  CHECK(warnings[1].find("'t interpolateboundary 1' (sharp corners): Catmull-Clark's rules apply") == 0);
  CHECK(warnings[2].find("'t smoothtriangles smooth' (OpenSubdiv's TRI_SUB_SMOOTH edge weights next to triangles): Catmull-Clark's rules apply") == 0);

  // OpenSubdiv's own options are the defaults; tags it has but polarview cannot use are named.
  warnings.clear();
  const PolyMesh plain = parseObjText(std::string(kTwoQuads) +
                                          "t interpolateboundary 1/0/0 2\nt facevaryinginterpolateboundary 1/0/0 1\n"
                                          "t vertexedit 1/0/1 0 add\nt sparkle 0/1/0 3\n",
                                      "plain.obj", &warnings);
  CHECK(plain.tags.empty());
  CHECK(warnings == std::vector<std::string>{"1 face-varying 't' tags ignored (polarview has no face-varying data)",
                                             "1 hierarchical-edit 't' tags ignored (OpenSubdiv 3 does not apply them either)",
                                             "1 't' tags of unknown kind ignored (the first: 'sparkle' on line 13)"});
}

TEST_CASE("obj: each kind of bad t tag names its line") {
  struct Bad {
    const char* tag;
    const char* words;
  };
  const Bad cases[] = {
      {"t\n", "tag without a name"},
      {"t crease\n", "tag 'crease': malformed counts ''"},
      {"t crease 2/1 0 1 2\n", "malformed counts '2/1'"},
      {"t crease 2/1/0/0 0 1 2\n", "malformed counts"},
      {"t crease 2/-1/0 0 1\n", "malformed counts"},
      {"t crease 2/1/0 0 1\n", "tag 'crease' has 2 values, its counts 2/1/0 say 3"},
      {"t crease 2/1/0 0 1 2 3\n", "has 4 values"},
      {"t crease 99999999999999999999/1/0 0 1 2\n", "has 3 values"},
      {"t crease 3/1/0 0 1 2 1\n", "tag 'crease' with counts 3/1/0: expected 2k/1/0 or 2k/k/0"},
      {"t crease 4/3/0 0 1 1 2 1 1 1\n", "expected 2k/1/0 or 2k/k/0"},
      {"t crease 2/1/1 0 1 1 x\n", "expected 2k/1/0"},
      {"t crease 2/1/0 0 x 1\n", "tag 'crease': malformed vertex id 'x'"},
      {"t crease 2/1/0 0 -1 1\n", "vertex id -1 is negative (tag ids are 0-based)"},
      {"t crease 2/1/0 0 3000000000 1\n", "vertex id 3000000000 is too large"},
      {"t crease 2/1/0 0 1 abc\n", "malformed number 'abc'"},
      {"t crease 2/1/0 0 1 -1\n", "tag 'crease': sharpness -1 is negative"},
      {"t crease 2/1/0 0 1 nan\n", "sharpness is NaN"},
      {"t crease 2/1/0 0 1 -inf\n", "sharpness is infinite"},
      {"t crease 2/1/0 0 1 1e999\n", "sharpness '1e999' is too large"},
      {"t crease 2/1/0 2 2 1\n", "tag 'crease': edge from vertex 2 to itself"},
      {"t crease 2/1/0 0 6 1\n", "tag 'crease': vertex id 6 out of range (6 vertices; tag ids are 0-based)"},
      {"t crease 2/1/0 0 2 1\n", "tag 'crease': vertices 0 and 2 (0-based) are not an edge of any face"},
      {"t crease 2/1/0 0 1 1\nt crease 2/1/0 4 1 1\nt crease 2/1/0 3 1 1\n", "vertices 3 and 1"},
      {"t corner 1/1/0 6 1\n", "tag 'corner': vertex id 6 out of range"},
      {"t corner 2/3/0 0 1 1 1 1\n", "tag 'corner' with counts 2/3/0: expected k/1/0 or k/k/0"},
      {"t corner 0/1/0 1\n", "expected k/1/0"},
      {"t corner 1/1/0 0 -0.5\n", "sharpness -0.5 is negative"},
      {"t hole 1/0/0 2\n", "tag 'hole': face id 2 out of range (2 faces; tag ids are 0-based)"},
      {"t hole 1/1/0 0 1\n", "tag 'hole' with counts 1/1/0: expected k/0/0"},
      {"t interpolateboundary 1/0/0 3\n", "tag 'interpolateboundary': '3' is not 0 (none), 1 (edge and corner) or 2 (edge only)"},
      {"t interpolateboundary 1/0/0 -1\n", "is not 0 (none)"},
      {"t interpolateboundary 0/0/1 edge\n", "tag 'interpolateboundary' with counts 0/0/1: expected 1/0/0"},
      {"t creasemethod 0/0/1 fast\n", "tag 'creasemethod': 'fast' is not 'normal' or 'chaikin'"},
      {"t smoothtriangles 0/0/1 loop\n", "is not 'catmark' or 'smooth'"},
      {"t facevaryinginterpolateboundary 1/0/0 6\n", "is not 0 to 5"},
  };
  for (const Bad& bad : cases) {
    const std::string text = std::string(kTwoQuads) + bad.tag;
    std::string message;
    CAPTURE(text);
    const int64_t line = errorLine(text, &message);
    CAPTURE(message);
    CHECK(line > kTwoQuadsLines);
    CHECK(message.find(bad.words) != std::string::npos);
    CHECK(message.find("bad.obj:" + std::to_string(line) + ": ") == 0);
  }
  // Ids are checked once the whole file is known: a tag may come before its vertices and faces.
  std::string message;
  CHECK(errorLine(std::string("t corner 1/1/0 6 1.0\nt hole 1/0/0 0\n") + kTwoQuads, &message) == 1);
  CHECK(message == "bad.obj:1: tag 'corner': vertex id 6 out of range (6 vertices; tag ids are 0-based)");
  const PolyMesh early = parseObjText(std::string("t corner 1/1/0 5 1.0\nt hole 1/0/0 0\n") + kTwoQuads, "early.obj");
  CHECK(early.tags.corners == std::vector<CornerVertex>{{5, 1.0}});
  CHECK(early.tags.holes == std::vector<Index>{0});
}

TEST_CASE("obj: t tags survive a save/load round trip") {
  TempDir dir;
  PolyMesh mesh = parseObjText(kTwoQuads, "q.obj");
  mesh.tags.creases = {{0, 1, 0.1}, {2, 5, kInfiniteSharpness}, {4, 5, 1.0 / 3.0}};
  mesh.tags.corners = {{3, 2.75}, {4, 1e-9}};
  mesh.tags.holes = {1};
  mesh.tags.boundary = BoundaryInterpolation::None;
  mesh.tags.creaseMethod = CreaseMethod::Chaikin;
  mesh.tags.triangles = TriangleSubdivision::Smooth;
  const std::string path = (dir.path / "tags.obj").string();
  saveObj(path, mesh);
  const PolyMesh back = loadObj(path);
  CHECK(back.tags.creases == mesh.tags.creases);
  CHECK(back.tags.corners == mesh.tags.corners);
  CHECK(back.tags.holes == mesh.tags.holes);
  CHECK(back.tags.boundary == mesh.tags.boundary);
  CHECK(back.tags.creaseMethod == mesh.tags.creaseMethod);
  CHECK(back.tags.triangles == mesh.tags.triangles);

  // Default tags write no `t` line at all; a bad sharpness is refused before anything is written.
  saveObj(path, parseObjText(kTwoQuads, "q.obj"));
  std::ifstream written(path);
  const std::string text((std::istreambuf_iterator<char>(written)), std::istreambuf_iterator<char>());
  CHECK(text.find("\nt ") == std::string::npos);
  mesh.tags.corners[0].sharpness = -1;
  CHECK_THROWS_AS(saveObj((dir.path / "bad.obj").string(), mesh), InputError);
  CHECK_FALSE(fs::exists(dir.path / "bad.obj"));
}

// [SECTION] Streaming: hostile files are refused as they are read

namespace {

// A stream of one byte, endless or `limit` bytes long and then `tail`, that counts what it hands out.
class EndlessBytes : public std::streambuf {
 public:
  explicit EndlessBytes(char byte, size_t limit = SIZE_MAX, std::string tail = "") : limit_(limit), tail_(std::move(tail)) {
    block_.fill(byte);
  }
  size_t served = 0;

 protected:
  int_type underflow() override {
    if (served >= limit_) {
      if (tailServed_ || tail_.empty()) return traits_type::eof();
      tailServed_ = true;
      setg(tail_.data(), tail_.data(), tail_.data() + tail_.size());
      return traits_type::to_int_type(tail_[0]);
    }
    const size_t n = std::min(block_.size(), limit_ - served);
    setg(block_.data(), block_.data(), block_.data() + n);
    served += n;
    return traits_type::to_int_type(block_[0]);
  }

 private:
  std::array<char, 4096> block_;
  size_t limit_;
  std::string tail_;
  bool tailServed_ = false;
};

// The InputError's message when `in` is parsed (empty if it parsed).
std::string streamError(std::istream& in, const std::string& name = "stream.obj") {
  try {
    parseObj(in, name);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("obj: an endless stream of NUL bytes or of garbage is refused at its first chunk") {
  for (char byte : {'\0', '\x01', 'x'}) {
    EndlessBytes source(byte);
    std::istream in(&source);
    const std::string message = streamError(in);
    CAPTURE(message);
    CHECK(message.find("stream.obj:1: ") == 0);
    CHECK(message.find(byte == 'x' ? "unknown statement 'xxxx" : byte == '\0' ? "binary data (NUL byte)" : "binary data (control character)") !=
          std::string::npos);
    CHECK(source.served <= (size_t(1) << 20));  // bounded memory: never more than one chunk ahead
  }
}

TEST_CASE("obj: a statement after 256 MB of blanks on its line is read (blanks are not collected)") {
  // Each byte of a line is looked at about once, however many chunks it spans.
  EndlessBytes source(' ', size_t(256) << 20, std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  std::istream in(&source);
  const PolyMesh m = parseObj(in, "blanks.obj");
  CHECK(m.faceLine == std::vector<int64_t>{4});
  CHECK(m.points[1] == Point(1, 0, 0));
}

TEST_CASE("obj: a 64 MB file of NUL bytes is refused, naming line 1") {
  TempDir dir;
  const std::string path = (dir.path / "zeros.obj").string();
  {
    std::ofstream out(path, std::ios::binary);
    const std::string block(size_t(1) << 20, '\0');
    for (int i = 0; i < 64; ++i) out << block;
  }
  REQUIRE(fs::file_size(path) == (uint64_t(64) << 20));
  try {
    loadObj(path);
    FAIL("a file of NUL bytes was read");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) == path + ":1: binary data (NUL byte), not a text OBJ file");
  }
}

TEST_CASE("obj: lines cut across read chunks give the same mesh and errors as one piece") {
  // parseObj reads 64 KiB at a time: put a CRLF, a CR, a continuation and a bad byte at each
  // offset around the first chunk end and compare with parseObjText, which gets the text whole.
  constexpr size_t kChunk = size_t(1) << 16;
  for (const char* tail : {"\r\n", "\r", "\n", " \\\r\n"}) {
    for (size_t shift = 0; shift < 6; ++shift) {
      const std::string comment = "# " + std::string(kChunk - 4 + shift, 'c');
      const std::string text = comment + tail + kTwoQuads;
      CAPTURE(tail);
      CAPTURE(shift);
      std::istringstream stream(text);
      const PolyMesh streamed = parseObj(stream, "s.obj"), whole = parseObjText(text, "s.obj");
      CHECK(streamed.faceLine == whole.faceLine);
      CHECK(streamed.faceVerts == whole.faceVerts);
      CHECK(streamed.faceLine.front() == 9);  // the comment is line 1 (continued or not), kTwoQuads lines 2-10
      for (const std::string& bad : {std::string("v 1 \x01 2\n"), std::string("v 1 abc 2\n")}) {
        std::istringstream badStream(comment + tail + bad);
        std::string wholeMessage;
        errorLine(comment + tail + bad, &wholeMessage);
        CHECK(streamError(badStream, "bad.obj") == wholeMessage);
      }
    }
  }
  // A byte-order mark split over the first reads is still a byte-order mark.
  std::string withBom = std::string("\xEF\xBB\xBF") + kTwoQuads;
  std::istringstream bom(withBom);
  CHECK(parseObj(bom, "bom.obj").faceLine == std::vector<int64_t>{8, 9});
}

TEST_CASE("obj: line numbers are 64-bit, past 2^31 lines") {
  static_assert(std::is_same_v<decltype(PolyMesh::faceLine)::value_type, int64_t>);
  const InputError e("huge.obj", int64_t(3) << 31, "malformed number 'x'");
  CHECK(e.line() == int64_t(6442450944));
  CHECK(std::string(e.what()) == "huge.obj:6442450944: malformed number 'x'");
}

// [SECTION] Saving: shortest numbers, and an edited file written into its own text

namespace {

// A cube as Blender's OBJ exporter writes one (mtllib, o, 6-decimal v, vt, vn, s, usemtl, f v/vt/vn),
// with what other writers add: a CRLF line, a vertex with w, one with a colour and a comment, a
// statement continued over two lines, a group and a `t` tag. Vertex 8 (1-based) is on line 12.
const char* kBlenderCube =
    "# Blender 3.6.5\r\n"
    "# www.blender.org\n"
    "mtllib cube.mtl\n"
    "o Cube\n"
    "v 1.000000 1.000000 -1.000000\n"
    "v 1.000000 -1.000000 -1.000000 1.0\n"
    "v 1.000000 1.000000 1.000000 0.8 0.2 0.2 # red\n"
    "v 1.000000 -1.000000 1.000000\n"
    "v -1.000000 1.000000 -1.000000\n"
    "v -1.000000 \\\n  -1.000000 -1.000000\n"
    "v -1.000000 1.000000 1.000000\n"
    "v  -1.000000\t-1.000000 1.000000\n"
    "vn -0.0000 1.0000 -0.0000\nvn -0.0000 -0.0000 1.0000\nvn -1.0000 -0.0000 -0.0000\n"
    "vn -0.0000 -1.0000 -0.0000\nvn 1.0000 -0.0000 -0.0000\nvn -0.0000 -0.0000 -1.0000\n"
    "vt 0.625000 0.500000\nvt 0.875000 0.500000\nvt 0.875000 0.750000\nvt 0.625000 0.750000\n"
    "s 0\n"
    "usemtl Material\n"
    "g body\n"
    "f 1/1/1 5/2/1 7/3/1 3/4/1\n"
    "f 4/4/2 3/3/2 7/2/2 8/1/2\n"
    "f 8/1/3 7/2/3 5/3/3 6/4/3\n"
    "f 6/1/4 2/2/4 4/3/4 8/4/4\n"
    "f 2/1/5 1/2/5 3/3/5 4/4/5\n"
    "f 6/1/6 5/2/6 1/3/6 2/4/6\n"
    "t crease 2/1/0 0 4 2.5\n";

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void writeText(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// `text` with its first occurrence of `from` replaced by `to` (which must be there).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("obj: numbers are written as the shortest decimal that reads back to the same double") {
  TempDir dir;
  PolyMesh mesh;
  mesh.points = {{0.19509, -0.980785, 1.0}, {0.1 + 0.2, 1e-300, -0.0}, {1.0 / 3.0, 123456789.0, 5e-324}};
  mesh.addFace({0, 1, 2});
  mesh.tags.corners = {{2, 0.1}};
  const std::string path = (dir.path / "short.obj").string();
  saveObj(path, mesh);
  // 17 significant digits would write 0.19509000000000001 and 0.30000000000000004 alike.
  CHECK(readText(path) ==
        "v 0.19509 -0.980785 1\n"
        "v 0.30000000000000004 1e-300 -0\n"
        "v 0.3333333333333333 123456789 5e-324\n"
        "f 1 2 3\n"
        "t corner 1/1/0 2 0.1\n");
  const PolyMesh back = loadObj(path);
  CHECK(back.points == mesh.points);
  CHECK(std::signbit(back.points[1].z));
  CHECK(back.tags.corners == mesh.tags.corners);
}

TEST_CASE("obj: an edited file keeps every line but the moved vertices' coordinates, byte for byte") {
  TempDir dir;
  const std::string in = (dir.path / "cube.obj").string(), out = (dir.path / "cube_edited.obj").string();
  writeText(in, kBlenderCube);
  std::string text;
  PolyMesh mesh = loadObj(in, nullptr, &text);
  CHECK(text == kBlenderCube);
  writeText(in, "v 0 0 0\n");  // the file changes on disk after the load: the text read is kept

  // Nothing moved: the file as it was, every byte.
  CHECK(saveObjEdited(out, mesh, text, in));
  CHECK(readText(out) == kBlenderCube);

  // Vertex 8 moves in x and z; y keeps its text ("-1.000000"), the tab and double blank stay.
  mesh.points[7].x = 0.19509;
  mesh.points[7].z = 0.1 + 0.2;
  CHECK(saveObjEdited(out, mesh, text, in));
  std::string expected =
      replaced(kBlenderCube, "v  -1.000000\t-1.000000 1.000000\n", "v  0.19509\t-1.000000 0.30000000000000004\n");
  CHECK(readText(out) == expected);
  CHECK(loadObj(out).points == mesh.points);

  // w and colour fields and the comment stay; a continued statement becomes one line.
  mesh.points[1].y = 2.0;
  mesh.points[2].z = -0.5;
  mesh.points[5].x = 0.25;
  CHECK(saveObjEdited(out, mesh, text, in));
  expected = replaced(expected, "v 1.000000 -1.000000 -1.000000 1.0\n", "v 1.000000 2 -1.000000 1.0\n");
  expected = replaced(expected, "v 1.000000 1.000000 1.000000 0.8 0.2 0.2 # red\n", "v 1.000000 1.000000 -0.5 0.8 0.2 0.2 # red\n");
  expected = replaced(expected, "v -1.000000 \\\n  -1.000000 -1.000000\n", "v 0.25    -1.000000 -1.000000\n");
  CHECK(readText(out) == expected);
  const PolyMesh back = loadObj(out);
  CHECK(back.points == mesh.points);
  CHECK(back.faceVerts == mesh.faceVerts);
  CHECK(back.tags.creases == mesh.tags.creases);
}

TEST_CASE("obj: an edited save keeps CR-only line ends and a byte-order mark; other faces write a plain file") {
  TempDir dir;
  const std::string text = std::string("\xEF\xBB\xBF") + "v 0 0 0\r# cr only\rv 1 0 0\rv 1 1 0 # moved\rvt 0 0\rf 1/1 2/1 3/1";
  PolyMesh mesh = parseObjText(text, "cr.obj");
  mesh.points[0].z = 1e-300;  // the first statement, right after the byte-order mark
  mesh.points[2].x = -0.75;
  const std::string out = (dir.path / "cr_edited.obj").string();
  CHECK(saveObjEdited(out, mesh, text, "cr.obj"));
  CHECK(readText(out) == replaced(replaced(text, "v 1 1 0 # moved", "v -0.75 1 0 # moved"), "v 0 0 0\r", "v 0 0 1e-300\r"));

  // A mesh with other faces (a conversion's) is not the source's: plain v/f lines, shortest numbers.
  PolyMesh other = mesh;
  other.faceVerts = {0, 2, 1};
  CHECK_FALSE(saveObjEdited(out, other, text, "cr.obj"));
  CHECK(readText(out) == "v 0 0 1e-300\nv 1 0 0\nv -0.75 1 0\nf 1 3 2\n");
  // A non-finite coordinate is refused before anything is written.
  mesh.points[0].y = std::numeric_limits<double>::infinity();
  const std::string bad = (dir.path / "bad.obj").string();
  CHECK_THROWS_AS(saveObjEdited(bad, mesh, text, "cr.obj"), InputError);
  CHECK_FALSE(fs::exists(bad));
}
