// A whole viewer session without a window: commands load models, the surfaces follow, a failed
// load keeps the model, Ctrl+Z returns to the previous model, and saves and exports write files
// (Save OBJ of an edited file: the file's own text with the moved vertex's coordinates replaced).
#include <doctest/doctest.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

#include <glm/geometric.hpp>

#include "core/mesh/constants.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/shapes.h"
#include "session/command_table.h"
#include "session/session.h"
#include "session/settings_rules.h"

using namespace polarview;

namespace {

// The window's part, recorded.
struct FakeWindow : WindowServices {
  int framed = 0, screenshots = 0;
  std::string clipboardText;
  void frameModel() override { ++framed; }
  void setClipboard(const std::string& text) override { clipboardText = text; }
  std::string clipboard() override { return clipboardText; }
  void takeScreenshot() override { ++screenshots; }
};

// The frame loop's session part, until nothing is left to do.
void settle(Session& session) {
  do {
    viewerCommands().runQueued(session);
    session.updateModelAndSurfaces();
    session.updatePanels();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  } while (session.busy() || !session.commandQueue().empty());
}

std::filesystem::path freshDirectory() {
  std::random_device random;
  const auto path = std::filesystem::temp_directory_path() / ("polarview_session_" + std::to_string(random()));
  std::filesystem::create_directories(path);
  return path;
}

SessionOptions quiet() {
  SessionOptions options;
  options.persistRecent = false;  // tests leave ~/.config alone
  options.prepareNextLevel = false;
  return options;
}


std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A UV sphere as Blender's OBJ exporter writes it: mtllib, o, v with 6 decimals, vn, vt, s,
// usemtl, quads and pole triangles as f v/vt/vn. `segments` around, `rings` from pole to pole.
std::string blenderSphere(int segments, int rings) {
  std::string text = "# Blender 3.6.5\n# www.blender.org\nmtllib sphere.mtl\no Sphere\n";
  char line[160];
  const double pi = std::acos(-1.0);
  std::vector<std::array<double, 3>> points = {{0, 0, 1}};
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double polar = pi * r / rings, azimuth = 2 * pi * s / segments;
      points.push_back({std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar)});
    }
  points.push_back({0, 0, -1});
  for (const auto& p : points) {
    std::snprintf(line, sizeof line, "v %.6f %.6f %.6f\n", p[0], p[1], p[2]);
    text += line;
  }
  for (const auto& p : points) {
    std::snprintf(line, sizeof line, "vn %.4f %.4f %.4f\n", p[0], p[1], p[2]);
    text += line;
  }
  for (int s = 0; s <= segments; ++s) {
    std::snprintf(line, sizeof line, "vt %.6f 0.500000\n", double(s) / segments);
    text += line;
  }
  text += "s 1\nusemtl Material\n";
  const int last = int(points.size());  // 1-based south pole
  auto ringVertex = [&](int r, int s) { return 2 + (r - 1) * segments + s % segments; };
  for (int s = 0; s < segments; ++s) {
    const int a = ringVertex(1, s), b = ringVertex(1, s + 1);
    std::snprintf(line, sizeof line, "f 1/%d/1 %d/%d/%d %d/%d/%d\n", s + 1, a, s + 1, a, b, s + 2, b);
    text += line;
  }
  for (int r = 1; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const int a = ringVertex(r, s), b = ringVertex(r + 1, s), c = ringVertex(r + 1, s + 1), d = ringVertex(r, s + 1);
      std::snprintf(line, sizeof line, "f %d/%d/%d %d/%d/%d %d/%d/%d %d/%d/%d\n", a, s + 1, a, b, s + 1, b, c, s + 2, c, d, s + 2, d);
      text += line;
    }
  for (int s = 0; s < segments; ++s) {
    const int a = ringVertex(rings - 1, s), b = ringVertex(rings - 1, s + 1);
    std::snprintf(line, sizeof line, "f %d/%d/%d %d/%d/%d %d/%d/%d\n", b, s + 2, b, a, s + 1, a, last, s + 1, last);
    text += line;
  }
  return text;
}

// Writes `text` as folder/name and opens it as the viewer does (File > Open); returns the path.
std::string openWritten(Session& session, const std::filesystem::path& folder, const std::string& name, const std::string& text) {
  const std::string path = (folder / name).string();
  std::ofstream(path, std::ios::binary) << text;
  REQUIRE(session.apply(session.document().loadFile(path)));
  settle(session);
  return path;
}

// Drags control vertex `vertex` (0-based) `dx` pixels to the right in a 400 x 400 view looking down
// -z at the unit sphere, as the viewer's mouse does (editor drag, points committed, one undo step).
void dragVertex(Document& document, int vertex, float dx) {
  ViewTransform view;
  view.rect = ScreenRect{0, 0, 400, 400};
  view.viewProjection = glm::dmat4(0.5);
  view.viewProjection[3][3] = 1.0;
  const std::optional<glm::dvec3> at = view.project(document.editor().points()[size_t(vertex)]);
  REQUIRE(at);
  REQUIRE(document.editor().beginDrag(vertex, view, glm::dvec3(0, 0, -1), float(at->x), float(at->y)));
  REQUIRE(document.editor().dragTo(view, float(at->x) + dx, float(at->y)));
  document.commitEditedPoints();
  document.editor().endDrag();
}

// The shortest decimal that reads back to `value` (what the writer must write for a moved coordinate).
std::string shortest(double value) {
  char text[64];
  return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}

// `saved` is `original` but for line `changed` (0-based), a `v` line whose numbers are `point`:
// each one the original's text when unchanged, else the shortest decimal of the new value.
void checkOnlyVertexLineChanged(const std::string& original, const std::string& saved, size_t changed, const Point& point) {
  std::vector<std::string> before = linesOf(original), after = linesOf(saved);
  REQUIRE(before.size() == after.size());
  for (size_t i = 0; i < before.size(); ++i)
    if (i != changed) CHECK(after[i] == before[i]);
  CHECK(after[changed] != before[changed]);
  std::istringstream was(before[changed]), now(after[changed]);
  std::string keyword, oldToken, newToken;
  was >> keyword;
  now >> keyword;
  CHECK(keyword == "v");
  for (int c = 0; c < 3; ++c) {
    was >> oldToken;
    now >> newToken;
    CHECK(std::stod(newToken) == point[c]);
    CHECK((newToken == oldToken || newToken == shortest(point[c])));
  }
}
}  // namespace

TEST_CASE("session: the default model through a command, its surface, and a failed load that keeps it") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerSettings& settings = session.settings();
  ViewerStatus& status = session.status();
  session.queueCommand("file.default");
  settle(session);
  REQUIRE(session.model().mesh != nullptr);
  CHECK(window.framed == 1);
  CHECK(status.file.modelName.rfind("default", 0) == 0);
  REQUIRE(session.surfaces().shown(0) != nullptr);
  CHECK(session.surfaces().shown(0)->key == surfaceRequest(settings, session.model()).wanted[0]);
  CHECK(status.views[0].patchCount > 0);

  const uint64_t generation = session.model().generation;
  settings.file.pathField = "/nonexistent/model.obj";
  session.queueCommand("file.open");
  settle(session);
  CHECK(session.model().generation == generation);  // the model stays
  CHECK_FALSE(status.file.error.empty());
  CHECK(session.notices().text().find("could not open /nonexistent/model.obj") == 0);
}

TEST_CASE("session: Ctrl+Z with no edit returns to the model replaced last, again to redo") {
  FakeWindow window;
  Session session(quiet(), window);
  REQUIRE(session.apply(session.document().loadMesh(shapes::cube(), "cube")));
  REQUIRE(session.apply(session.document().loadMesh(shapes::mushroom(6), "mushroom")));
  settle(session);
  session.queueCommand("edit.undo");
  settle(session);
  CHECK(session.model().name == "cube");
  CHECK(session.surfaces().shown(0)->key.model == session.model().generation);
  session.queueCommand("edit.undo");
  settle(session);
  CHECK(session.model().name == "mushroom");
}

TEST_CASE("session: a cylinder's n-gon caps have no pole; N-gons to triangle fans makes two, Ctrl+Z returns") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerSettings& settings = session.settings();
  ViewerStatus& status = session.status();
  const std::filesystem::path dir = freshDirectory();
  const std::string path = (dir / "cylinder.obj").string();
  saveObj(path, shapes::ngonCylinder(24));
  settings.file.pathField = path;
  session.queueCommand("file.open");
  settle(session);
  REQUIRE(status.file.loadedPath == path);
  const PoleInspectorStatus& inspector = status.poleInspector;
  CHECK(inspector.poles.empty());
  CHECK(inspector.survey.fanFaces == 2);  // what the Poles panel offers to convert
  CHECK(inspector.survey.rejectedCount == 0);

  session.queueCommand("model.ngon-to-fan");
  settle(session);
  CHECK(status.file.modelFaces == 24 + 2 * 24);
  REQUIRE(inspector.poles.size() == 2);
  CHECK(inspector.poles == std::vector<Index>{48, 49});
  CHECK(inspector.survey.fanFaces == 0);
  CHECK(session.notices().text().find("2 faces made triangle fans") == 0);
  CHECK(session.surfaces().shown(0)->key.model == session.model().generation);
  CHECK(status.views[0].polesByScheme == 2);  // C2PS refines both

  session.queueCommand("edit.undo");
  settle(session);
  CHECK(status.file.modelFaces == 26);
  CHECK(inspector.poles.empty());
  CHECK(inspector.survey.fanFaces == 2);
  // Nothing to convert: a notice, the model stays.
  const uint64_t generation = session.model().generation;
  REQUIRE(session.apply(session.document().loadMesh(shapes::globe(8, 3), "globe")));
  settle(session);
  session.queueCommand("model.ngon-to-fan");
  settle(session);
  CHECK(session.model().generation == generation + 1);
  CHECK(session.notices().text().find("no face with 5 or more sides") == 0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("session: the Poles panel's candidates that are not poles, the nearest first, with reasons") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerStatus& status = session.status();
  // A cone without a base (its 16-valent fan's rim is a boundary) and, apart, an octahedron (six
  // 4-valent fans ringed by triangles, no quads).
  PolyMesh cone;
  for (int i = 0; i < 16; ++i) cone.points.push_back({std::cos(i * kPi / 8), std::sin(i * kPi / 8), 0.0});
  cone.points.push_back({0.0, 0.0, 2.0});
  for (int i = 0; i < 16; ++i) cone.addFace({i, (i + 1) % 16, 16});
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {1.0, -1.0}) {
      Point p(5.0, 0.0, 0.0);
      p[axis] += sign;
      cone.points.push_back(p);  // 17 + 2 axis + (sign < 0)
    }
  for (int octant = 0; octant < 8; ++octant) {
    const Index x = 17 + (octant & 1), y = 19 + (octant >> 1 & 1), z = 21 + (octant >> 2 & 1);
    const bool outward = (__builtin_popcount(unsigned(octant)) % 2) == 0;  // an even number of minus signs
    if (outward) cone.addFace({x, y, z});
    else cone.addFace({x, z, y});
  }
  REQUIRE(session.apply(session.document().loadMesh(cone, "cone")));
  settle(session);
  const PoleSurvey& survey = status.poleInspector.survey;
  CHECK(status.poleInspector.poles.empty());
  REQUIRE(survey.rejected.size() == 2);
  CHECK(survey.rejectedCount == 1 + 6);
  CHECK(survey.rejected[0].words == "a 1-link vertex is on a boundary");
  REQUIRE(survey.rejected[0].nearest.size() == 1);
  CHECK(survey.rejected[0].nearest[0].vertex == 16);
  CHECK(survey.rejected[0].nearest[0].valence == 16);
  CHECK(survey.rejected[0].nearest[0].reason.find("is on a boundary") != std::string::npos);
  // The octahedron's six, the first three by vertex id listed.
  CHECK(survey.rejected[1].words == "a 1-link vertex is not between 2 triangles and 2 quads");
  CHECK(survey.rejected[1].count == 6);
  REQUIRE(survey.rejected[1].nearest.size() == 3);
  CHECK(survey.rejected[1].nearest[0].vertex == 17);
  CHECK(survey.rejected[1].nearest[2].valence == 4);
  CHECK(survey.fanFaces == 0);
}

TEST_CASE("session: Save OBJ and Export .bv write what the model and the active view are") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerSettings& settings = session.settings();
  ViewerStatus& status = session.status();
  REQUIRE(session.apply(session.document().loadMesh(shapes::mushroom(6), "mushroom")));
  settings.views[0].level = 2;
  settle(session);
  const std::filesystem::path folder = freshDirectory();
  settings.edit.savePath = (folder / "saved.obj").string();
  settings.edit.surfacePath = (folder / "surface.bv").string();
  session.queueCommand("edit.save");
  session.queueCommand("export.surface");
  settle(session);
  CHECK(status.edit.error.empty());
  const PolyMesh saved = loadObj(settings.edit.savePath);
  CHECK(saved.faceCount() == session.model().mesh->faceCount());
  CHECK(saved.points == session.model().mesh->points);
  // BezierView's file: one record a patch, as many as the view's patches.
  std::ifstream bv(settings.edit.surfacePath);
  REQUIRE(bv.good());
  CHECK(session.notices().text().find(std::to_string(session.surfaces().shown(0)->patches.size()) + " Bezier patches") != std::string::npos);
  std::filesystem::remove_all(folder);
}

TEST_CASE("session: Export surface writes the format of the path's extension, and refuses an unknown one") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerSettings& settings = session.settings();
  ViewerStatus& status = session.status();
  REQUIRE(session.apply(session.document().loadMesh(shapes::mushroom(8), "mushroom")));
  settings.views[0].level = 1;
  settle(session);
  const std::filesystem::path folder = freshDirectory();
  const auto firstBytes = [](const std::filesystem::path& path, size_t count) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes(count, '\0');
    in.read(bytes.data(), std::streamsize(count));
    return bytes;
  };
  const size_t patches = session.surfaces().shown(0)->patches.size();
  settings.edit.surfacePath = (folder / "surface.step").string();
  session.queueCommand("export.surface");
  settle(session);
  CHECK(status.edit.error.empty());
  CHECK(firstBytes(settings.edit.surfacePath, 13) == "ISO-10303-21;");
  CHECK(session.notices().text().find(std::to_string(patches) + " B-spline surfaces") != std::string::npos);
  settings.edit.surfacePath = (folder / "surface.glb").string();
  session.queueCommand("export.surface");
  settle(session);
  CHECK(firstBytes(settings.edit.surfacePath, 4) == "glTF");
  CHECK(session.notices().text().find("watertight") != std::string::npos);
  // An extension no format has: nothing written, the formats named.
  settings.edit.surfacePath = (folder / "surface.xyz").string();
  session.queueCommand("export.surface");
  settle(session);
  CHECK(status.edit.error.find(".step") != std::string::npos);
  CHECK(!std::filesystem::exists(settings.edit.surfacePath));
  // The format box sets the default name's extension.
  settings.edit.surfaceFormat = "iges";
  settle(session);
  CHECK(status.edit.defaultSurfacePath.size() > 4);
  CHECK(status.edit.defaultSurfacePath.substr(status.edit.defaultSurfacePath.size() - 4) == ".igs");
  std::filesystem::remove_all(folder);
}

TEST_CASE("session: after an eigenvector net and Ctrl+Z, the outputs are named after the default model again") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerStatus& status = session.status();
  session.queueCommand("file.default");
  settle(session);
  CHECK(status.edit.defaultSavePath == "default_edited.obj");
  session.queueCommand("model.eigenvector");
  settle(session);
  CHECK(status.file.modelName.rfind("RTS eigenvector", 0) == 0);
  session.queueCommand("edit.undo");  // no vertex drag to undo: back to the default model
  settle(session);
  CHECK(status.file.modelName.rfind("default: ", 0) == 0);
  CHECK(status.edit.defaultSavePath == "default_edited.obj");
  CHECK(status.edit.defaultSurfacePath.rfind("default_c2ps_", 0) == 0);
}

TEST_CASE("session: Save OBJ of an edited Blender file keeps every line of it but the moved vertex's") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerSettings& settings = session.settings();
  ViewerStatus& status = session.status();
  const std::filesystem::path folder = freshDirectory();
  const std::string original = blenderSphere(8, 6);
  const std::string input = openWritten(session, folder, "sphere.obj", original);
  // The file changes on disk after the load: the save still writes the text that was loaded.
  std::ofstream(input, std::ios::binary) << "v 0 0 0\n";

  const int vertex = 5;  // on the first ring; its `v` line is line 10 (0-based 9)
  dragVertex(session.document(), vertex, 20.0f);
  const Point moved = session.model().mesh->points[vertex];
  CHECK(moved != session.document().editor().loadedPoints()[vertex]);
  settings.edit.savePath = (folder / "sphere_edited.obj").string();
  session.queueCommand("edit.save");
  settle(session);
  CHECK(status.edit.error.empty());
  CHECK(session.notices().text().find("1 vertex moved; every other line as in the file") != std::string::npos);
  const std::string saved = readText(settings.edit.savePath);
  checkOnlyVertexLineChanged(original, saved, 4 + size_t(vertex), moved);
  CHECK(loadObj(settings.edit.savePath).points == session.model().mesh->points);

  // A conversion's model (Fig. 14a on a cube file) has other faces: no file text to keep, plain
  // v/f lines of the model shown.
  openWritten(session, folder, "cube.obj",
              "o Cube\nv -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\nvt 0 0\n"
              "f 4/1 3/1 2/1 1/1\nf 5/1 6/1 7/1 8/1\nf 1/1 2/1 6/1 5/1\nf 2/1 3/1 7/1 6/1\nf 3/1 4/1 8/1 7/1\nf 4/1 1/1 5/1 8/1\n");
  session.queueCommand("model.ev-to-polar");
  settle(session);
  REQUIRE(session.model().mesh->faceCount() != 6);
  session.queueCommand("edit.save");
  settle(session);
  CHECK(status.edit.error.empty());
  CHECK(session.notices().text().find("every other line as in the file") == std::string::npos);
  const std::string converted = readText(settings.edit.savePath);
  CHECK(converted.find("vt ") == std::string::npos);
  const PolyMesh back = loadObj(settings.edit.savePath);
  CHECK(back.faceVerts == session.model().mesh->faceVerts);
  CHECK(back.points == session.model().mesh->points);
  std::filesystem::remove_all(folder);
}

TEST_CASE("session: Save OBJ of an edited non-manifold file writes it in the file's numbering") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerSettings& settings = session.settings();
  ViewerStatus& status = session.status();
  const std::filesystem::path folder = freshDirectory();
  // Three quads on one edge (vertices 2 and 3): refined split along it (manifold_split.h).
  const std::string original =
      "g fins\nv 0 0 0\nv 0.5 0 0\nv 0.5 0.5 0\nv 0 0.5 0\nv 0.5 0 0.5\nv 0.5 0.5 0.5\nv 0.5 0 -0.5\nv 0.5 0.5 -0.5\n"
      "vt 0 0\nf 1/1 2/1 3/1 4/1\nf 2/1 5/1 6/1 3/1\nf 2/1 7/1 8/1 3/1\n";
  openWritten(session, folder, "fin.obj", original);
  REQUIRE(session.model().mesh->vertexCount() == 8);
  dragVertex(session.document(), 4, -16.0f);
  settings.edit.savePath = (folder / "fin_edited.obj").string();
  session.queueCommand("edit.save");
  settle(session);
  CHECK(status.edit.error.empty());
  checkOnlyVertexLineChanged(original, readText(settings.edit.savePath), 5, session.model().mesh->points[4]);
  std::filesystem::remove_all(folder);
}

TEST_CASE("session: a sphere's K (all > 0) gets a one-sided automatic range over its own values, not +-max") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerSettings& settings = session.settings();
  ViewerStatus& status = session.status();
  REQUIRE(session.apply(session.document().loadMesh(shapes::globe(16, 7), "globe")));
  settings.views[0].level = 3;
  settings.shading.mode = ShadingParams::Mode::Gaussian;
  settle(session);
  REQUIRE(session.surfaces().shown(0) != nullptr);
  const std::vector<double>& k = session.surfaces().shown(0)->samples->gaussian;
  const double lowest = *std::min_element(k.begin(), k.end()), highest = *std::max_element(k.begin(), k.end());
  REQUIRE(lowest > 0.0);
  const ColourInterval range = colourInterval(settings, status);
  CAPTURE(range.low);
  CAPTURE(range.high);
  // [P10, P90] of K: inside [min, max] (the old +-P90 reached down to -P90, all of K on the red end).
  CHECK(range.oneSided());
  CHECK(range.low >= lowest);
  CHECK(range.high <= highest);
  CHECK(range.low < range.high);
  // The map still varies over the sphere: its lowest and highest K differ in colour, and both are
  // on the positive half of the paper's map (not blue).
  const glm::vec3 low = colorMapCpu(settings.shading.colormap, lowest, range), high = colorMapCpu(settings.shading.colormap, highest, range);
  CHECK(glm::length(low - high) > 0.5f);
  CHECK(low.z == 0.0f);
  CHECK(colourRangeNote(settings, status).find("all K > 0: range") == 0);
  // Mixed signs keep the paper's map centred on zero: the mushroom's neck is negative.
  REQUIRE(session.apply(session.document().loadMesh(shapes::mushroom(6), "mushroom")));
  settle(session);
  CHECK_FALSE(colourInterval(settings, status).oneSided());
  CHECK(colourInterval(settings, status).low == -colourInterval(settings, status).high);
  CHECK(colourRangeNote(settings, status).empty());
}

TEST_CASE("session: a pole zoom to rings m..m+2 raises the views to level m+2, or is refused, and a lower level ends it") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerSettings& settings = session.settings();
  ViewerStatus& status = session.status();
  REQUIRE(session.apply(session.document().loadMesh(shapes::globe(8, 5), "globe")));
  settings.views[0].level = 3;
  settle(session);
  // Rings 4..6 at level 3 did not exist: the view went blank. Now the level goes to 6.
  settings.poleInspector.zoomRing = 4;
  settle(session);
  CHECK(settings.poleInspector.zoomRing == 4);
  CHECK(settings.views[0].level == 6);
  CHECK(status.views[0].shownLevel == 6);
  CHECK(session.notices().text().find("level 6 for the pole zoom") == 0);
  // A level under the zoom's rings ends it, saying why.
  settings.views[0].level = 5;
  settle(session);
  CHECK(settings.poleInspector.zoomRing == -1);
  CHECK(session.notices().text().find("pole zoom off: rings 4-6 need level 6") == 0);
  // Deeper than the scheme goes on this model: refused, the level stays.
  const int deepest = status.views[0].deepestLevel;
  settings.poleInspector.zoomRing = deepest;
  settle(session);
  CHECK(settings.poleInspector.zoomRing == -1);
  CHECK(settings.views[0].level == 5);
  CHECK(session.notices().text().find("stops at level " + std::to_string(deepest)) != std::string::npos);
}
