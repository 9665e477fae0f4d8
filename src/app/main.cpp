// polarview: the viewer when run bare or with `view`, otherwise a command-line subcommand.
#include <algorithm>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "app/cli_commands.h"
#ifdef POLARVIEW_HAVE_VIEWER
#include "app/figure_command.h"
#include "app/viewer_app.h"
#endif

int main(int argc, char** argv) {
  using namespace polarview::cli;
  const std::string command = argc > 1 ? argv[1] : "";
  Args args(argv + std::min(argc, 2), argv + argc);
  const std::string file = args.empty() ? "" : args[0];
  if (command == "refine") return guarded(file, runRefine, args);
  if (command == "export") return guarded(file, runExport, args);
  if (command == "convert") return guarded(file, runConvert, args);
  if (command == "info") return guarded(file, runInfo, args);
  if (command == "pole") return guarded(file, runPole, args);
  if (command == "bench") return guarded(file, runBench, args);
  if (command == "shape") return guarded("", runShape, args);
  if (command == "spectrum") return guarded("", runSpectrum, args);
  if (command == "-h" || command == "--help" || command == "help") {
    std::cout << usageText();
    return 0;
  }
#ifdef POLARVIEW_HAVE_VIEWER
  if (command.empty()) return polarview::runViewer("");
  if (command == "view") return polarview::runViewerCommand(args);
  if (command == "render") return polarview::runRenderCommand(args);
  if (command == "figure") return polarview::runFigureCommand(args);
#else
  if (command.empty() || command == "view" || command == "render" || command == "figure") {
    std::cerr << "polarview: built without the viewer (POLARVIEW_BUILD_VIEWER=OFF)\n";
    return 2;
  }
#endif
  std::cerr << "polarview: unknown command '" << command << "'\n" << usageText();
  return 2;
}
