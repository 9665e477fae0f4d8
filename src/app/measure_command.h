// `polarview measure IN.obj`: area, enclosed volume, centroid and inertia of the limit surface.
// Its options: `polarview measure --help`.
#pragma once

#include "app/command_args.h"

namespace polarview::cli {

CommandParser measureCommand();

}  // namespace polarview::cli
