// `polarview view` and `polarview render` as option tables and bodies (command_args.h); main.cpp's
// command table runs them. `polarview view --help` / `render --help` list their options.
#pragma once

#include "app/command_args.h"

namespace polarview {

// GLFW ends with a window command, after its ViewerApp: declare one before the app.
struct GlfwSession {
  GlfwSession() = default;
  GlfwSession(const GlfwSession&) = delete;
  GlfwSession& operator=(const GlfwSession&) = delete;
  ~GlfwSession();
};

// view [FILE.obj]: the viewer (with --frames a benchmark that prints frame times as JSON).
CommandParser viewCommand();
// render FILE.obj -o OUT.png: 1 to 4 views in one image, no window shown.
CommandParser renderCommand();

}  // namespace polarview
