// IGES 5.3 files of B-spline surfaces (docs/formats.md, STEP and IGES).
//
// LAYOUT. 80-column ASCII records, each ending in its section letter (column 73) and its sequence
// number within the section (columns 74-80):
//  * Start (S): one line naming the file's content.
//  * Global (G): the 26 parameters of IGES 5.3 section 2.2.4, ',' and ';' as delimiters, units
//    flag and name (mm: 2 'MM', m: 6 'M', inch: 1 'INCH'), model scale 1.0, version flag 11 (5.3),
//    resolution 1e-7 of the bounding-box diagonal, the largest absolute coordinate.
//  * Directory Entry (D): two records per entity, ten 8-column fields each.
//  * Parameter Data (P): each entity's parameters in columns 1-64, its directory entry's sequence
//    number in columns 66-72.
//  * Terminate (T): the number of records of each section.
// One entity 128 (rational B-spline surface, form 0) per CadSurface, in order, polynomial flag
// set (all weights 1), open and non-periodic, knots 0 and 1 of multiplicity degree + 1, parameter
// range [0,1]^2; its label is "CAP"/"RING"/... and its subscript the patch index. Reals are the
// shortest text that reads back as the same double, with a 'D' exponent where there is one.
#pragma once

#include <iosfwd>
#include <string>

#include "core/export/cad_file_info.h"
#include "core/export/cad_surfaces.h"

namespace polarview {

// Writes the IGES file of `set` to `out` (layout above). [O(surfaces)]
void writeIges(std::ostream& out, const CadSurfaceSet& set, const CadFileInfo& info);

// An IGES string constant: Hollerith "<length>H<text>" (bytes outside printable ASCII as '_'). [O(text)]
std::string igesString(const std::string& text);

// An IGES real: shortestDouble with a decimal point and a 'D' exponent ("1.D-07"). [O(1)]
std::string igesReal(double value);

}  // namespace polarview
