// The formats the limit surface is written in, one table: `polarview export` (format from the
// output's extension, --format to override) and the viewer's "Edit and export" read it. Each row
// writes a PatchSet atomically (nothing is left behind on any error) and says what it wrote.
#pragma once

#include <string>
#include <vector>

#include "core/export/cad_file_info.h"
#include "core/spline/patch_extraction.h"

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
};

struct ExportFormat {
  const char* name;                     // --format NAME: "bv", "step", "iges", "ply", "glb"
  std::vector<std::string> extensions;  // ".bv"; ".step", ".stp"; ...
  const char* description;              // one line of help
  bool curvature;                       // holds curvature: the model must be at least kSmallestModelExtent
  // Writes `set` to `path` (atomically) and returns what it wrote, for "PATH: <summary>". Throws
  // InputError (bad data, named after settings.source) or std::runtime_error (I/O).
  std::string (*write)(const std::string& path, const PatchSet& set, const ExportSettings& settings);
};
const std::vector<ExportFormat>& exportFormats();

// The row named `name`, or whose extension `path` ends with (case-insensitive); nullptr if none.
const ExportFormat* exportFormatNamed(const std::string& name);
const ExportFormat* exportFormatForPath(const std::string& path);
// "bv, step, iges, ply, glb" and ".bv, .step, .stp, ..." for messages and help.
std::string exportFormatNames();
std::string exportFormatExtensions();

}  // namespace polarview
