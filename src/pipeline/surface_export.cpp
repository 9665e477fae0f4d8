// The export formats' table (surface_export.h). Each row's writer lives with its format: .bv in
// core/spline/bezierview_export, CAD and tessellations in core/export; all write to a stream, and
// writeSurfaceFile makes the file (atomic_file.h).
#include "pipeline/surface_export.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <memory>
#include <ostream>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/export/iges_writer.h"
#include "core/mesh/atomic_file.h"
#include "core/mesh/input_error.h"
#include "core/export/step_writer.h"
#include "core/export/tessellation_writers.h"
#include "pipeline/memory_budget.h"
#include "pipeline/shading.h"

namespace polarview {

namespace {

// .bv: its stats come of writing it (the caps' pieces are fitted as they are written).
ExportWriter prepareBv(const PatchSet& set, const ExportSettings& settings) {
  checkFinitePatches(set, settings.source);
  return [&set, source = settings.source](std::ostream& out) -> ExportStats {
    return writeBezierView(out, set, BezierViewOptions{}, source);
  };
}

// [SECTION] tessellations (PLY, glb): the core writes, the colours come from here

// The viewer's default automatic range takes the 10th and 90th percentiles of K by area
// (ColourRangeSettings::quantile, session/viewer_settings.h).
constexpr float kColourQuantile = 0.90f;

// K per vertex with the area it stands for (a third of its triangles'), end caps left out where
// other patches exist, as the viewer's samples (sampleCurvatures): their K at a Catmull-Clark
// extraordinary vertex says nothing about the shape's scale. Non-finite values are left out (the
// writers refuse them, naming the vertex).
void curvatureByArea(const Tessellation& mesh, const PatchSet& set, std::vector<double>& values, std::vector<double>& weights) {
  // Areas in units of the bounding box (a model of 1e140 has areas past double's range).
  Point low(std::numeric_limits<double>::max()), high(-std::numeric_limits<double>::max());
  for (const Point& p : mesh.positions) low = glm::min(low, p), high = glm::max(high, p);
  const Point size = high - low;
  const double unit = std::max({size.x, size.y, size.z, std::numeric_limits<double>::min()});
  std::vector<double> area(mesh.positions.size(), 0.0);
  for (const auto& t : mesh.triangles) {
    const Point a = mesh.positions[t[0]] / unit;
    const double third = glm::length(glm::cross(mesh.positions[t[1]] / unit - a, mesh.positions[t[2]] / unit - a)) / 6.0;
    for (uint32_t v : t) area[v] += third;
  }
  const bool onlyEndCaps = set.count(PatchKind::EndCap) == set.patches.size();
  for (size_t v = 0; v < area.size(); ++v) {
    if (!onlyEndCaps && set.patches[mesh.sources[v].patch].kind == PatchKind::EndCap) continue;
    if (!std::isfinite(mesh.gaussian[v]) || !std::isfinite(area[v])) continue;  // the writer refuses them
    values.push_back(mesh.gaussian[v]);
    weights.push_back(area[v]);
  }
}

// Peak memory of a tessellation a vertex (about N^2 a patch): the welded mesh, its hash, colours and
// the file's buffer. Measured: C2PS level 6 of assets/default.obj at --samples 64, 16.9 million
// vertices, 5.13 GB peak RSS (304 bytes a vertex).
constexpr double kBytesPerTessellationVertex = 320.0;

}  // namespace

void checkTessellationBudget(const PatchSet& set, int samples, size_t memoryBudget, const std::string& source) {
  const auto bytesAt = [&](int n) { return double(set.patches.size()) * n * n * kBytesPerTessellationVertex; };
  const double budget = double(memoryBudgetBytes(memoryBudget));
  if (bytesAt(samples) <= budget) return;
  int fitting = samples;
  while (fitting > 1 && bytesAt(fitting) > budget) --fitting;
  const std::string advice = bytesAt(fitting) <= budget ? "--samples " + std::to_string(fitting) + " fits"
                                                        : "a lower level is needed";
  char text[256];
  std::snprintf(text, sizeof text,
                "a tessellation of %zu patches with --samples %d needs about %.3g GB, over the memory budget of %.3g GB (%s)",
                set.patches.size(), samples, bytesAt(samples) / 1e9, budget / 1e9, advice.c_str());
  throw BudgetRefusal(source, 0, text);
}

TessellationColouring colourTessellation(const Tessellation& mesh, const PatchSet& set) {
  std::vector<double> values, weights;
  curvatureByArea(mesh, set, values, weights);
  TessellationColouring colouring;
  colouring.range = values.empty() ? ColourInterval{} : colourStatistics(values, weights, kColourQuantile).automaticInterval();
  const ShadingParams::ColorMap map = ShadingParams{}.colormap;
  colouring.colours.reserve(mesh.positions.size());
  for (double k : mesh.gaussian) colouring.colours.push_back(colorMapCpu(map, k, colouring.range));
  return colouring;
}

namespace {

// Tessellates `set`, colours K as the viewer's default Gaussian view does and makes the file's bytes
// with `bytesOf` (which refuses non-finite values), all before the file is opened.
ExportWriter prepareTessellation(const PatchSet& set, const ExportSettings& settings,
                                 std::string (*bytesOf)(const Tessellation&, const TessellationFileInfo&)) {
  checkTessellationBudget(set, settings.samples, settings.memoryBudget, settings.source);
  const Tessellation mesh = tessellatePatchSet(set, settings.samples);
  TessellationColouring coloured = colourTessellation(mesh, set);
  const ColourInterval range = coloured.range;
  TessellationFileInfo info{settings.source, settings.schemeLabel, settings.level, std::move(coloured.colours), {}};
  char colouring[96];
  std::snprintf(colouring, sizeof colouring, "K through the paper colour map over [%.6g, %.6g]", range.low, range.high);
  info.colouring = colouring;
  std::string bytes = bytesOf(mesh, info);

  TessellationStats stats;
  stats.vertices = mesh.positions.size();
  stats.triangles = mesh.triangles.size();
  stats.edges = countTessellationEdges(mesh);
  if (!mesh.gaussian.empty()) {
    const auto [lowest, highest] = std::minmax_element(mesh.gaussian.begin(), mesh.gaussian.end());
    stats.gaussianLow = *lowest;
    stats.gaussianHigh = *highest;
  }
  stats.colours = range;
  return [bytes = std::move(bytes), stats](std::ostream& out) -> ExportStats {
    out.write(bytes.data(), std::streamsize(bytes.size()));
    return stats;
  };
}

ExportWriter preparePly(const PatchSet& set, const ExportSettings& settings) {
  return prepareTessellation(set, settings, plyBytes);
}

ExportWriter prepareGlb(const PatchSet& set, const ExportSettings& settings) {
  return prepareTessellation(set, settings, glbBytes);
}

// [SECTION] CAD files (STEP, IGES): B-spline surfaces, written by the core

std::string baseName(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// The time CAD files say they were written: now, or SOURCE_DATE_EPOCH (seconds since 1970, UTC)
// where it is set, so that the same export makes the same bytes (reproducible-builds.org's
// convention); a malformed value is refused rather than ignored.
std::time_t fileTime() {
  const char* epoch = std::getenv("SOURCE_DATE_EPOCH");
  if (!epoch) return std::time(nullptr);
  const std::string text = epoch;
  // At most year 9999: the stamp has four digits for the year.
  const bool digits = !text.empty() && text.size() <= 12 && text.find_first_not_of("0123456789") == std::string::npos;
  const long long seconds = digits ? std::stoll(text) : -1;
  if (!digits || seconds > 253402300799LL)
    throw InputError("SOURCE_DATE_EPOCH", 0, "expects whole seconds since 1970-01-01 UTC (up to 9999-12-31), got '" + text + "'");
  return std::time_t(seconds);
}

// What the CAD file says about itself: names, the time it is written (UTC) and its unit.
CadFileInfo cadFileInfo(const ExportSettings& settings) {
  CadFileInfo info;
  info.fileName = settings.fileName;
  info.productName = baseName(settings.source);
  info.description = "polarview limit surface: " + settings.schemeLabel + " level " + std::to_string(settings.level) +
                     " of " + info.productName;
  const std::time_t when = fileTime();
  std::tm utc{};
  gmtime_r(&when, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%S", &utc);
  info.timestamp = stamp;
  info.unit = settings.units;
  return info;
}

CadStats cadStats(const CadSurfaceSet& surfaces, const ExportSettings& settings) {
  CadStats stats;
  stats.surfaces = surfaces.surfaces.size();
  stats.written = surfaces.written;
  stats.capSectors = surfaces.capSectors;
  stats.capRelativeDeviation = surfaces.capRelativeDeviation();
  stats.units = settings.units;
  return stats;
}

// The IGES row: the surfaces (refused before the file is opened when not finite), then the file.
ExportWriter prepareIges(const PatchSet& set, const ExportSettings& settings) {
  auto surfaces = std::make_shared<const CadSurfaceSet>(cadSurfaces(set, settings.source));
  return [surfaces, info = cadFileInfo(settings), stats = cadStats(*surfaces, settings)](std::ostream& out) -> ExportStats {
    writeIges(out, *surfaces, info);
    return stats;
  };
}

// The STEP row: the surfaces and their shell, then the file.
ExportWriter prepareStep(const PatchSet& set, const ExportSettings& settings) {
  auto surfaces = std::make_shared<const CadSurfaceSet>(cadSurfaces(set, settings.source));
  auto topology = std::make_shared<const CadTopology>(cadTopology(*surfaces));
  CadStats stats = cadStats(*surfaces, settings);
  stats.shell = true;
  stats.closed = topology->closed();
  stats.edges = topology->edges.size();
  stats.freeEdges = topology->freeEdges;
  stats.tJunctionSplits = topology->tJunctionSplits;
  return [surfaces, topology, info = cadFileInfo(settings), stats](std::ostream& out) -> ExportStats {
    writeStep(out, *surfaces, *topology, info);
    return stats;
  };
}

// "(regular a, boundary b, polar-ring c, pole-cap d for e cap sectors, end-cap f)".
std::string kindCounts(const std::array<size_t, 5>& written, size_t capSectors) {
  auto count = [&](PatchKind kind) { return std::to_string(written[size_t(kind)]); };
  return "(regular " + count(PatchKind::Regular) + ", boundary " + count(PatchKind::Boundary) + ", polar-ring " +
         count(PatchKind::PolarRing) + ", pole-cap " + count(PatchKind::PoleCap) + " for " + std::to_string(capSectors) +
         " cap sectors, end-cap " + count(PatchKind::EndCap) + ")";
}

std::string summary(const BezierViewStats& stats) {
  std::string text = std::to_string(stats.total()) + " Bezier patches in " + std::to_string(stats.groups) + " groups " +
                     kindCounts(stats.written, stats.capSectors);
  if (stats.capSectors > 0) {
    char caps[96];
    std::snprintf(caps, sizeof caps, "; caps within %.2g of the bounding box (at most %d piece%s a cap sector)",
                  stats.capRelativeDeviation(), stats.maxCapSplit, stats.maxCapSplit == 1 ? "" : "s");
    text += caps;
  }
  return text;
}

std::string summary(const TessellationStats& stats) {
  const TessellationEdges& edges = stats.edges;
  std::string closure = edges.watertight() ? "watertight" : std::to_string(edges.boundary) + " boundary edges";
  if (edges.nonManifold + edges.misoriented > 0)  // a degenerate input (a part of it collapsed to a point)
    closure += ", not a manifold: " + std::to_string(edges.nonManifold + edges.misoriented) +
               " edges used by three or more triangles or twice the same way";
  char text[160];
  std::snprintf(text, sizeof text, ", K in [%.6g, %.6g]; colours over [%.6g, %.6g]", stats.gaussianLow, stats.gaussianHigh,
                stats.colours.low, stats.colours.high);
  return std::to_string(stats.vertices) + " vertices, " + std::to_string(stats.triangles) + " triangles, " + closure + text;
}

std::string summary(const CadStats& stats) {
  std::string text = std::to_string(stats.surfaces) + " B-spline surfaces " + kindCounts(stats.written, stats.capSectors);
  if (stats.capSectors > 0) {
    char caps[64];
    std::snprintf(caps, sizeof caps, "; caps within %.2g of the bounding box", stats.capRelativeDeviation);
    text += caps;
  }
  if (stats.shell && stats.closed)
    text += "; one closed shell (a solid) of " + std::to_string(stats.edges) + " shared edges, " +
            std::to_string(stats.tJunctionSplits) + " split at T-junctions";
  else if (stats.shell)
    text += "; one open shell of " + std::to_string(stats.edges) + " edges, " + std::to_string(stats.freeEdges) + " free";
  for (const LengthUnitInfo& unit : lengthUnits())
    if (unit.unit == stats.units) text += std::string(", units ") + unit.name;
  return text;
}

std::string lowered(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

}  // namespace

const std::vector<LengthUnitInfo>& lengthUnits() {
  static const std::vector<LengthUnitInfo> units = {
      {LengthUnit::Millimetre, "mm"}, {LengthUnit::Metre, "m"}, {LengthUnit::Inch, "inch"}};
  return units;
}

const std::vector<ExportFormat>& exportFormats() {
  static const std::vector<ExportFormat> formats = {
      {"bv", {".bv"}, "Bezier patches for BezierView (exact; caps within 1e-7 of the bounding box)", false, prepareBv},
      {"ply", {".ply"}, "watertight triangle mesh, binary PLY: exact normal, K and H per vertex, colours of K", true, preparePly},
      {"glb", {".glb"}, "watertight triangle mesh, glTF 2.0 binary: exact normal, K and H per vertex, colours of K", true, prepareGlb},
      {"step", {".step", ".stp"}, "STEP AP214 B-spline faces sewn into one shell, a solid where closed (exact; caps within 1e-7 of the bounding box)", false, prepareStep},
      {"iges", {".igs", ".iges"}, "IGES 5.3 B-spline surfaces, entity 128 (exact; caps within 1e-7 of the bounding box)", false,
       prepareIges},
  };
  return formats;
}

const ExportFormat* exportFormatNamed(const std::string& name) {
  for (const ExportFormat& format : exportFormats())
    if (lowered(name) == format.name) return &format;
  return nullptr;
}

const ExportFormat* exportFormatForPath(const std::string& path) {
  const std::string lower = lowered(path);
  for (const ExportFormat& format : exportFormats())
    for (const std::string& extension : format.extensions)
      if (lower.size() > extension.size() && lower.compare(lower.size() - extension.size(), extension.size(), extension) == 0)
        return &format;
  return nullptr;
}

std::string exportSummary(const ExportStats& stats) {
  return std::visit([](const auto& s) { return summary(s); }, stats);
}

ExportStats writeSurfaceFile(const std::string& path, const PatchSet& set, const ExportFormat& format, ExportSettings settings) {
  if (settings.fileName.empty()) settings.fileName = baseName(path);
  const ExportWriter write = format.prepare(set, settings);  // refusals come before the file is opened
  ExportStats stats;
  writeFileAtomically(path, [&](std::ostream& out) { stats = write(out); });
  return stats;
}

std::string exportFormatNames() {
  std::string names;
  for (const ExportFormat& format : exportFormats()) names += std::string(names.empty() ? "" : ", ") + format.name;
  return names;
}

std::string exportFormatExtensions() {
  std::string names;
  for (const ExportFormat& format : exportFormats())
    for (const std::string& extension : format.extensions) names += (names.empty() ? "" : ", ") + extension;
  return names;
}

}  // namespace polarview
