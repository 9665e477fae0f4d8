// `polarview` / `polarview view` and `polarview render`: their option tables around ViewerApp.
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "app/viewer_app.h"
#include "session/command_ids.h"
#include "session/command_table.h"
#include "app/viewer_commands.h"

#include "session/settings_rules.h"
#include "app/command_args.h"
#include "core/mesh/constants.h"
#include "app/viewer_styles.h"
#include "core/mesh/input_error.h"
#include "pipeline/level_limits.h"
#include "pipeline/surface_build.h"

namespace polarview {
namespace {

// [SECTION] Shared option parsing

std::pair<int, int> parseSize(const std::string& text) {
  size_t x = text.find('x');
  if (x == std::string::npos) throw UsageError("--size expects WxH, got '" + text + "'");
  return {parseIntArgument("--size width", text.substr(0, x), 16, 8192),
          parseIntArgument("--size height", text.substr(x + 1), 16, 8192)};
}

std::vector<SchemeChoice> parseSchemes(const std::string& text) {
  std::vector<SchemeChoice> schemes;
  std::stringstream list(text);
  std::string name;
  while (std::getline(list, name, ',')) {
    std::optional<SchemeChoice> scheme = parseSchemeChoice(name);
    if (!scheme) throw UsageError("unknown scheme '" + name + "' (" + schemeChoiceNames(", ") + ")");
    schemes.push_back(*scheme);
  }
  if (schemes.empty() || int(schemes.size()) > kMaxViews) throw UsageError("--scheme takes 1 to 4 schemes");
  return schemes;
}

// The shading modes' names, from the shading-mode table (shading.h), for usage and errors.
std::string shadeModeNames(const char* separator) {
  std::string names;
  for (const ShadingModeInfo& info : shadingModes()) names += (names.empty() ? "" : separator) + std::string(info.name);
  return names;
}

ShadingParams::Mode parseShade(const std::string& text) {
  std::optional<ShadingParams::Mode> mode = parseShadeMode(text);
  if (!mode) throw UsageError("unknown --shade '" + text + "' (" + shadeModeNames(", ") + ")");
  return *mode;
}

// --shade MODE[,MODE...]: one mode for every view or one per view (checked against the views later).
std::vector<ShadingParams::Mode> parseShadeList(const std::string& text) {
  std::vector<ShadingParams::Mode> modes;
  std::stringstream list(text);
  std::string name;
  while (std::getline(list, name, ',')) modes.push_back(parseShade(name));
  if (modes.empty() || int(modes.size()) > kMaxViews) throw UsageError("--shade takes 1 to 4 modes");
  return modes;
}

// The rows view and render share: the model, its views' schemes and level, the window's size.
OptionRow modelRow(std::string* input) {
  return positionalOption("FILE.obj", "the model (OBJ; default: the built-in model)", input);
}
OptionRow schemesRow(std::vector<SchemeChoice>* schemes) {
  return actionOption({"--scheme", "--schemes"}, "S[,S...]",
                      "1 to 4 views side by side, one scheme each (" + schemeChoiceNames("|") + ")",
                      [schemes](const std::string& v) { *schemes = parseSchemes(v); });
}
OptionRow levelRow(std::optional<int>* level, const std::string& help) {
  return intOption({"--level"}, "L", help + " (0.." + std::to_string(kMaxLevel) + ")", level, 0, kMaxLevel);
}
OptionRow sizeRow(int* width, int* height, const std::string& help) {
  return actionOption({"--size"}, "WxH", help, [=](const std::string& v) { std::tie(*width, *height) = parseSize(v); });
}

// Puts one view per scheme, all at `level`.
void setViews(ViewerSettings& settings, const std::vector<SchemeChoice>& schemes, int level) {
  settings.viewCount = int(schemes.size());
  for (size_t v = 0; v < schemes.size(); ++v) {
    settings.views[v].scheme = schemes[v];
    settings.views[v].level = level;
  }
}

// Prints the first refusal or refinement error of the visible views (a view that does not show
// what was asked for); true if there was one.
bool reportViewErrors(const ViewerApp& app) {
  const ViewerSettings& settings = app.settings();
  const ViewerStatus& status = app.status();
  for (int v = 0; v < settings.viewCount; ++v) {
    const BuiltSurface* shown = app.shownSurface(v);
    const View& wanted = settings.views[size_t(v)];
    bool showsWanted = shown && shown->key.model == app.modelGeneration() && shown->key.scheme == wanted.scheme &&
                       shown->key.level == wanted.level;
    if (!showsWanted || !status.views[size_t(v)].message.empty()) {
      std::string message = status.views[size_t(v)].message;
      if (message.empty()) message = "view " + std::to_string(v + 1) + " could not be built";
      // Name the model file, as every input error does (refinement errors already start with it).
      const std::string& file = app.model().name;
      if (message.rfind(file + ":", 0) != 0) message = file + ": " + message;
      std::cerr << "polarview: " << message << "\n";
      return true;
    }
  }
  return false;
}

// The medians of the positions-only updates `costs` (view --edit) as a JSON object: every view
// together per frame, ms.
std::string editStatsJson(const std::vector<EditCost>& costs) {
  std::vector<double> total, positions, patches, upload;
  int views = 0;
  for (const EditCost& c : costs) {
    total.push_back(c.totalMs);
    positions.push_back(c.positionsMs);
    patches.push_back(c.patchesMs);
    upload.push_back(c.uploadMs);
    views = std::max(views, c.views);
  }
  char text[240];
  std::snprintf(text, sizeof text,
                "{\"frames\":%zu,\"views\":%d,\"median_ms\":%.3f,\"positions_ms\":%.3f,\"patches_ms\":%.3f,"
                "\"upload_ms\":%.3f}",
                costs.size(), views, median(total), median(positions), median(patches), median(upload));
  return text;
}

// {"frames":N,"views":k,"schemes":[...],"level":L,"size":[w,h],"patches":[...],"median_ms":...}, and
// with `edit` "edit":{...} (editStatsJson).
std::string frameStatsJson(const ViewerApp& app, const std::vector<double>& frameMs, int width, int height,
                           const std::vector<EditCost>* edit = nullptr, const std::string& levelSteps = {}) {
  const ViewerSettings& settings = app.settings();
  const ViewerStatus& status = app.status();
  std::ostringstream json;
  json << "{\"frames\":" << frameMs.size() << ",\"views\":" << settings.viewCount << ",\"schemes\":[";
  for (int v = 0; v < settings.viewCount; ++v) json << (v ? "," : "") << '"' << schemeChoiceCliName(settings.views[size_t(v)].scheme) << '"';
  json << "],\"level\":" << settings.views[0].level << ",\"size\":[" << width << "," << height << "]";
  // Per view, one number of its status: "KEY":[view 0, view 1, ...].
  const auto perView = [&](const char* key, int ViewStatus::*field) {
    json << ",\"" << key << "\":[";
    for (int v = 0; v < settings.viewCount; ++v) json << (v ? "," : "") << status.views[size_t(v)].*field;
    json << "]";
  };
  perView("patches", &ViewStatus::patchCount);
  // The level drawn (< the level where deeper rings are below a pixel) and its patches.
  perView("drawn_levels", &ViewStatus::drawnLevel);
  perView("drawn_patches", &ViewStatus::drawnPatches);
  // What the last frame drew of those (pipeline/draw_selection.h): primitives (a group of sub-pixel
  // ring sectors is one), the patches they cover, the patches culled outside the view.
  perView("drawn_primitives", &ViewStatus::drawnPrimitives);
  perView("visible_patches", &ViewStatus::visiblePatches);
  perView("culled_patches", &ViewStatus::culledPatches);
  // Per view the last frame's draw of it, finished, ms.
  json << ",\"view_ms\":[";
  for (int v = 0; v < settings.viewCount; ++v) json << (v ? "," : "") << std::round(status.views[size_t(v)].drawMs * 100.0) / 100.0;
  json << "]";
  // Poles the scheme refined and poles left to Catmull-Clark (RTS / BPS below valence 5).
  perView("poles_by_scheme", &ViewStatus::polesByScheme);
  perView("poles_by_cc", &ViewStatus::polesByCatmullClark);
  // The deepest level the view's memory budget admits for its scheme on this model.
  perView("deepest_levels", &ViewStatus::deepestLevel);
  json << ",\"titles\":[";
  for (int v = 0; v < settings.viewCount; ++v) json << (v ? "," : "") << '"' << viewTitle(status.views[size_t(v)]) << '"';
  const ColourInterval range = colourInterval(settings, status);
  const double medianMs = median(frameMs);
  const double minMs = frameMs.empty() ? 0.0 : *std::min_element(frameMs.begin(), frameMs.end());
  const double maxMs = frameMs.empty() ? 0.0 : *std::max_element(frameMs.begin(), frameMs.end());
  // JSON has no inf or NaN: refuse rather than print them (or null for a number that overflowed).
  for (double number : {range.low, range.high, medianMs, minMs, maxMs})
    if (!std::isfinite(number))
      throw InputError(app.model().name, 0, "the statistics have a non-finite number: the input's coordinates are too large, too small or degenerate");
  json << "],\"shade\":\"" << shadeModeName(settings.shading.mode) << "\",\"shades\":[";
  for (int v = 0; v < settings.viewCount; ++v) json << (v ? "," : "") << '"' << shadeModeName(settings.viewShade(v)) << '"';
  // "range": the symmetric R (the larger side); "one_sided": the range does not hold zero.
  json << "],\"range\":" << std::max(-range.low, range.high) << ",\"range_min\":" << range.low
       << ",\"range_max\":" << range.high << ",\"one_sided\":" << (range.oneSided() ? "true" : "false");
  char numbers[160];
  std::snprintf(numbers, sizeof numbers, ",\"median_ms\":%.2f,\"min_ms\":%.2f,\"max_ms\":%.2f", medianMs, minMs, maxMs);
  json << numbers;
  if (edit) json << ",\"edit\":" << editStatsJson(*edit);
  if (!levelSteps.empty()) json << ",\"level_steps\":" << levelSteps;
  json << "}";
  return json.str();
}

// [SECTION] render

constexpr int kDefaultRenderLevel = 3;

struct RenderRequest {
  std::string input, output;
  std::vector<SchemeChoice> schemes{SchemeChoice::C2PS};
  std::optional<int> level;  // none: kDefaultRenderLevel, or each view's deepest where that is less
  bool fullDraw = false;     // draw every patch of the level, also those below a pixel
  std::vector<ShadingParams::Mode> shades{ShadingParams::Mode::Gaussian};  // one, or one per view
  std::optional<ShadingParams::ColorMap> colormap;
  int width = 1200, height = 800, supersample = 1;
  std::optional<double> range;  // --range R; double: K of a model of 1e-80 is 1e160
  std::optional<ColourInterval> rangeApart;  // --range MIN:MAX
  bool asymmetric = false;          // automatic range with each side apart
  std::optional<float> percentile;  // automatic range: +-max(-P(100 - p), P(p)) of K or H by area
  std::string cameraJson;
  std::optional<ViewPreset> preset;
  bool transparent = false, controlNet = false, boundaries = false, wireframe = false, poles = true, surface = true;
  int timeFrames = 0;
};

// --range R (the map spans -R..R) or MIN:MAX with MIN < MAX: two slopes with zero in the middle
// when MIN < 0 < MAX, else one-sided (ColourInterval).
void parseRange(const std::string& text, RenderRequest& r) {
  const std::string expected = "--range expects R > 0 or MIN:MAX with MIN < MAX, got '" + text + "'";
  auto number = [&](const std::string& part) {
    char* end = nullptr;
    const double value = std::strtod(part.c_str(), &end);
    if (part.empty() || *end != '\0' || !std::isfinite(value)) throw UsageError(expected);
    return value;
  };
  const size_t colon = text.find(':');
  if (colon == std::string::npos) {
    r.range = number(text);
    if (!(*r.range > 0.0)) throw UsageError(expected);
    return;
  }
  r.rangeApart = ColourInterval{number(text.substr(0, colon)), number(text.substr(colon + 1))};
  if (!(r.rangeApart->low < r.rangeApart->high)) throw UsageError(expected);
}

constexpr ViewPreset kPresets[] = {ViewPreset::Front, ViewPreset::Top, ViewPreset::Side, ViewPreset::Iso};

std::string presetNames(const char* separator) {
  std::string names;
  for (ViewPreset p : kPresets) names += (names.empty() ? "" : separator) + std::string(viewPresetName(p));
  return names;
}

// The colour maps by their command-line names.
struct ColormapName {
  const char* name;
  ShadingParams::ColorMap map;
};
constexpr ColormapName kColormaps[] = {{"paper", ShadingParams::ColorMap::Paper},
                                       {"coolwarm", ShadingParams::ColorMap::CoolWarm},
                                       {"viridis", ShadingParams::ColorMap::Viridis},
                                       {"magnitude", ShadingParams::ColorMap::Magnitude}};

std::string colormapNames(const char* separator) {
  std::string names;
  for (const ColormapName& c : kColormaps) names += (names.empty() ? "" : separator) + std::string(c.name);
  return names;
}

OptionTable renderTable(RenderRequest& r) {
  return {
      modelRow(&r.input),
      textOption({"-o", "--output"}, "OUT.png", "the image, written atomically (needed unless --time)", &r.output),
      schemesRow(&r.schemes),
      levelRow(&r.level, "the level; default 3, or each view's deepest within the memory budget"),
      actionOption({"--shade"}, "MODE[,MODE...]", "one shading for every view, or one per view (" + shadeModeNames("|") + ")",
                   [&r](const std::string& v) { r.shades = parseShadeList(v); }),
      sizeRow(&r.width, &r.height, "the image's size (default 1200x800)"),
      actionOption({"--range"}, "R|MIN:MAX", "the colour map spans -R..R, or MIN..MAX (one-sided when MIN, MAX have one sign; default: automatic)",
                   [&r](const std::string& v) { parseRange(v, r); }),
      actionOption({"--percentile"}, "P", "automatic range at the P-th percentile of |K| or |H| by area (50..100)",
                   [&r](const std::string& v) { r.percentile = float(parseIntArgument("--percentile", v, 50, 100)); }),
      flagOption({"--asymmetric"}, "automatic range with each side of zero apart", &r.asymmetric),
      actionOption({"--colormap"}, "NAME", "the colour map (" + colormapNames("|") + ")",
                   [&r](const std::string& name) {
                     for (const ColormapName& c : kColormaps)
                       if (name == c.name) r.colormap = c.map;
                     if (!r.colormap) throw UsageError("unknown --colormap '" + name + "' (" + colormapNames(", ") + ")");
                   }),
      textOption({"--camera"}, "JSON", "the camera, as the viewer's Camera panel copies it", &r.cameraJson),
      actionOption({"--preset"}, "NAME", "look from the " + presetNames("|") + " direction",
                   [&r](const std::string& name) {
                     for (ViewPreset p : kPresets)
                       if (name == viewPresetName(p)) r.preset = p;
                     if (!r.preset) throw UsageError("unknown --preset '" + name + "' (" + presetNames(", ") + ")");
                   }),
      supersampleOption(&r.supersample),
      flagOption({"--transparent"}, "a transparent background", &r.transparent),
      flagOption({"--net"}, "draw the control net", &r.controlNet),
      flagOption({"--no-surface"}, "no surface (the net, the wireframe or the boundaries alone)", &r.surface, false),
      flagOption({"--boundaries"}, "draw the patch boundaries", &r.boundaries),
      flagOption({"--wireframe"}, "draw the wireframe", &r.wireframe),
      flagOption({"--no-poles"}, "no pole markers", &r.poles, false),
      flagOption({"--full-draw"}, "draw every patch of the level, also those below a pixel", &r.fullDraw),
      intOption({"--time"}, "N", "render N times and print the frame times as JSON (1..10000)", &r.timeFrames, 1, 10000)};
}

// The combinations the table cannot refuse.
void checkRenderRequest(const RenderRequest& r) {
  if (r.output.empty() && r.timeFrames == 0) throw UsageError("missing -o OUT.png");
  if (r.shades.size() != 1 && r.shades.size() != r.schemes.size())
    throw UsageError("--shade takes one mode, or one per --scheme view (" + std::to_string(r.schemes.size()) + "), got " +
                     std::to_string(r.shades.size()));
  // One colour bar per image: Gaussian and mean curvature cannot share it.
  const auto has = [&](ShadingParams::Mode m) { return std::count(r.shades.begin(), r.shades.end(), m) > 0; };
  if (has(ShadingParams::Mode::Gaussian) && has(ShadingParams::Mode::Mean))
    throw UsageError("--shade: gaussian and mean in one image would need two colour bars");
}

// Loads the model (the default one when `input` is empty), then opens the window: a bad file
// fails with its one-line error before any window or output exists.
bool openModelAndWindow(ViewerApp& app, const std::string& input) {
  DocumentResult loaded = input.empty() ? app.document().loadDefaultModel() : app.document().loadFile(input);
  const bool failed = !input.empty() && !loaded.ok;
  app.session().apply(std::move(loaded));
  if (failed) {
    std::cerr << "polarview: " << app.status().file.error << "\n";
    return false;
  }
  // The reader's findings, as the other commands print them (cli_commands.cpp, loadInput).
  for (const std::string& warning : app.status().file.warnings) std::cerr << "polarview: warning: " << input << ": " << warning << "\n";
  std::string error;
  if (!app.init(&error)) {
    std::cerr << "polarview: " << error << "\n";
    return false;
  }
  return true;
}

// Each visible view whose level is past the deepest its scheme makes on this model within the
// budget takes that deepest level, said on stderr ("... within the memory budget (`why`)").
void clampToDeepestLevels(ViewerApp& app, const std::string& input, size_t faceBudget, const std::string& why) {
  ViewerSettings& settings = app.settings();
  for (int v = 0; v < settings.viewCount; ++v) {
    View& view = settings.views[size_t(v)];
    const int deepest = deepestLevel(app.model(), view.scheme, faceBudget);
    if (deepest >= view.level) continue;
    std::cerr << "polarview: " << input << ": " << schemeChoiceLabel(view.scheme) << " at level " << deepest
              << ", its deepest on this model within the memory budget (" << why << ")\n";
    view.level = deepest;
  }
}

// Views as asked. Without --level each view takes the default level, or the deepest its scheme
// makes on this model within the budget (said on stderr): a level asked for and over the budget is
// refused when the views are built.
void setRenderViews(ViewerApp& app, const RenderRequest& r, size_t faceBudget) {
  setViews(app.settings(), r.schemes, r.level.value_or(kDefaultRenderLevel));
  if (!r.level) clampToDeepestLevels(app, r.input, faceBudget, "the default is " + std::to_string(kDefaultRenderLevel));
}

// Shading, colour range and what is drawn, as asked.
void setRenderStyle(ViewerSettings& settings, const RenderRequest& r) {
  settings.linkCameras = true;
  settings.showPanels = false;
  settings.shading.mode = r.shades.front();
  if (r.shades.size() > 1)
    for (size_t v = 0; v < r.shades.size(); ++v) settings.views[v].shade = r.shades[v];
  if (r.colormap) settings.shading.colormap = *r.colormap;
  if (r.percentile) settings.colour.quantile = *r.percentile / 100.0f;
  if (r.range || r.rangeApart) settings.colour.automatic = false;
  if (r.range) settings.colour.typedRange = *r.range;
  if (r.rangeApart) settings.colour.typedApart = *r.rangeApart;
  if (r.rangeApart || r.asymmetric) settings.colour.symmetric = false;
  settings.display.surface = r.surface;
  // Net only: --no-surface shows the control net unless wireframe or boundaries stand in for it.
  settings.display.controlNet = r.controlNet || (!r.surface && !r.wireframe && !r.boundaries);
  settings.display.patchBoundaries = r.boundaries;
  settings.display.wireframe = r.wireframe;
  settings.display.poleMarkers = r.poles;
}

// The camera: framed on the model in the first view's shape (after --preset's direction), or --camera.
void setRenderCamera(ViewerApp& app, const RenderRequest& r) {
  ViewerSettings& settings = app.settings();
  ScreenRect imageRect{0, 0, float(r.width), float(r.height)};
  ScreenRect firstView = layoutViews(settings.viewCount, imageRect, colourBarReserve(settings, 1.0f)).front();
  if (r.preset) settings.sharedCamera.applyPreset(*r.preset);  // the direction, then framing along it
  app.frameModel(&firstView);
  if (r.cameraJson.empty()) return;
  std::string error;
  std::optional<OrbitCamera> camera = cameraFromJson(r.cameraJson, settings.sharedCamera, &error);
  if (!camera) throw UsageError("--camera: " + error);
  settings.sharedCamera = *camera;
}

// Renders the image (--time: N times), then writes it, or prints the frame times.
int renderAndWrite(ViewerApp& app, const RenderRequest& r) {
  RgbaImage image;
  std::vector<double> frameMs;
  int frames = std::max(r.timeFrames, 1);
  try {
    for (int f = 0; f < frames; ++f) {
      auto start = std::chrono::steady_clock::now();
      image = renderStyledImage(app, r.width, r.height, r.supersample, r.transparent);
      frameMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    // The statistics before the image: a refused number leaves no file behind.
    const std::string stats = r.timeFrames > 0 ? frameStatsJson(app, frameMs, r.width, r.height) : "";
    if (!r.output.empty()) writePngAtomic(r.output, image);
    if (r.timeFrames > 0) std::cout << stats << "\n";
    else std::cout << r.output << "\n";
  } catch (const std::exception& e) {
    std::cerr << "polarview: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

int renderWithApp(RenderRequest& r) {
  checkRenderRequest(r);
  const GlfwSession session;
  ViewerOptions options;
  options.width = std::min(r.width, 1920);
  options.height = std::min(r.height, 1080);
  options.hidden = true;
  options.persistRecent = false;
  options.vsync = false;
  options.prepareNextLevel = false;  // one picture: no level steps to come
  options.levelOfDetail = !r.fullDraw;
  ViewerApp app(options);
  if (!openModelAndWindow(app, r.input)) return 1;
  // An image this GL cannot hold is a usage error, said before any work.
  if (std::string problem = checkRenderTargetSize(r.width, r.height, r.supersample); !problem.empty()) {
    std::cerr << "polarview: render: --size " << r.width << "x" << r.height << " --supersample " << r.supersample
              << ": " << problem << "\n";
    return 2;
  }
  setRenderViews(app, r, options.faceBudget);
  setRenderStyle(app.settings(), r);
  setRenderCamera(app, r);
  // Refine every view (a refused level or a refinement error is bad input: exit 1, no file).
  app.runFrame();
  app.waitUntilIdle();
  if (reportViewErrors(app)) return 1;
  return renderAndWrite(app, r);
}

// [SECTION] view

struct ViewRequest {
  std::string input;
  std::vector<SchemeChoice> schemes;
  std::optional<int> level;
  std::optional<ShadingParams::Mode> shade;
  int width = 1600, height = 900;
  int frames = 0;
  bool stats = false, hidden = false, showHelp = false;
  bool edit = false;    // the frames drag a control vertex (positions-only updates every frame)
  bool levelSteps = false;  // first view: level L-1, then L (deeper), L-1, L again, each step timed
  bool inspectPoles = false;  // open the "Poles" section
  std::string capture;  // after the frames: the whole window, panels included, as a PNG
  std::vector<std::string> commands;  // --do: viewer commands ("level 7"), run once the model is loaded
};

OptionTable viewTable(ViewRequest& r) {
  return {modelRow(&r.input),
          schemesRow(&r.schemes),
          levelRow(&r.level, "the views' level"),
          actionOption({"--shade"}, "MODE", "the shading (" + shadeModeNames("|") + ")",
                       [&r](const std::string& v) { r.shade = parseShade(v); }),
          sizeRow(&r.width, &r.height, "the window's size (default 1600x900)"),
          intOption({"--frames"}, "N", "run N frames, then close (a benchmark; 1..100000)", &r.frames, 1, 100000),
          flagOption({"--stats"}, "with --frames: print the frame times as JSON", &r.stats),
          flagOption({"--edit"}, "with --frames: the frames drag a control vertex", &r.edit),
          flagOption({"--level-steps"}, "with --frames and --level L >= 1: time the steps L-1 -> L -> L-1 -> L",
                     &r.levelSteps),
          textOption({"--capture"}, "WINDOW.png", "with --frames: the whole window, panels included, as a PNG", &r.capture),
          flagOption({"--hidden"}, "an invisible window", &r.hidden),
          flagOption({"--show-help"}, "open the help window", &r.showHelp),
          flagOption({"--inspect-poles"}, "open the Poles section", &r.inspectPoles),
          listOption({"--do"}, "CMD[,CMD...]",
                     "run these viewer commands after the model loads: an id and its argument, if any ('level 7', "
                     "'shade gaussian', 'camera.frame'; `polarview help keys` lists them)",
                     &r.commands)};
}

// The combinations the table cannot refuse.
void checkViewRequest(const ViewRequest& r) {
  if (r.edit && r.frames == 0) throw UsageError("--edit needs --frames N");
  if (r.levelSteps && (r.frames == 0 || !r.level || *r.level < 1))
    throw UsageError("--level-steps needs --frames N and --level L >= 1");
  for (const std::string& command : r.commands) {
    std::string error;
    if (!viewerCommands().parse(command, &error)) throw UsageError("--do: " + error + " (polarview help keys lists the commands)");
  }
}

// --level-steps: the first view steps L-1 -> L -> L-1 -> L as a user pressing ] and [ does (each
// after a pause long enough for the view to make its next level ahead), then toggles its scheme to
// Catmull-Clark (from Catmull-Clark: to C2PS) and back twice as `S` does (the second time both are parked); per step the CPU split of what the new frame waited for
// (refinement, patch set, samples off the GL thread; packing + upload on it), how many patches
// stayed on the GPU, and the first frame's time (upload and draw).
// As JSON: [{"from":..,"to":..,"scheme":..,"refine_ms":..,...}, ...].
std::string runLevelSteps(ViewerApp& app, int level) {
  ViewerSettings& settings = app.settings();
  const ViewerStatus& status = app.status();
  std::ostringstream json;
  json << "[";
  int from = settings.views[0].level;
  const SchemeChoice scheme = settings.views[0].scheme;
  // The scheme toggled to: Catmull-Clark, or C2PS from Catmull-Clark (its first visit is the
  // first build of the C2PS level).
  const SchemeChoice other = scheme == SchemeChoice::CatmullClark ? SchemeChoice::C2PS : SchemeChoice::CatmullClark;
  struct Step {
    int level;
    SchemeChoice scheme;
  };
  const Step steps[] = {{level, scheme}, {level - 1, scheme}, {level, scheme}, {level, other},
                        {level, scheme}, {level, other},     {level, scheme}};
  for (size_t k = 0; k < std::size(steps); ++k) {
    requestLevel(settings, status, app.notices(), steps[k].level);
    settings.views[0].scheme = steps[k].scheme;
    app.runFrame();  // starts the job
    app.waitUntilIdle();
    app.runFrame();  // shows it: upload + draw
    const ViewStatus& shown = app.status().views[0];
    char entry[480];
    std::snprintf(entry, sizeof entry,
                  "%s{\"from\":%d,\"to\":%d,\"scheme\":\"%s\",\"shown\":%d,\"refine_ms\":%.2f,\"patches_ms\":%.2f,"
                  "\"samples_ms\":%.2f,\"upload_ms\":%.2f,\"cpu_ms\":%.2f,\"kept_patches\":%d,\"patches\":%d,\"frame_ms\":%.2f}",
                  k ? "," : "", from, steps[k].level, schemeChoiceCliName(steps[k].scheme), shown.shownLevel, shown.refineOnlyMs,
                  shown.patchesMs, shown.samplesMs, shown.uploadMs, shown.refineMs + shown.uploadMs, shown.keptPatches,
                  shown.patchCount, status.frameMs);
    json << entry;
    from = steps[k].level;
  }
  json << "]";
  return json.str();
}

// The control vertex a --edit benchmark drags: the one whose projection lies nearest the first
// view's centre (in front when several do); -1 when none is on screen.
int centralVertex(const ViewerApp& app) {
  const ViewTransform view = app.viewTransform(0);
  const std::vector<Point>& points = app.document().editor().points();
  const float cx = view.rect.x + 0.5f * view.rect.w, cy = view.rect.y + 0.5f * view.rect.h;
  int best = -1;
  double bestDistance = 1e300;
  for (size_t i = 0; i < points.size(); ++i) {
    const std::optional<glm::dvec3> at = view.project(points[i]);
    if (!at || !view.rect.contains(float(at->x), float(at->y))) continue;
    const double d = std::hypot(at->x - cx, at->y - cy);
    if (d < bestDistance) {
      bestDistance = d;
      best = int(i);
    }
  }
  return best;
}

// --frames N --edit: N frames of a mouse drag of a control vertex through the real input path
// (pick, drag in the view plane, positions-only update of every view, upload); returns the frame
// times. The vertex goes round a circle of radius 12 pixels and is released where it ends.
std::vector<double> runEditFrames(ViewerApp& app, int frames) {
  ViewerSettings& settings = app.settings();
  const ViewerStatus& status = app.status();
  settings.display.controlNet = true;
  app.runFrame();
  const int vertex = centralVertex(app);
  if (vertex < 0) throw std::runtime_error("view --edit: no control vertex on screen to drag");
  const std::optional<glm::dvec3> at = app.viewTransform(0).project(app.document().editor().points()[size_t(vertex)]);
  const float x0 = float(at->x), y0 = float(at->y);
  app.overridePointer(PointerState{x0, y0, false});
  app.runFrame();
  app.overridePointer(PointerState{x0, y0, true});  // the press picks the vertex
  app.runFrame();
  std::vector<double> frameMs;
  float x = x0, y = y0;
  for (int f = 0; f < frames && !app.shouldClose(); ++f) {
    const double angle = 2.0 * kPi * double(f + 1) / double(std::max(frames, 8));
    x = x0 + 12.0f * float(std::sin(angle));
    y = y0 - 12.0f * float(1.0 - std::cos(angle));
    app.overridePointer(PointerState{x, y, true});
    app.runFrame();
    frameMs.push_back(status.frameMs);
  }
  app.overridePointer(PointerState{x, y, false});  // released where it is: one undo step
  app.runFrame();
  app.overridePointer(std::nullopt);
  if (app.document().editCosts().empty()) throw std::runtime_error("view --edit: the drag moved no control vertex");
  return frameMs;
}

int viewWithApp(ViewRequest& r) {
  checkViewRequest(r);
  const GlfwSession session;
  ViewerOptions options;
  options.width = r.width;
  options.height = r.height;
  options.hidden = r.hidden;
  options.persistRecent = r.frames == 0;
  options.vsync = r.frames == 0;
  options.scriptedCommands = r.commands;
  ViewerApp app(options);
  ViewerSettings& settings = app.settings();
  const ViewerStatus& status = app.status();
  if (!openModelAndWindow(app, r.input)) return 1;
  // --level-steps starts one level above the one it steps to.
  const std::optional<int> firstLevel = r.levelSteps ? std::optional<int>(*r.level - 1) : r.level;
  if (!r.schemes.empty()) setViews(settings, r.schemes, firstLevel.value_or(settings.views[0].level));
  else if (firstLevel) requestLevel(settings, status, app.notices(), *firstLevel);
  // A window shows the deepest level a view can make rather than an empty view (render refuses).
  if (firstLevel) clampToDeepestLevels(app, r.input.empty() ? "default model" : r.input, options.faceBudget,
                                       "--level " + std::to_string(*firstLevel) + " asked");
  app.frameModel();
  if (r.shade) settings.shading.mode = *r.shade;
  settings.showHelp = r.showHelp;
  if (r.inspectPoles) app.session().queueCommand(command_ids::kPolesInspect);

  if (r.frames == 0) {
    while (!app.shouldClose()) app.runFrame();
    return 0;
  }

  // Benchmark: refine first, then time N frames (panels included, as a user sees them).
  app.runFrame();
  app.waitUntilIdle();
  std::vector<double> frameMs;
  std::string levelSteps;
  if (r.levelSteps) levelSteps = runLevelSteps(app, *r.level);
  if (r.edit) {
    frameMs = runEditFrames(app, r.frames);
    app.waitUntilIdle();  // the curvature samples retaken after the drag
  } else {
    for (int f = 0; f < r.frames && !app.shouldClose(); ++f) {
      app.runFrame();
      frameMs.push_back(status.frameMs);
    }
  }
  if (!r.capture.empty()) {
    app.captureWindowNextFrame(r.capture);
    app.runFrame();
  }
  if (r.stats)
    std::cout << frameStatsJson(app, frameMs, r.width, r.height, r.edit ? &app.document().editCosts() : nullptr, levelSteps) << "\n";
  return 0;
}

}  // namespace

GlfwSession::~GlfwSession() { glfwTerminate(); }

CommandParser viewCommand() { return makeCommandParser(viewTable, viewWithApp); }
CommandParser renderCommand() { return makeCommandParser(renderTable, renderWithApp); }

}  // namespace polarview
