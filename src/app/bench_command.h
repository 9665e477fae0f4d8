// `polarview bench IN.obj`: timings and memory; speed-ups over the OpenSubdiv peer only where both
// computed the same (Catmull-Clark) surface. Its options: `polarview bench --help`.
#pragma once

#include "app/command_args.h"

namespace polarview::cli {

CommandParser benchCommand();

}  // namespace polarview::cli
