// STEP (ISO 10303-21) files of B-spline surfaces, schema AP214 (AUTOMOTIVE_DESIGN), as OpenCASCADE
// reads them into valid faces (docs/formats.md, STEP and IGES).
//
// LAYOUT. One product (PRODUCT, PRODUCT_DEFINITION, ..., SHAPE_DEFINITION_REPRESENTATION) whose
// shape is a MANIFOLD_SURFACE_SHAPE_REPRESENTATION holding one SHELL_BASED_SURFACE_MODEL with one
// OPEN_SHELL of ADVANCED_FACEs, one per CadSurface, in order. Faces are not sewn: each has its own
// vertices and edges (T-junctions between levels would need split edges). A face's surface is a
// B_SPLINE_SURFACE_WITH_KNOTS (knots 0 and 1, multiplicity degree + 1); its outer bound is the
// loop (0,0) -> (1,0) -> (1,1) -> (0,1) of its boundary iso-curves, each an EDGE_CURVE on a
// SURFACE_CURVE: the boundary row or column of control points as a B_SPLINE_CURVE_WITH_KNOTS plus
// the PCURVE (a LINE in the parameter square). A cap piece's collapsed edge u = 0 is left out (3
// edges meeting at the pole's vertex), as OpenCASCADE writes a degenerate edge itself.
// The faces are named "<kind> level L [ring M] patch P [piece I/N]" (kind as patchKindName).
// Numbers: shortest round-trip text (std::to_chars), so the file holds the exact doubles.
// Units: the context's length unit is SI_UNIT(.MILLI.,.METRE.), SI_UNIT($,.METRE.) or
// CONVERSION_BASED_UNIT('INCH', 25.4 mm); the uncertainty is 1e-7 of the bounding-box diagonal.
#pragma once

#include <iosfwd>

#include "core/export/cad_file_info.h"
#include "core/export/cad_surfaces.h"

namespace polarview {

// Writes the STEP file of `set` to `out` (layout above). [O(surfaces)]
void writeStep(std::ostream& out, const CadSurfaceSet& set, const CadFileInfo& info);

// A STEP string literal of `text`: quotes doubled, backslashes doubled, other bytes outside
// printable ASCII replaced by '_'. [O(text)]
std::string stepString(const std::string& text);

// A STEP REAL: shortestDouble with a decimal point and an upper-case exponent ("1.E-07"). [O(1)]
std::string stepReal(double value);

}  // namespace polarview
