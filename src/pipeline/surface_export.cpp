// The export formats' table (surface_export.h). Each row's writer lives with its format: .bv in
// core/spline/bezierview_export (through patch_export), CAD and tessellations in core/export.
#include "pipeline/surface_export.h"

#include <algorithm>
#include <cctype>
#include <ctime>

#include "core/export/iges_writer.h"
#include "core/export/step_writer.h"
#include "pipeline/patch_export.h"

namespace polarview {

namespace {

std::string writeBv(const std::string& path, const PatchSet& set, const ExportSettings& settings) {
  const BezierViewStats stats = writeBezierViewFile(path, set, settings.source);
  std::string text = std::to_string(stats.total()) + " Bezier patches in " + std::to_string(stats.groups) +
                     " groups (regular " + std::to_string(stats.written[size_t(PatchKind::Regular)]) + ", boundary " +
                     std::to_string(stats.written[size_t(PatchKind::Boundary)]) + ", polar-ring " +
                     std::to_string(stats.written[size_t(PatchKind::PolarRing)]) + ", pole-cap " +
                     std::to_string(stats.written[size_t(PatchKind::PoleCap)]) + " for " +
                     std::to_string(stats.capSectors) + " cap sectors, end-cap " +
                     std::to_string(stats.written[size_t(PatchKind::EndCap)]) + ")";
  if (stats.capSectors > 0) {
    char caps[96];
    std::snprintf(caps, sizeof caps, "; caps within %.2g of the bounding box (at most %d piece%s a cap sector)",
                  stats.capRelativeDeviation(), stats.maxCapSplit, stats.maxCapSplit == 1 ? "" : "s");
    text += caps;
  }
  return text;
}

std::string baseName(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// What the CAD file says about itself: names, the time it is written (UTC) and its unit.
CadFileInfo cadFileInfo(const std::string& path, const ExportSettings& settings) {
  CadFileInfo info;
  info.fileName = baseName(path);
  info.productName = baseName(settings.source);
  info.description = "polarview limit surface: " + settings.schemeLabel + " level " + std::to_string(settings.level) +
                     " of " + info.productName;
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%S", &utc);
  info.timestamp = stamp;
  info.unit = settings.units;
  return info;
}

// A CAD row: the surfaces (refused before anything is written when not finite), then the file.
template <void (*writeFile)(std::ostream&, const CadSurfaceSet&, const CadFileInfo&)>
std::string writeCad(const std::string& path, const PatchSet& set, const ExportSettings& settings) {
  const CadSurfaceSet surfaces = cadSurfaces(set, settings.source);
  const CadFileInfo info = cadFileInfo(path, settings);
  writeStreamAtomically(path, [&](std::ostream& out) { writeFile(out, surfaces, info); });
  std::string units;
  for (const LengthUnitInfo& unit : lengthUnits())
    if (unit.unit == settings.units) units = unit.name;
  return describeCadSurfaces(surfaces) + ", units " + units;
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
      {"bv", {".bv"}, "Bezier patches for BezierView (exact; caps within 1e-7 of the bounding box)", writeBv},
      {"step", {".step", ".stp"}, "STEP AP214 B-spline faces (exact; caps within 1e-7 of the bounding box)", writeCad<writeStep>},
      {"iges", {".igs", ".iges"}, "IGES 5.3 B-spline surfaces, entity 128 (exact; caps within 1e-7 of the bounding box)",
       writeCad<writeIges>},
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
