// The command-line subcommands of `polarview` that need no window: refine, info, pole, bench.
// Each takes the arguments after its name and returns the process exit code:
// 0 success, 1 bad input (one line "polarview: FILE:LINE: what" on stderr), 2 usage error.
#pragma once

#include <string>
#include <vector>

namespace polarview::cli {

using Args = std::vector<std::string>;

// polarview refine IN.obj -o OUT.obj --scheme cc|c2ps|rts|bps --levels L [--uniform-first-step]
int runRefine(const Args& args);
// polarview info IN.obj [--json]
int runInfo(const Args& args);
// polarview pole IN.obj [--scheme c2ps|rts|bps] [--uniform-first-step] --json
int runPole(const Args& args);
// polarview bench IN.obj --scheme S --levels L [--reps N] --json
int runBench(const Args& args);

// polarview shape globe|cap|mushroom|cube|torus [--valence n] [--links k] -o OUT.obj
int runShape(const Args& args);

// The usage text printed for `polarview --help` and usage errors.
const char* usageText();

// Runs `command`, turning InputError / bad_alloc into the one-line error and exit code 1.
int guarded(const std::string& file, int (*command)(const Args&), const Args& args);

}  // namespace polarview::cli
