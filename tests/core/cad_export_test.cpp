// CAD export (core/export): the B-spline surfaces the STEP and IGES writers put in their files, and
// the files' structure read back. Bicubic patches must be the same polynomial as evaluatePatch
// (position, derivatives, K and H by an independent de Boor evaluation); caps stay within 1e-7 of
// the bounding-box diagonal with their row u = 0 on the pole; every control point reads back from
// the files bit for bit; IGES records are 80 columns with consistent sequence numbers and a
// Global section of the 5.3 parameters. OpenCASCADE's reading is tests/cli/cad_occt.sh.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/export/cad_surfaces.h"
#include "core/export/cad_topology.h"
#include "core/export/iges_writer.h"
#include "core/export/step_writer.h"
#include "core/mesh/input_error.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/shapes.h"
#include "core/subdiv/refiner.h"

using namespace polarview;

namespace {

struct Case {
  std::string name;
  PolyMesh mesh;
  Scheme scheme;
  int level;
};

std::vector<Case> cases() {
  const std::string assets = POLARVIEW_ASSET_DIR;
  std::vector<Case> out;
  out.push_back({"cube", shapes::cube(), Scheme::CatmullClark, 2});
  out.push_back({"grid", shapes::grid(4, 3, [](double x, double y) { return 0.3 * x * x - 0.2 * x * y; }), Scheme::CatmullClark, 1});
  out.push_back({"globe n=5", shapes::globe(5, 4), Scheme::RTS, 1});
  for (Scheme s : {Scheme::C2PS, Scheme::RTS, Scheme::BPS}) out.push_back({"default.obj", loadObj(assets + "/default.obj"), s, 2});
  out.push_back({"cube_cc2.obj", loadObj(assets + "/cube_cc2.obj"), Scheme::CatmullClark, 1});
  return out;
}

PatchSet patchesOf(const Case& c) { return extractPatches(Refinement(c.mesh, {c.scheme, c.level, false}, c.name)); }

// K and H from first and second derivatives, the normal along du x dv (patch.h's sign of H).
std::pair<double, double> curvatures(const CadSurfaceDerivatives& d) {
  const Point n = glm::normalize(glm::cross(d.du, d.dv));
  const double E = glm::dot(d.du, d.du), F = glm::dot(d.du, d.dv), G = glm::dot(d.dv, d.dv);
  const double L = glm::dot(d.duu, n), M = glm::dot(d.duv, n), N = glm::dot(d.dvv, n);
  const double det = E * G - F * F;
  return {(L * N - M * M) / det, (E * N - 2 * F * M + G * L) / (2 * det)};
}

CadFileInfo infoWith(CadUnit unit) {
  CadFileInfo info;
  info.fileName = "test.step";
  info.productName = "it's a test";
  info.timestamp = "2026-12-03T18:30:49";
  info.unit = unit;
  return info;
}

// The double an IGES or STEP real denotes ('D' exponents read as 'E').
double readReal(std::string text) {
  for (char& c : text)
    if (c == 'D') c = 'E';
  return std::strtod(text.c_str(), nullptr);
}

}  // namespace

TEST_CASE("cad surfaces: every B-spline patch is written as the same bicubic, derivatives, K and H included") {
  for (const Case& c : cases()) {
    CAPTURE(c.name);
    CAPTURE(int(c.scheme));
    const PatchSet set = patchesOf(c);
    const CadSurfaceSet surfaces = cadSurfaces(set, c.name);
    REQUIRE(surfaces.boxDiagonal > 0.0);
    double worstPosition = 0, worstFirst = 0, worstSecond = 0, worstK = 0, worstH = 0;
    size_t bicubic = 0;
    for (const CadSurface& surface : surfaces.surfaces) {
      if (surface.kind == PatchKind::PoleCap) continue;
      ++bicubic;
      REQUIRE(surface.bezier.degU == 3);
      REQUIRE(surface.bezier.degV == 3);
      for (int a = 0; a <= 4; ++a)
        for (int b = 0; b <= 4; ++b) {
          const double u = a / 4.0, v = b / 4.0;
          const CadSurfaceDerivatives d = evaluateCadSurface(surface, u, v);
          const SurfacePoint p = evaluatePatch(set.patches[surface.patch], u, v);
          const double first = std::max(glm::length(p.du), glm::length(p.dv));
          const double second = std::max({first, glm::length(p.duu), glm::length(p.duv), glm::length(p.dvv)});
          worstPosition = std::max(worstPosition, glm::length(d.position - p.position) / surfaces.boxDiagonal);
          worstFirst = std::max({worstFirst, glm::length(d.du - p.du) / first, glm::length(d.dv - p.dv) / first});
          worstSecond = std::max({worstSecond, glm::length(d.duu - p.duu) / second, glm::length(d.duv - p.duv) / second,
                                  glm::length(d.dvv - p.dvv) / second});
          // K and H need a regular parametrisation (an end cap's corner may have du x dv = 0).
          if (glm::length(glm::cross(p.du, p.dv)) <= 1e-9 * glm::length(p.du) * glm::length(p.dv)) continue;
          const auto [K, H] = curvatures(d);
          const double kappa = std::abs(p.mean) + std::sqrt(std::max(p.mean * p.mean - p.gaussian, 0.0));
          // Relative to the point's own curvature, or the model's scale where it is flat.
          const double flat = 1.0 / surfaces.boxDiagonal;
          worstK = std::max(worstK, std::abs(K - p.gaussian) / std::max({std::abs(p.gaussian), kappa * kappa, flat * flat}));
          worstH = std::max(worstH, std::abs(H - p.mean) / std::max({std::abs(p.mean), kappa, flat}));
        }
    }
    CHECK(bicubic == set.patches.size() - set.count(PatchKind::PoleCap));
    CHECK(worstPosition < 1e-13);
    CHECK(worstFirst < 1e-12);
    CHECK(worstSecond < 1e-11);
    CHECK(worstK < 1e-9);
    CHECK(worstH < 1e-9);
  }
}

TEST_CASE("cad surfaces: cap pieces stay within 1e-7 of the bounding box, tile their sector and start at the pole") {
  for (const Case& c : cases()) {
    const PatchSet set = patchesOf(c);
    if (set.count(PatchKind::PoleCap) == 0) continue;
    CAPTURE(c.name);
    const CadSurfaceSet surfaces = cadSurfaces(set, c.name);
    CHECK(surfaces.capSectors == set.count(PatchKind::PoleCap));
    CHECK(surfaces.capRelativeDeviation() <= 1e-7);
    double worst = 0.0;
    std::map<size_t, int> nextPiece;  // per cap sector: the piece expected next
    for (const CadSurface& surface : surfaces.surfaces) {
      if (surface.kind != PatchKind::PoleCap) continue;
      CHECK(surface.piece == nextPiece[surface.patch]++);
      CHECK(surface.bezier.degU == 5);  // the cap is a quintic in u (patch.h)
      const Patch absolute = withAbsolutePositions(set.patches[surface.patch]);
      for (int j = 0; j <= surface.bezier.degV; ++j) CHECK(surface.bezier.cp[size_t(j)] == absolute.cp[0]);  // the pole p0
      for (int a = 0; a <= 8; ++a)
        for (int b = 0; b <= 8; ++b) {
          const double u = a / 8.0, v = b / 8.0;
          const Point written = evaluateCadSurface(surface, u, v).position;
          worst = std::max(worst, glm::length(written - evaluatePatch(set.patches[surface.patch], u, sectorV(surface, v)).position));
        }
    }
    for (const auto& [patch, pieces] : nextPiece) {
      CAPTURE(patch);
      for (const CadSurface& surface : surfaces.surfaces)
        if (surface.patch == patch) CHECK(surface.pieces == pieces);
    }
    CHECK(worst / surfaces.boxDiagonal <= 1.5e-7);
  }
}

TEST_CASE("cad export: STEP and IGES reals read back as the same double, in the formats' syntax") {
  for (double x : {0.0, 1.0, -2.0, 0.1, 1.0 / 3.0, 1e-7, -1.5e300, 4.9e-324, 123456789012345678.0, 0.9234970745527634}) {
    CAPTURE(x);
    const std::string step = stepReal(x), iges = igesReal(x);
    CHECK(step.find('.') != std::string::npos);
    CHECK(iges.find('.') != std::string::npos);
    CHECK(step.find_first_of("ed") == std::string::npos);
    CHECK(iges.find_first_of("eEd") == std::string::npos);
    CHECK(readReal(step) == x);
    CHECK(readReal(iges) == x);
  }
  CHECK(stepReal(1e-7) == "1.E-07");
  CHECK(igesReal(2.5) == "2.5");
  CHECK(stepString("it's a\\b") == "'it''s a\\\\b'");
  CHECK(igesString("MM") == "2HMM");
}

TEST_CASE("cad export: the STEP file holds every control point bit for bit, one face per surface in one solid, its unit") {
  const Case c = cases()[3];  // default.obj, C2PS level 2: bicubic patches and caps
  const CadSurfaceSet surfaces = cadSurfaces(patchesOf(c), c.name);
  const CadTopology topology = cadTopology(surfaces);
  const std::map<CadUnit, std::string> unitEntity = {
      {CadUnit::Millimetre, "(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))"},
      {CadUnit::Metre, "(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT($,.METRE.))"},
      {CadUnit::Inch, "(CONVERSION_BASED_UNIT('INCH',#2)LENGTH_UNIT()NAMED_UNIT(#3))"}};
  for (const auto& [unit, entity] : unitEntity) {
    std::ostringstream out;
    writeStep(out, surfaces, infoWith(unit));
    const std::string text = out.str();
    CHECK(text.rfind("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(", 0) == 0);
    CHECK(text.find("FILE_NAME('test.step','2026-12-03T18:30:49'") != std::string::npos);
    CHECK(text.find("FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));") != std::string::npos);
    CHECK(text.find("PRODUCT('it''s a test'") != std::string::npos);
    CHECK(text.find(entity) != std::string::npos);
    if (unit == CadUnit::Inch) CHECK(text.find("#2=LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#1)") != std::string::npos);
    CHECK(text.substr(text.size() - 26) == "ENDSEC;\nEND-ISO-10303-21;\n");

    // Entities numbered 1, 2, ... in order; every reference defined.
    std::map<int, std::string> entities;
    std::istringstream lines(text.substr(text.find("DATA;\n") + 6));
    std::string line;
    int expected = 1;
    while (std::getline(lines, line) && line != "ENDSEC;") {
      const size_t equals = line.find('=');
      REQUIRE(line[0] == '#');
      REQUIRE(std::stoi(line.substr(1, equals - 1)) == expected++);
      REQUIRE(line.back() == ';');
      entities[expected - 1] = line.substr(equals + 1, line.size() - equals - 2);
    }
    const std::regex reference("#(\\d+)");
    for (const auto& [id, body] : entities)
      for (auto m = std::sregex_iterator(body.begin(), body.end(), reference); m != std::sregex_iterator(); ++m)
        REQUIRE(entities.count(std::stoi((*m)[1])) == 1);

    // Faces in order, each on its surface, whose control points are the written ones.
    std::vector<int> faces;
    for (const auto& [id, body] : entities)
      if (body.rfind("ADVANCED_FACE(", 0) == 0) faces.push_back(id);
    REQUIRE(faces.size() == surfaces.surfaces.size());
    const std::regex pointValue("CARTESIAN_POINT\\('',\\(([^,]+),([^,]+),([^,)]+)\\)\\)");
    for (size_t k = 0; k < faces.size(); k += 7) {
      std::smatch parts;
      const std::regex faceParts("ADVANCED_FACE\\('[^']*',\\(#(\\d+)\\),#(\\d+),\\.T\\.\\)");
      REQUIRE(std::regex_match(entities[faces[k]], parts, faceParts));
      const int surfaceId = std::stoi(parts[2]);
      const std::string& bspline = entities[surfaceId];
      REQUIRE(bspline.rfind("B_SPLINE_SURFACE_WITH_KNOTS(''," + std::to_string(surfaces.surfaces[k].bezier.degU) + "," +
                                std::to_string(surfaces.surfaces[k].bezier.degV) + ",((",
                            0) == 0);
      size_t n = 0;
      for (auto m = std::sregex_iterator(bspline.begin(), bspline.end(), reference); m != std::sregex_iterator(); ++m, ++n) {
        std::smatch value;
        const std::string& point = entities[std::stoi((*m)[1])];
        REQUIRE(std::regex_match(point, value, pointValue));
        const Point& p = surfaces.surfaces[k].bezier.cp[n];
        CHECK(Point(readReal(value[1]), readReal(value[2]), readReal(value[3])) == p);
      }
      CHECK(n == surfaces.surfaces[k].bezier.cp.size());
      // The face's loop is its sides' pieces (a cap's collapsed side left out, T-junctions split).
      const bool cap = surfaces.surfaces[k].kind == PatchKind::PoleCap;
      const std::string& bound = entities[std::stoi(parts[1])];
      const std::string& loop = entities[std::stoi(bound.substr(bound.find("#") + 1))];
      CHECK(size_t(std::count(loop.begin(), loop.end(), '#')) == topology.loops[k].size());
      CHECK(topology.loops[k].size() >= (cap ? 3u : 4u));
    }
    // A closed model is one solid: one closed shell of every face.
    CHECK(topology.closed());
    size_t solids = 0, closedShells = 0;
    for (const auto& [id, body] : entities) {
      solids += body.rfind("MANIFOLD_SOLID_BREP(", 0) == 0;
      if (body.rfind("CLOSED_SHELL(", 0) == 0) {
        ++closedShells;
        CHECK(size_t(std::count(body.begin(), body.end(), '#')) == faces.size());
      }
      CHECK(body.rfind("OPEN_SHELL(", 0) != 0);
    }
    CHECK(solids == 1);
    CHECK(closedShells == 1);
  }
}

TEST_CASE("cad export: IGES records, sequence numbers, Global section and entity 128 read back") {
  const Case c = cases()[3];
  const CadSurfaceSet surfaces = cadSurfaces(patchesOf(c), c.name);
  std::ostringstream out;
  CadFileInfo info = infoWith(CadUnit::Inch);
  // A file name longer than a record, with delimiters in it: a Hollerith string across records.
  info.fileName = "a, long; name " + std::string(90, 'x') + ",.igs";
  writeIges(out, surfaces, info);
  std::istringstream in(out.str());
  std::map<char, std::vector<std::string>> sections;  // columns 1-72 of each record, by section
  std::string line, order;
  while (std::getline(in, line)) {
    REQUIRE(line.size() == 80);
    const char letter = line[72];
    REQUIRE(std::string("SGDPT").find(letter) != std::string::npos);
    if (order.empty() || order.back() != letter) order += letter;
    sections[letter].push_back(line.substr(0, 72));
    CHECK(std::stoi(line.substr(73)) == int(sections[letter].size()));
  }
  CHECK(order == "SGDPT");
  char terminate[40];
  std::snprintf(terminate, sizeof terminate, "S%7zuG%7zuD%7zuP%7zu", sections['S'].size(), sections['G'].size(),
                sections['D'].size(), sections['P'].size());
  CHECK(sections['T'].at(0).rfind(terminate, 0) == 0);

  // Global: Hollerith strings and plain values, delimited by ',' and ended by ';'.
  std::string global;
  for (const std::string& record : sections['G']) {
    // A record ends at a delimiter (then blank-padded) or runs to column 72 inside a string.
    const std::string trimmed = record.substr(0, record.find_last_not_of(' ') + 1);
    global += (!trimmed.empty() && (trimmed.back() == ',' || trimmed.back() == ';')) ? trimmed : record;
  }
  std::vector<std::string> fields;
  for (size_t k = 0; k < global.size();) {
    size_t h = k;
    while (h < global.size() && std::isdigit(static_cast<unsigned char>(global[h]))) ++h;
    std::string field;
    if (h > k && global[h] == 'H') {
      const size_t length = std::stoul(global.substr(k, h - k));
      field = global.substr(h + 1, length);
      k = h + 1 + length;
    } else {
      const size_t end = global.find_first_of(",;", k);
      field = global.substr(k, end - k);
      k = end;
    }
    fields.push_back(field);
    if (global[k] == ';') break;
    ++k;
  }
  REQUIRE(fields.size() == 26);
  CHECK(fields[0] == ",");
  CHECK(fields[1] == ";");
  CHECK(fields[2] == "it's a test");
  CHECK(fields[3] == info.fileName);
  CHECK(fields[6] == "32");
  CHECK(fields[12] == "1.");   // model space scale
  CHECK(fields[13] == "1");    // inch
  CHECK(fields[14] == "INCH");
  CHECK(fields[17] == "20261203.183049");
  CHECK(readReal(fields[18]) == doctest::Approx(1e-7 * surfaces.boxDiagonal));
  CHECK(readReal(fields[19]) >= std::max(std::abs(surfaces.boxMax.z), std::abs(surfaces.boxMin.z)));
  CHECK(fields[22] == "11");   // IGES 5.3

  // Directory: two records per surface pointing at its parameter records, which read back exactly.
  REQUIRE(sections['D'].size() == 2 * surfaces.surfaces.size());
  for (size_t k = 0; k < surfaces.surfaces.size(); k += 5) {
    const std::string& first = sections['D'][2 * k];
    const std::string& second = sections['D'][2 * k + 1];
    CHECK(std::stoi(first.substr(0, 8)) == 128);
    const int start = std::stoi(first.substr(8, 8)), count = std::stoi(second.substr(24, 8));
    std::string parameters;
    for (int r = start; r < start + count; ++r) {
      const std::string& record = sections['P'].at(size_t(r - 1));
      CHECK(std::stoi(record.substr(64, 8)) == int(2 * k + 1));
      parameters += record.substr(0, 64);
    }
    std::vector<double> values;
    std::istringstream tokens(parameters.substr(0, parameters.find(';')));
    std::string token;
    while (std::getline(tokens, token, ',')) values.push_back(readReal(token));
    const BezierPatch& b = surfaces.surfaces[k].bezier;
    const size_t knots = size_t(2 * (b.degU + 1) + 2 * (b.degV + 1)), points = b.cp.size();
    REQUIRE(values.size() == 10 + knots + points + 3 * points + 4);
    CHECK(values[0] == 128);
    CHECK(values[1] == b.degU);
    CHECK(values[3] == b.degU);
    CHECK(values[7] == 1);  // polynomial
    for (size_t w = 0; w < points; ++w) CHECK(values[10 + knots + w] == 1.0);
    for (int j = 0; j <= b.degV; ++j)
      for (int i = 0; i <= b.degU; ++i) {
        const size_t at = 10 + knots + points + 3 * size_t(i + (b.degU + 1) * j);
        CHECK(Point(values[at], values[at + 1], values[at + 2]) == b.cp[size_t((b.degV + 1) * i + j)]);
      }
  }
}

TEST_CASE("cad export: a non-finite control point is refused before anything is made") {
  PatchSet set = extractPatches(Refinement(shapes::torus(6, 5), {Scheme::CatmullClark, 0, false}, "torus"));
  set.patches[3].cp[7].y = std::nan("");
  CHECK_THROWS_AS(cadSurfaces(set, "torus"), InputError);
  set.patches[3].cp[7].y = 0.0;
  set.patches[3].cp[5].y = 1e308;  // finite, but its Bezier conversion (16 times it) overflows
  CHECK_THROWS_AS(cadSurfaces(set, "torus"), InputError);
}
