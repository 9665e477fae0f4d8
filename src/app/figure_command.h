// `polarview figure N|all -o DIR`: the figures of Myles & Peters 2009 (Figs. 1, 2, 4, 11, 12, 13, 14)
// rendered from the models shipped in assets/ with the schemes, levels, shading and colour maps their
// captions name, as DIR/figNN.png, and for `all` the gallery DIR/README.md: one line per figure on what
// it shows and where it differs from the paper.
#pragma once

#include "app/command_args.h"

namespace polarview {

// The figure command's option table and body (command_args.h); main.cpp's command table runs it:
// 0 ok, 1 bad input or a failed render ("polarview: FILE: msg"), 2 usage error.
CommandParser figureCommand();

}  // namespace polarview
