// libFuzzer target over the OBJ reader alone (tests/fuzz/README.md): bytes -> parseObjText, `t`
// tags (crease, corner, hole, options) included, then saveObj -> loadObj of what it read.
//
// Expected: polarview::InputError naming the input and a line of it (0: none). A finding: any
// other exception, a crash, ASan/UBSan report, a hang, or a broken guarantee of obj_io.h:
//  * the mesh has faces of >= 3 distinct vertices with ids in range and their OBJ lines, every
//    coordinate finite and at most kMaxObjCoordinate (checkParsedMesh in fuzz_common.h);
//  * its tags are sorted and merged, ids in range, crease edges edges of a face, sharpness finite
//    and > 0 (checkTags);
//  * saveObj writes what loadObj reads back to the bit (points, faces, tags);
//  * saveObjEdited writes the text itself, byte for byte, when no vertex moved, and with every
//    other vertex moved writes what loadObj reads back as the moved mesh (its statements walked as
//    the reader walks them).
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

#include "core/mesh/input_error.h"
#include "core/mesh/obj_io.h"
#include "fuzz_common.h"
#include "obj_mutator.h"

using namespace polarview;
using namespace polarview::fuzz;

namespace {

constexpr size_t kMaxInputBytes = 1 << 16;

// Lines of the text as the reader counts them: ended by LF, CRLF or a lone CR.
int64_t lineCount(const std::string& text) {
  int64_t lines = 1;
  for (size_t i = 0; i < text.size(); ++i)
    lines += text[i] == '\n' || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'));
  return lines;
}

// Where the round trip writes: tmpfs when there is one (saveObj fsyncs), else the temporary
// directory; one file per process (-jobs), removed after each input.
const std::string& roundTripPath() {
  static const std::string path = [] {
    std::error_code error;
    const std::filesystem::path dir =
        std::filesystem::is_directory("/dev/shm", error) && ::access("/dev/shm", W_OK) == 0
            ? std::filesystem::path("/dev/shm")
            : std::filesystem::temp_directory_path();
    return (dir / ("polarview-fuzz-obj-" + std::to_string(::getpid()) + ".obj")).string();
  }();
  return path;
}

// The file `writer` wrote at `path` reads back (then removed) as `mesh`: points, faces and tags.
void checkReadsBack(const std::string& path, const PolyMesh& mesh, const std::string& writer) {
  gStage = "loadObj of " + writer + "'s file";
  PolyMesh back;
  try {
    back = loadObj(path);
  } catch (const InputError& e) {
    fail(writer + "'s file does not read back: " + e.what());
  }
  std::remove(path.c_str());
  if (back.points != mesh.points) fail("points differ after " + writer + " -> loadObj");
  if (back.faceStart != mesh.faceStart || back.faceVerts != mesh.faceVerts) fail("faces differ after " + writer + " -> loadObj");
  const SubdivTags &a = mesh.tags, &b = back.tags;
  if (a.creases != b.creases || a.corners != b.corners || a.holes != b.holes || a.boundary != b.boundary ||
      a.creaseMethod != b.creaseMethod || a.triangles != b.triangles)
    fail("tags differ after " + writer + " -> loadObj");
}

void checkRoundTrip(const PolyMesh& mesh) {
  gStage = "saveObj";
  const std::string& path = roundTripPath();
  std::remove(path.c_str());
  saveObj(path, mesh, kSource);
  checkReadsBack(path, mesh, "saveObj");
}

// The bytes at `path`, removed.
std::string takeFile(const std::string& path) {
  std::string text;
  if (FILE* file = std::fopen(path.c_str(), "rb")) {
    char buffer[4096];
    for (size_t got; (got = std::fread(buffer, 1, sizeof buffer, file)) > 0;) text.append(buffer, got);
    std::fclose(file);
  }
  std::remove(path.c_str());
  return text;
}

void checkEditedSave(const std::string& text, PolyMesh mesh) {
  gStage = "saveObjEdited, nothing moved";
  const std::string& path = roundTripPath();
  if (!saveObjEdited(path, mesh, text, kSource)) fail("saveObjEdited did not take the mesh read from the text");
  if (takeFile(path) != text) fail("saveObjEdited with nothing moved changed the text");
  gStage = "saveObjEdited, every other vertex moved";
  for (size_t v = 0; v < mesh.points.size(); v += 2) mesh.points[v] = mesh.points[v] * 0.5 + Point(0.25, -0.0, 1e-300);
  if (!saveObjEdited(path, mesh, text, kSource)) fail("saveObjEdited did not take the moved mesh");
  checkReadsBack(path, mesh, "saveObjEdited");
}

void run(const uint8_t* data, size_t size) {
  if (size > kMaxInputBytes) return;
  const std::string text(reinterpret_cast<const char*>(data), size);
  gStage = "parseObjText";
  std::vector<std::string> warnings;
  PolyMesh mesh;
  try {
    mesh = parseObjText(text, kSource, &warnings);
  } catch (const InputError& e) {
    if (e.file() != kSource) fail("InputError names '" + e.file() + "', not the input: " + e.what());
    const int64_t lines = lineCount(text);
    if (e.line() < 0 || e.line() > lines)
      fail("InputError on line " + std::to_string(e.line()) + " of " + std::to_string(lines) + ": " + e.what());
    return;
  }
  checkParsedMesh(mesh);
  checkRoundTrip(mesh);
  checkEditedSave(text, std::move(mesh));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return runInput([&] { run(data, size); });
}
