// STEP (ISO 10303-21) files of B-spline surfaces, schema AP214 (AUTOMOTIVE_DESIGN), as OpenCASCADE
// reads them into valid faces (docs/formats.md, STEP and IGES).
//
// LAYOUT. One product (PRODUCT, PRODUCT_DEFINITION, ..., SHAPE_DEFINITION_REPRESENTATION) whose
// shape is the shell of cadTopology (core/export/cad_topology.h): the surfaces' shared vertices and
// edges, T-junctions split. A closed shell is a solid: ADVANCED_BREP_SHAPE_REPRESENTATION holding
// a MANIFOLD_SOLID_BREP of one CLOSED_SHELL (faces written reversed, same_sense and bound .F., where
// the surfaces' normals point inwards); an open one is a MANIFOLD_SURFACE_SHAPE_REPRESENTATION
// holding a SHELL_BASED_SURFACE_MODEL of one OPEN_SHELL. One ADVANCED_FACE per CadSurface, in order
// (a surface shrunk to a point, which bounds nothing, is left out). A face's surface is a
// B_SPLINE_SURFACE_WITH_KNOTS (knots 0 and 1, multiplicity degree + 1); its outer bound is the loop
// of its sides' pieces, counter-clockwise in (u, v) from (0,0). Each EDGE_CURVE joins two
// VERTEX_POINTs by a SURFACE_CURVE: the side piece's control points as a B_SPLINE_CURVE_WITH_KNOTS
// (a whole side reuses the surface's CARTESIAN_POINTs) with one PCURVE per face using it (a LINE in
// that face's parameter square, its parameter the curve's). A shared edge is used twice, with
// opposite orientation. A cap piece's collapsed edge u = 0 is left out (3 edges meeting at the
// pole's vertex), as OpenCASCADE writes a degenerate edge itself.
// The faces are named "<kind> level L [ring M] patch P [piece I/N]" (kind as patchKindName).
// Numbers: shortest round-trip text (std::to_chars), so the file holds the exact doubles.
// Units: the context's length unit is SI_UNIT(.MILLI.,.METRE.), SI_UNIT($,.METRE.) or
// CONVERSION_BASED_UNIT('INCH', 25.4 mm); the uncertainty is 1e-7 of the bounding-box diagonal.
#pragma once

#include <iosfwd>

#include "core/export/cad_file_info.h"
#include "core/export/cad_surfaces.h"
#include "core/export/cad_topology.h"

namespace polarview {

// Writes the STEP file of `set` to `out` (layout above); `topology` is cadTopology(set). [O(surfaces)]
void writeStep(std::ostream& out, const CadSurfaceSet& set, const CadTopology& topology, const CadFileInfo& info);
// The same, the topology made here. [O(surfaces * log surfaces)]
void writeStep(std::ostream& out, const CadSurfaceSet& set, const CadFileInfo& info);

// A STEP string literal of `text`: quotes doubled, backslashes doubled, other bytes outside
// printable ASCII replaced by '_'. [O(text)]
std::string stepString(const std::string& text);

// A STEP REAL: shortestDouble with a decimal point and an upper-case exponent ("1.E-07"). [O(1)]
std::string stepReal(double value);

}  // namespace polarview
