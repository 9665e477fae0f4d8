// What a CAD file (STEP, IGES) says about itself besides its geometry.
#pragma once

#include <string>

namespace polarview {

// The length unit the file names. Coordinates are written as they are: the unit says what they
// mean, it does not scale them.
enum class CadUnit { Millimetre, Metre, Inch };

struct CadFileInfo {
  std::string fileName = "surface";  // the output's base name (headers)
  std::string productName = "polarview surface";  // the product the shape belongs to (the input's name)
  std::string description = "polarview limit surface";  // one line: scheme, level, source
  std::string timestamp = "2000-01-01T00:00:00";  // ISO 8601, UTC (STEP FILE_NAME; IGES converts it)
  CadUnit unit = CadUnit::Millimetre;
};

}  // namespace polarview
