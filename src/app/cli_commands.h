// The command-line subcommands of `polarview` that need no window: refine, info, pole, bench.
// Each takes the arguments after its name and returns the process exit code:
// 0 success, 1 bad input (one line "polarview: FILE:LINE: what" on stderr), 2 usage error.
#pragma once

#include <string>
#include <vector>

namespace polarview::cli {

using Args = std::vector<std::string>;

// polarview refine IN.obj -o OUT.obj --scheme cc|c2ps|c2ps-u|rts|rts-u|bps --levels L
// (c2ps-u = c2ps --uniform-first-step, rts-u likewise; the flag with another scheme: usage error)
int runRefine(const Args& args);
// polarview export IN.obj --scheme S --level L -o OUT.bv [--uniform] [--memory-budget SIZE]: the limit
// surface in BezierView's .bv format, feature-adaptive (or uniform), written atomically.
int runExport(const Args& args);
// polarview convert IN.obj --ev-to-polar [--pentagons] -o OUT.obj: Fig. 14's conversion of
// Catmull-Clark extraordinary vertices into polar configurations (core/mesh/ev_to_polar.h)
int runConvert(const Args& args);
// polarview info IN.obj [--json]: poles apart from rejected pole candidates (with reasons)
int runInfo(const Args& args);
// polarview pole IN.obj [--scheme c2ps|c2ps-u|rts|rts-u|bps] [--json]
int runPole(const Args& args);
// polarview bench IN.obj --scheme S --levels L [--reps N] [--json]; speed-ups over the OpenSubdiv
// peer only where both computed the same (Catmull-Clark) surface
int runBench(const Args& args);

// polarview shape globe|cap|mushroom|cube|torus|valence20|fingertips [--valence n] [--links k]
// [--height NAME] -o OUT.obj (valence20, fingertips: the paper's Figs. 12 and 2c, fixed)
int runShape(const Args& args);
// `polarview spectrum --scheme rts|bps|cc --valence n [--count k] [--json]`: the leading eigenvalues
// of the scheme's subdivision matrix at valence n (Table 1 for RTS).
int runSpectrum(const Args& args);

// The usage text printed for `polarview --help` and usage errors.
const char* usageText();

// Runs `command`, turning InputError / bad_alloc into the one-line error and exit code 1.
int guarded(const std::string& file, int (*command)(const Args&), const Args& args);

}  // namespace polarview::cli
