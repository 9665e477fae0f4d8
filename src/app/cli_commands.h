// The command-line subcommands of `polarview` that need no window: refine, export, continuity, convert, info,
// pole, shape, spectrum (bench: bench_command.h). Each is an option table and a body (command_args.h): main.cpp's
// command table runs them through runGuarded, which gives the exit code: 0 success, 1 bad input
// (one line "polarview: FILE:LINE: what" on stderr), 2 usage error. What each command does and its
// options: `polarview COMMAND --help`, generated from the tables in cli_commands.cpp.
#pragma once

#include "app/command_args.h"

namespace polarview::cli {

using polarview::Args;

// refine IN.obj: the mesh refined uniformly, written as OBJ (c2ps-u, rts-u: the Section-6 variant).
CommandParser refineCommand();
// export IN.obj: the limit surface in a format of surface_export.h's table (.bv, STEP, IGES, PLY,
// glb), feature-adaptive (or uniform), written atomically.
CommandParser exportCommand();
// continuity IN.obj: position, normal and curvature differences across every seam of the
// feature-adaptive patches, per kind of seam (core/spline/continuity.h).
CommandParser continuityCommand();
// convert IN.obj --ev-to-polar | --ngon-to-fan: Fig. 14's conversion of Catmull-Clark extraordinary
// vertices into polar configurations (core/mesh/ev_to_polar.h), or n-gons into triangle fans
// (core/mesh/ngon_to_fan.h).
CommandParser convertCommand();
// info IN.obj: poles apart from rejected pole candidates (with reasons), extraordinary vertices.
CommandParser infoCommand();
// pole IN.obj: limit, normal and curvature at each pole (the Taylor expansion (32)), ring by ring.
CommandParser poleCommand();
// shape NAME -o OUT.obj: the models polarview ships (the paper's Figs. 12 and 2c among them).
CommandParser shapeCommand();
// spectrum --scheme S --valence n: the leading eigenvalues of the scheme's subdivision matrix at
// valence n (Table 1 for RTS); C2PS's Lemma 5 and (30) measured instead.
CommandParser spectrumCommand();

}  // namespace polarview::cli
