// polarview's OBJ reader against tinyobjloader (the reader the design names, Debian's 2.0.0rc10 in
// double precision), as an independent oracle: both read the shipped models and tagged files alike,
// and where they differ it is tinyobjloader losing data (docs/toolchain.md, tinyobjloader).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <tuple>

#include <tiny_obj_loader.h>

#include "core/mesh/obj_io.h"

using namespace polarview;

namespace {

tinyobj::ObjReader readWithTinyObj(const std::string& text) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  reader.ParseFromString(text, "", config);
  REQUIRE_MESSAGE(reader.Valid(), reader.Error());
  return reader;
}

// Vertices to 4 units in the last place (tinyobjloader does not round correctly), faces and their
// sizes, and crease tags exactly. Returns the largest relative coordinate difference.
double compareReaders(const std::string& text, const std::string& name) {
  CAPTURE(name);
  const PolyMesh ours = parseObjText(text, name);
  const tinyobj::ObjReader theirs = readWithTinyObj(text);
  const std::vector<tinyobj::real_t>& v = theirs.GetAttrib().vertices;
  REQUIRE(v.size() == 3 * ours.points.size());
  double worst = 0.0;
  for (size_t i = 0; i < ours.points.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double a = ours.points[i][c], b = double(v[3 * i + size_t(c)]);
      worst = std::max(worst, std::abs(a - b) / std::max(std::abs(a), 1e-300));
    }
  CHECK(worst <= 9e-16);  // 4 units in the last place
  // Faces, in file order over all shapes (groups).
  std::vector<Index> verts;
  std::vector<int> sizes;
  std::vector<CreaseEdge> creases;
  for (const tinyobj::shape_t& shape : theirs.GetShapes()) {
    for (const tinyobj::index_t& index : shape.mesh.indices) verts.push_back(index.vertex_index);
    for (const unsigned char k : shape.mesh.num_face_vertices) sizes.push_back(k);
    for (const tinyobj::tag_t& tag : shape.mesh.tags)
      if (tag.name == "crease")
        for (size_t k = 0; k + 1 < tag.intValues.size(); k += 2)
          creases.push_back({std::min(tag.intValues[k], tag.intValues[k + 1]), std::max(tag.intValues[k], tag.intValues[k + 1]),
                             double(tag.floatValues[tag.floatValues.size() == 1 ? 0 : k / 2])});
  }
  CHECK(verts == ours.faceVerts);
  REQUIRE(sizes.size() == size_t(ours.faceCount()));
  for (Index f = 0; f < ours.faceCount(); ++f) CHECK(sizes[size_t(f)] == ours.faceSize(f));
  std::sort(creases.begin(), creases.end(), [](const CreaseEdge& x, const CreaseEdge& y) { return std::tie(x.v0, x.v1) < std::tie(y.v0, y.v1); });
  CHECK(creases == ours.tags.creases);
  return worst;
}

}  // namespace

TEST_CASE("obj vs tinyobjloader: the shipped models and a tagged file read alike") {
  size_t files = 0;
  double worst = 0.0;
  for (const auto& entry : std::filesystem::directory_iterator(POLARVIEW_ASSET_DIR)) {
    if (entry.path().extension() != ".obj") continue;
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    worst = std::max(worst, compareReaders(text, entry.path().filename().string()));
    ++files;
  }
  CHECK(files >= 10);
  const std::string tagged =
      "# a cube with a crease loop\nv -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
      "g box\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\nt crease 2/1/0 0 1 2.5\nt crease 4/1/0 1 2 2 3 10\n";
  compareReaders(tagged, "tagged.obj");
  MESSAGE(files, " shipped models: coordinates within ", worst, " relative of tinyobjloader's");
}

TEST_CASE("obj vs tinyobjloader: where it loses data (why polarview reads OBJ itself)") {
  // Face sizes are kept in one byte: a 300-gon comes back as a 44-gon.
  std::string polygon;
  for (int k = 0; k < 300; ++k) polygon += "v " + std::to_string(std::cos(k * 0.0209)) + " " + std::to_string(std::sin(k * 0.0209)) + " 0\n";
  polygon += "f";
  for (int k = 1; k <= 300; ++k) polygon += " " + std::to_string(k);
  polygon += "\n";
  CHECK(parseObjText(polygon, "polygon.obj").faceSize(0) == 300);
  CHECK(int(readWithTinyObj(polygon).GetShapes().at(0).mesh.num_face_vertices.at(0)) == 300 % 256);
  // Numbers are not rounded correctly: the shortest text of a double does not read back to it.
  const std::string text = "v 0.30000000000000004 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  CHECK(parseObjText(text, "round.obj").points[0].x == 0.30000000000000004);
  CHECK(double(readWithTinyObj(text).GetAttrib().vertices[0]) != 0.30000000000000004);
}
