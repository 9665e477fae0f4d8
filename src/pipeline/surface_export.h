// The formats the limit surface is written in, one table: `polarview export` (format from the
// output's extension, --format to override) and the viewer's "Edit and export" read it. Each row
// prepares a PatchSet's file (refusing bad data first) and writes it to a stream, saying what it
// wrote; writeSurfaceFile makes the file atomically (nothing is left behind on any error) and
// exportSummary says it in a line.
#pragma once

#include <array>
#include <functional>
#include <iosfwd>
#include <string>
#include <variant>
#include <vector>

#include "core/export/cad_file_info.h"
#include "core/export/tessellation.h"
#include "core/spline/bezierview_export.h"
#include "core/spline/patch_extraction.h"
#include "pipeline/shading.h"

namespace polarview {

// The length unit a CAD file names (STEP, IGES; core/export/cad_file_info.h): coordinates are
// written as they are, the unit says what they mean.
using LengthUnit = CadUnit;
struct LengthUnitInfo {
  LengthUnit unit;
  const char* name;  // as --units takes it: "mm", "m", "inch"
};
const std::vector<LengthUnitInfo>& lengthUnits();

// What a writer needs besides the patches.
struct ExportSettings {
  std::string source = "<patches>";  // the input's name: in file headers and error messages
  std::string schemeLabel;           // "C2PS", ... (file headers)
  int level = 0;                     // the refinement level the patches come from (file headers)
  LengthUnit units = LengthUnit::Millimetre;
  int samples = 8;                   // tessellations (PLY, glb): segments along each patch edge
  size_t memoryBudget = 0;           // bytes a tessellation may take (0: memory_budget.h's default)
  std::string fileName;              // the name CAD files give themselves (writeSurfaceFile: the path's)
};

// What a tessellation file holds (PLY, glb).
struct TessellationStats {
  size_t vertices = 0, triangles = 0;
  TessellationEdges edges;                      // boundary and non-manifold edges (watertight: none)
  double gaussianLow = 0.0, gaussianHigh = 0.0;  // K over the vertices
  ColourInterval colours;                       // the K the colour map spans
};

// The colours the tessellation files (PLY, glb) give their vertices: K through the viewer's default
// colour map over its automatic range (the 10th and 90th percentiles of K by area, end caps left
// out). The Python module's tessellate() hands out the same. [O(vertices log vertices)]
struct TessellationColouring {
  ColourInterval range;             // the K the colour map spans
  std::vector<glm::vec3> colours;   // per vertex, sRGB in [0, 1]
};
TessellationColouring colourTessellation(const Tessellation& mesh, const PatchSet& set);

// Refuses (BudgetRefusal named after `source`, before anything is allocated) a tessellation of `set`
// with `samples` segments a patch edge whose estimate exceeds `memoryBudget` bytes (0: the default
// of memory_budget.h), naming the densest --samples that fits. [O(1)]
void checkTessellationBudget(const PatchSet& set, int samples, size_t memoryBudget, const std::string& source);

// What a CAD file holds (STEP, IGES).
struct CadStats {
  size_t surfaces = 0;
  std::array<size_t, 5> written{};  // surfaces per PatchKind (caps: the pieces)
  size_t capSectors = 0;
  double capRelativeDeviation = 0.0;  // the caps' distance from the limit / bounding-box diagonal
  LengthUnit units = LengthUnit::Millimetre;
  // STEP: the faces' shell (core/export/cad_topology.h); IGES writes separate surfaces.
  bool shell = false;
  bool closed = false;          // one closed shell: a solid
  size_t edges = 0, freeEdges = 0, tJunctionSplits = 0;
};

// What a format's writer wrote: .bv, a tessellation, or CAD surfaces.
using ExportStats = std::variant<BezierViewStats, TessellationStats, CadStats>;
// A prepared file's writer: writes its bytes to the stream and says what they hold. It refers to the
// PatchSet it was prepared from, which must outlive it.
using ExportWriter = std::function<ExportStats(std::ostream&)>;

struct ExportFormat {
  const char* name;                     // --format NAME: "bv", "step", "iges", "ply", "glb"
  std::vector<std::string> extensions;  // ".bv"; ".step", ".stp"; ...
  const char* description;              // one line of help
  bool curvature;                       // holds curvature: the model must be at least kSmallestModelExtent
  // Makes what the file holds from `set`: refuses bad data (InputError named after settings.source)
  // and tessellations over the memory budget (BudgetRefusal) before any file is opened, and returns
  // the writer of its bytes to a stream (writeSurfaceFile runs it into the file).
  ExportWriter (*prepare)(const PatchSet& set, const ExportSettings& settings);
};
const std::vector<ExportFormat>& exportFormats();

// Writes `set` in `format` to `path` atomically (settings.fileName: the path's base name when
// empty): prepared first, so a refusal leaves the path untouched; then InputError(path, 0, ...) when
// the file cannot be made or written. [O(output)]
ExportStats writeSurfaceFile(const std::string& path, const PatchSet& set, const ExportFormat& format, ExportSettings settings);
// One line of what was written, for "wrote PATH: <summary>": "357 Bezier patches in 3 groups
// (regular a, ...)", "12345 vertices, 24680 triangles, watertight, K in [a, b]; ...", "357 B-spline
// surfaces (...), units mm".
std::string exportSummary(const ExportStats& stats);

// The row named `name`, or whose extension `path` ends with (case-insensitive); nullptr if none.
const ExportFormat* exportFormatNamed(const std::string& name);
const ExportFormat* exportFormatForPath(const std::string& path);
// "bv, step, iges, ply, glb" and ".bv, .step, .stp, ..." for messages and help.
std::string exportFormatNames();
std::string exportFormatExtensions();

}  // namespace polarview
