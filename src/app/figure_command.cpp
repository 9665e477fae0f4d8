#include "app/figure_command.h"

#include "session/settings_rules.h"
#include "app/command_args.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "app/viewer_app.h"
#include "app/viewer_commands.h"
#include "app/viewer_styles.h"
#include "core/mesh/atomic_file.h"
#include "core/mesh/ev_to_polar.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/shapes.h"
#include "core/subdiv/refiner.h"
#include "core/subdiv/spectrum.h"
#include "pipeline/eigen_nets.h"
#include "pipeline/image.h"

namespace polarview {
namespace {

// [SECTION] What each figure shows

using Mode = ShadingParams::Mode;
using Map = ShadingParams::ColorMap;

// What a panel draws: the limit surface, the input net, the net refined uniformly `level` times
// (the viewer's net of a level is the feature-adaptive one, refined only near poles), the surface
// with its patch boundaries coloured by spline ring (Fig. 11c), or the surface with the input net
// over it (Fig. 1). Nets are drawn over their lit limit surface (kNetSurfaceLevel), which hides
// the lines behind it: a bare wireframe of a closed model reads as a tangle at figure size.
enum class Draw { Surface, Net, RefinedNet, Rings, SurfaceNet };
// Fig. 14: the model's extraordinary vertices turned into poles in memory (core/mesh/ev_to_polar.h).
enum class Conversion { None, Polar, Pentagons };

struct Panel {
  std::string caption;  // its title, followed by "scheme · level" where a level is drawn
  SchemeChoice scheme;
  int level;
  Mode shade;
  Draw draw = Draw::Surface;
  int eigenvector = -1;  // >= 0: the panel's model is eigenNet(row's eigenValence, this k, c2psSteps)
  int c2psSteps = 0;
};

// One multi-view render of one model; a figure stacks its rows.
struct Row {
  std::string model;  // in assets/
  std::vector<Panel> panels;
  Conversion conversion = Conversion::None;
  std::optional<float> range{};  // a typed colour range (else the figure's shared or automatic one)
  double zoom = 1.0;             // > 1: that much closer than the framing (a close-up of the pole)
  int eigenValence = 0;          // > 0: the panels show RTS eigenvectors of this valence (Fig. 1)
  bool atPole = false;           // look at vertex 0 (the pole of every cap in assets/), not the framing's centre
};

struct Figure {
  int number;
  std::string title;
  std::string shows;    // the gallery line: what the PNG shows ...
  std::string differs;  // ... and where it differs from the paper
  std::vector<Row> rows;
  Map colormap = Map::Paper;
  bool sharedRange = true;  // rows after the first curvature row keep its colour range
  double yaw = -60.0, pitch = 40.0;  // camera direction (OrbitCamera), framed on each row's net
  int panelHeight = 250;             // above the colour bar / legend strip
  int width = 800;                   // the image's (`--width` overrides it)
  // Highlight lines (ShadingParams): > 0, this spacing and dark fraction instead of the viewer's.
  float highlightSpacing = 0.0f, highlightWidth = 0.0f;
};

// The level at which a net panel's surface is drawn under its net.
constexpr int kNetSurfaceLevel = 3;

constexpr SchemeChoice kCC = SchemeChoice::CatmullClark, kC2PS = SchemeChoice::C2PS,
                       kC2PSU = SchemeChoice::C2PSUniformFirstStep, kRTS = SchemeChoice::RTS,
                       kRTSU = SchemeChoice::RTSUniformFirstStep;

// The figures, one function each, with the paper's captions in mind (docs/schemes.md cites the
// paper; docs/gallery/README.md is what `figure all` writes). The models are the shipped OBJs
// (assets/README.md says which command made each).

// Fig. 1: the RTS eigenvectors of valence 6 (spectrum.h) as nets over the characteristic map;
// models made in memory (eigenNet), not read from assets/.
Panel eigenPanel(const std::string& caption, SchemeChoice scheme, int k, int steps) {
  return Panel{caption, scheme, 6, Mode::Shaded, Draw::SurfaceNet, k, steps};
}

Figure eigenvectorFigure() {
  return {1, "Making C2 subdivision work with degree bi-3",
       "top, the right eigenvectors v3, v4, v5 of RTS at valence 6 (`spectrum --scheme rts --valence 6 "
       "--vectors`) as control nets (black: links 0..5 of a 6-valent polar configuration with points "
       "(v1, v2, v_k), heights over the characteristic map) with their eigensplines e_k, the RTS limit "
       "surfaces of the nets: (a) e3, the paraboloid r^2, (b) e4 = r^2 B^6 cos 2t and (c) e5 = r^2 B^6 sin 2t, "
       "the saddles (lambda = 1/4; Table 1, Lemma 2), each above the characteristic spline chi = (e1, e2) "
       "(lambda = 1/2) and its net, a planar disk; bottom, (d-f) the same nets after three C2PS steps "
       "(valence 6 -> 48; links 0..5 of level 3 magnified 8 times, heights 64 = 4^3 times as Lemma 5 "
       "scales them) with C2PS's limit surface: their rings approach the periodic curves r^2, "
       "r^2 cos 2t, r^2 sin 2t (`spectrum --scheme c2ps` measures (30)'s O(8^-m))",
       "grey shading, not yellow and red; the radial eigenvectors and eigensplines (the paper's control "
       "lines marked o) are not drawn apart (they are the nets' and surfaces' sections along a spoke); "
       "(d-f) draw C2PS's refined nets T^3 v_k, which equal 4^-3 v_k of valence 48 up to O(8^-3) by (30), "
       "where the paper draws v_k as n grows; each surface's outer ring follows the boundary rules at "
       "the net's edge",
       {{"",
         {eigenPanel("(a) v3, e3 over chi", kRTS, 3, 0), eigenPanel("(b) v4, e4 over chi", kRTS, 4, 0),
          eigenPanel("(c) v5, e5 over chi", kRTS, 5, 0)},
         Conversion::None, std::nullopt, 1.2, 6},
        {"",
         {eigenPanel("(d) T^3 v3, n = 48", kC2PS, 3, 3), eigenPanel("(e) T^3 v4, n = 48", kC2PS, 4, 3),
          eigenPanel("(f) T^3 v5, n = 48", kC2PS, 5, 3)},
         Conversion::None, std::nullopt, 0.9, 6}},
       Map::Paper, false, -60.0, 20.0, 280, 900};
}

Figure polarConfigurationsFigure() {
  return {2, "Polar configurations",
       "(a) globe, (b) mushroom, (c) finger tips on a Catmull-Clark body: the polar configurations, "
       "C2PS's level-2 mesh (both drawn over the lit limit surface, which hides the lines behind it) "
       "and the C2PS limit surface (lit)",
       "one row per model (the paper has one column per model); our own models: a UV globe of valence "
       "16, the default mushroom of valence 12, a box hand with five valence-8 finger tips",
       {{"globe.obj",
         {{"(a) globe", kC2PS, 0, Mode::Shaded, Draw::Net},
          {"subdivided", kC2PS, 2, Mode::Shaded, Draw::RefinedNet},
          {"limit", kC2PS, 4, Mode::Shaded}}},
        {"default.obj",
         {{"(b) mushroom", kC2PS, 0, Mode::Shaded, Draw::Net},
          {"subdivided", kC2PS, 2, Mode::Shaded, Draw::RefinedNet},
          {"limit", kC2PS, 4, Mode::Shaded}}},
        {"fingertips.obj",
         {{"(c) finger tips", kC2PS, 0, Mode::Shaded, Draw::Net},
          {"subdivided", kC2PS, 2, Mode::Shaded, Draw::RefinedNet},
          {"limit", kC2PS, 4, Mode::Shaded}}}},
       Map::Paper, false, -70.0, 25.0, 280, 900};
}

Figure ripplesFigure() {
  return {4, "Avoiding ripples",
       "(a) a convex valence-16 polar configuration, (b) Catmull-Clark and (c) C2PS at level 4: top, "
       "Gaussian curvature (Catmull-Clark's oscillates in a 16-pointed star around the 16-valent "
       "vertex, C2PS's does not); bottom, a close-up of the pole in dense highlight lines (spacing 0.08 "
       "of the model's radius): Catmull-Clark's lines wiggle around the pole, C2PS's run straight through it",
       "the caption names no shading: the ripples show here in K (paper map) and highlight lines; our "
       "own convex input (a dome steep at its rim)",
       {{"convex16.obj",
         {{"(a) input", kC2PS, 0, Mode::Shaded, Draw::Net},
          {"(b)", kCC, 4, Mode::Gaussian},
          {"(c)", kC2PS, 4, Mode::Gaussian}}},
        {"convex16.obj",
         {{"(a) close-up", kC2PS, 0, Mode::Shaded, Draw::Net},
          {"(b)", kCC, 4, Mode::Highlight},
          {"(c)", kC2PS, 4, Mode::Highlight}},
         Conversion::None, std::nullopt, 2.2, 0, true}},
       Map::Paper, true, -60.0, 35.0, 330, 1050, 0.08f, 0.2f};
}

Figure rtsAndC2psFigure() {
  return {11, "Comparison of RTS and C2PS",
       "a valence-6 cone (the net of z = -0.7 r: a sharp tip, K rising from 0 on the flank to 70.6 at "
       "the pole; `pole --rings` measures it): top, Gauss curvature (magnitude map on +-5: dark blue is "
       "zero), bottom, lit and the spline rings. (a, b) C2PS applied directly: K waves along every "
       "spoke in the first ring (K from -16.6 to +3.6 there, a bright band with a dark zero circle "
       "inside it) and the silhouette kinks there; (c) spline rings and (d, e) surface and K with the "
       "uniform first step: K falls monotonically from 0 to -4.8 across the first ring, then rises to "
       "the pole (dK/dr changes sign 96 times along 12 spokes for C2PS, 12 with the uniform first step); "
       "(f) RTS with the uniform first step shows the 6-sidedness",
       "without Jet subdivision (Karciauskas et al. 2006), which polarview does not implement; our own "
       "input (the paper's is not printed); (f) is on the top row",
       {{"cap6_cone.obj",
         {{"(a)", kC2PS, 5, Mode::Gaussian}, {"(e)", kC2PSU, 5, Mode::Gaussian}, {"(f)", kRTSU, 5, Mode::Gaussian}},
         Conversion::None, 5.0f, 3.5, 0, true},
        {"cap6_cone.obj",
         {{"(b)", kC2PS, 5, Mode::Shaded}, {"(d)", kC2PSU, 5, Mode::Shaded}, {"(c) rings", kC2PSU, 5, Mode::Shaded, Draw::Rings}},
         Conversion::None, std::nullopt, 3.5, 0, true}},
       Map::Magnitude, false, -60.0, 35.0, 330, 1050};
}

Figure valence20Figure() {
  return {12, "Polar configuration of valence 20",
       "RTS and C2PS on a valence-20 cap (an elliptic bump), lit and in Gaussian curvature (magnitude "
       "map: dark blue is near zero) at level 4: similar surfaces and curvature at this high valence",
       "our own valence-20 input (the paper's is not printed)",
       {{"valence20.obj",
         {{"", kRTS, 4, Mode::Shaded},
          {"", kRTS, 4, Mode::Gaussian},
          {"", kC2PS, 4, Mode::Shaded},
          {"", kC2PS, 4, Mode::Gaussian}}}},
       Map::Magnitude, true, -60.0, 25.0, 260, 1040};
}

Figure shapeGalleryFigure() {
  const char* caps[][2] = {{"cap12_paraboloid.obj", "paraboloid"},
                           {"cap12_saddle.obj", "saddle"},
                           {"cap12_monkey.obj", "monkey saddle"},
                           {"cap12_flat4.obj", "flat point"},
                           {"cap12_saddle4.obj", "4th-order saddle"}};
  Figure gallery{13, "Shape gallery",
                 "valence-12 caps of a paraboloid, saddle, monkey saddle, flat point (r^4) and 4th-order saddle: "
                 "(a) input and (b) twice subdivided mesh, each over the lit limit surface, (c) Gaussian curvature of the C2PS limit surface "
                 "(paper map: green straddles zero, blue negative, red positive; each row its own range), "
                 "(d) highlight lines",
                 "our own height-function inputs of one valence (the paper's are not printed); level 4 surfaces",
                 {}, Map::Paper, false, -60.0, 40.0, 290, 1200};
  for (const auto& cap : caps)
    gallery.rows.push_back({cap[0],
                            {{std::string("(a) ") + cap[1], kC2PS, 0, Mode::Shaded, Draw::Net},
                             {"(b) subdivided", kC2PS, 2, Mode::Shaded, Draw::RefinedNet},
                             {"(c)", kC2PS, 4, Mode::Gaussian},
                             {"(d)", kC2PS, 4, Mode::Highlight}}});
  return gallery;
}

Figure conversionFigure() {
  return {14, "Conversion",
       "the corners (valence-3 extraordinary vertices) of a twice refined cube: (b) as they are, under "
       "Catmull-Clark; (a) converted into 6-valent polar configurations with three 5-valent extraordinary "
       "vertices each, and (c) into 3-valent polar configurations with three pentagons each, under C2PS "
       "(`convert --ev-to-polar [--pentagons]`); nets over the lit limit surface (lines behind it hidden) "
       "and Gaussian curvature at level 3: the converted corners carry the extra extraordinary vertices' "
       "curvature blemishes (green and blue around each corner), the paper's open question of shape",
       "the paper shows the connectivity only; valence 3 (a cube's corner) rather than a general n",
       {{"cube_cc2.obj",
         {{"(b) n-valent", kCC, 0, Mode::Shaded, Draw::Net}, {"(b)", kCC, 3, Mode::Gaussian}}},
        {"cube_cc2.obj",
         {{"(a) 2n-valent pole", kC2PS, 0, Mode::Shaded, Draw::Net}, {"(a)", kC2PS, 3, Mode::Gaussian}},
         Conversion::Polar},
        {"cube_cc2.obj",
         {{"(c) pentagons", kC2PS, 0, Mode::Shaded, Draw::Net}, {"(c)", kC2PS, 3, Mode::Gaussian}},
         Conversion::Pentagons}},
       Map::Paper, true, 45.0, 30.0, 330, 800};
}

// The figures in the paper's order.
std::vector<Figure> paperFigures() {
  return {eigenvectorFigure(), polarConfigurationsFigure(), ripplesFigure(), rtsAndC2psFigure(),
          valence20Figure(),   shapeGalleryFigure(),        conversionFigure()};
}

// [SECTION] Rendering

std::string assetPath(const std::string& name) { return std::string(POLARVIEW_ASSET_DIR) + "/" + name; }

// A row's model (converted for Fig. 14; Fig. 1's eigenvector net of its first panel); throws
// InputError on a bad file.
PolyMesh rowModel(const Row& row) {
  if (row.eigenValence > 0) return eigenNet(row.eigenValence, row.panels.front().eigenvector, row.panels.front().c2psSteps);
  const std::string path = assetPath(row.model);
  PolyMesh mesh = loadObj(path);
  if (row.conversion == Conversion::None) return mesh;
  return convertExtraordinaryToPolar(mesh, row.conversion == Conversion::Pentagons, path).mesh;
}

// Shows `mesh` in the app (which frames it); throws with the app's message when it is not usable.
void showModel(ViewerApp& app, PolyMesh mesh, const std::string& name) {
  DocumentResult shown = app.document().loadMesh(std::move(mesh), name);
  if (!shown.ok) throw std::runtime_error(app.document().fileStatus().error);
  app.session().apply(std::move(shown));
}

// Refines every view, then renders them in their styles; throws a view's refusal or error, naming
// the model file as every input error does.
RgbaImage renderViews(ViewerApp& app, int width, int height, int supersample) {
  app.runFrame();
  app.waitUntilIdle();
  const ViewerSettings& settings = app.settings();
  const ViewerStatus& status = app.status();
  const std::string& file = app.model().name;
  for (int v = 0; v < settings.viewCount; ++v) {
    const std::string& message = status.views[size_t(v)].message;
    if (!message.empty()) throw std::runtime_error(message.rfind(file + ":", 0) == 0 ? message : file + ": " + message);
  }
  return renderStyledImage(app, width, height, supersample, false);
}

// One row of `figure`: its model in one view per panel, side by side in an image `width` wide.
// `range` is the figure's shared colour range once a row has set it.
RgbaImage renderRow(ViewerApp& app, const Figure& figure, const Row& row, int width, int supersample,
                    std::optional<float>* range) {
  const PolyMesh model = rowModel(row);
  // Fig. 1's rows are framed on their widest net (e4's saddle), so that a row's panels share one scale.
  const std::string name = row.eigenValence > 0 ? "RTS eigenvectors, valence " + std::to_string(row.eigenValence)
                                                : assetPath(row.model);
  showModel(app, row.eigenValence > 0 ? eigenNet(row.eigenValence, 4, row.panels.front().c2psSteps) : model, name);
  ViewerSettings& settings = app.settings();
  const ViewerStatus& status = app.status();
  settings.viewCount = int(row.panels.size());
  for (size_t v = 0; v < row.panels.size(); ++v) {
    const Panel& panel = row.panels[v];
    View& view = settings.views[v];
    const bool net = panel.draw == Draw::Net || panel.draw == Draw::RefinedNet;
    view.scheme = panel.scheme;
    // A refined net is the level-0 net of the refined mesh, drawn in the second pass below.
    view.level = panel.draw == Draw::RefinedNet ? 0 : net ? kNetSurfaceLevel : panel.level;
    view.shade = panel.shade;
    view.caption = panel.caption;
    if (panel.draw != Draw::Net) {
      const std::string drawn = std::string(schemeChoiceLabel(panel.scheme)) + " \xC2\xB7 " + std::to_string(panel.level);
      view.caption += (view.caption.empty() ? "" : " ") + drawn;
    }
    DisplayFlags display;
    display.surface = panel.draw != Draw::RefinedNet;  // the refined net's surface comes in the second pass
    display.controlNet = net || panel.draw == Draw::SurfaceNet;
    display.patchBoundaries = panel.draw == Draw::Rings;
    display.boundaryColor = DisplayFlags::BoundaryColor::Ring;
    display.poleMarkers = false;
    view.display = display;
  }
  settings.shading.colormap = figure.colormap;
  const ShadingParams viewerDefaults;
  settings.shading.highlightSpacing = figure.highlightSpacing > 0 ? figure.highlightSpacing : viewerDefaults.highlightSpacing;
  settings.shading.highlightWidth = figure.highlightWidth > 0 ? figure.highlightWidth : viewerDefaults.highlightWidth;
  const std::optional<float> typed = row.range ? row.range : *range;
  settings.colour.automatic = !typed;
  if (typed) settings.colour.typedRange = *typed;

  // The camera's direction, then framing on the net in the first view's shape.
  const int height = figure.panelHeight + int(colourBarReserve(settings, 1.0f));
  const ScreenRect frame{0, 0, float(width), float(height)};
  const std::vector<ScreenRect> rects = layoutViews(settings.viewCount, frame, colourBarReserve(settings, 1.0f));
  settings.sharedCamera.yawDeg = figure.yaw;
  settings.sharedCamera.pitchDeg = figure.pitch;
  app.frameModel(&rects.front());
  settings.sharedCamera.distance /= row.zoom;
  if (row.atPole) settings.sharedCamera.target = glm::dvec3(model.points.front());
  const OrbitCamera camera = settings.sharedCamera;
  if (row.eigenValence > 0) {
    showModel(app, model, name);
    settings.sharedCamera = camera;
  }
  RgbaImage image = renderViews(app, width, height, supersample);
  if (figure.sharedRange && !*range && settings.showsColourBar())
    *range = float(std::max(-colourInterval(settings, status).low, colourInterval(settings, status).high));

  // Panels with a model of their own, drawn through the same camera into their place: refined nets
  // (the model refined uniformly, core Refinement) and Fig. 1's eigenvector nets after the first.
  for (size_t v = 0; v < row.panels.size(); ++v) {
    const Panel& panel = row.panels[v];
    if (panel.draw == Draw::RefinedNet) {
      const Refinement refined(model, refineOptionsFor(panel.scheme, panel.level), row.model);
      showModel(app, refined.finest().mesh, assetPath(row.model) + " refined");
      for (int w = 0; w < settings.viewCount; ++w) settings.views[size_t(w)].level = 0;  // only this panel is kept
      settings.views[v].level = kNetSurfaceLevel;
      settings.views[v].display->surface = true;
    } else if (panel.eigenvector >= 0 && v > 0) {
      showModel(app, eigenNet(row.eigenValence, panel.eigenvector, panel.c2psSteps), name);
    } else {
      continue;
    }
    settings.sharedCamera = camera;
    copyImageRect(image, renderViews(app, width, height, supersample), rects[v]);
  }
  return image;
}

// The rows one above the other (all `width` wide).
RgbaImage stackRows(const std::vector<RgbaImage>& rows) {
  RgbaImage image;
  image.width = rows.front().width;
  for (const RgbaImage& row : rows) image.height += row.height;
  image.pixels.reserve(size_t(image.width) * size_t(image.height) * 4);
  for (const RgbaImage& row : rows) image.pixels.insert(image.pixels.end(), row.pixels.begin(), row.pixels.end());
  return image;
}

std::string figureFile(int number) {
  char name[16];
  std::snprintf(name, sizeof name, "fig%02d.png", number);
  return name;
}

// The gallery's line of one figure: its PNG, what it shows, where it differs from the paper.
std::string galleryLine(const Figure& figure, const std::string& directory) {
  return "- **Fig. " + std::to_string(figure.number) + " (" + figure.title + ")** [" + figureFile(figure.number) +
         "](" + directory + figureFile(figure.number) + "): " + figure.shows + ". *Differs from the paper:* " +
         figure.differs + ".";
}

struct FigureRequest {
  std::vector<int> numbers;  // empty: all
  std::string directory;
  int width = 0, supersample = 2;  // width 0: each figure's own
};

// The figures' numbers as usage lists them: "1|2|4|11|12|13|14".
std::string figureNumbers(const char* separator) {
  std::string text;
  for (const Figure& f : paperFigures()) text += (text.empty() ? "" : separator) + std::to_string(f.number);
  return text;
}

// A figure's number, or "all" (r.numbers stays empty).
void chooseFigure(const std::string& word, FigureRequest& r) {
  if (word == "all") return;
  const int number = parseIntArgument("figure", word, 1, 14);
  const std::vector<Figure> figures = paperFigures();
  if (std::none_of(figures.begin(), figures.end(), [&](const Figure& f) { return f.number == number; }))
    throw UsageError("no figure " + word + " (" + figureNumbers(", ") + " or all)");
  r.numbers.push_back(number);
}

OptionTable figureTable(FigureRequest& r) {
  return {required(OptionRow{{}, figureNumbers("|") + "|all", "the figure, or all of them and the gallery DIR/README.md",
                             false, [&r](const std::string& word) { chooseFigure(word, r); }}),
          required(textOption({"-o", "--output"}, "DIR", "writes DIR/figNN.png from the models in assets/", &r.directory)),
          intOption({"--width"}, "W", "the image's width (320..4096; default each figure's own, 800..1200)", &r.width,
                    320, 4096),
          supersampleOption(&r.supersample)};
}

int renderFigures(FigureRequest& r) {
  std::filesystem::create_directories(r.directory);
  ViewerOptions options;
  options.hidden = true;
  options.persistRecent = false;
  options.vsync = false;
  options.prepareNextLevel = false;  // still pictures: no level steps to come
  ViewerApp app(options);
  std::string error;
  app.session().apply(app.document().loadDefaultModel());
  if (!app.init(&error)) throw std::runtime_error(error);
  app.settings().showPanels = false;
  app.settings().linkCameras = true;

  std::ostringstream gallery;
  gallery << "# Gallery\n\nThe paper's figures as polarview draws them, written by `polarview figure all -o "
             "docs/gallery` from the models in `assets/` (assets/README.md says which command made each). "
             "One line per figure: what it shows, and where it differs from the paper. The PNGs are full-colour "
             "RGB.\n\n";
  for (const Figure& figure : paperFigures()) {
    if (!r.numbers.empty() && std::find(r.numbers.begin(), r.numbers.end(), figure.number) == r.numbers.end()) continue;
    std::optional<float> range;
    std::vector<RgbaImage> rows;
    const int width = r.width > 0 ? r.width : figure.width;
    for (const Row& row : figure.rows) rows.push_back(renderRow(app, figure, row, width, r.supersample, &range));
    const std::string path = (std::filesystem::path(r.directory) / figureFile(figure.number)).string();
    writeOpaquePngAtomic(path, stackRows(rows));
    std::cout << path << "\n";
    gallery << galleryLine(figure, "") << "\n";
  }
  if (r.numbers.empty()) {
    const std::string path = (std::filesystem::path(r.directory) / "README.md").string();
    writeFileAtomically(path, gallery.str());
    std::cout << path << "\n";
  }
  return 0;
}

}  // namespace

CommandParser figureCommand() {
  return makeCommandParser(figureTable, +[](FigureRequest& r) {
    const GlfwSession session;  // ends after the figures' ViewerApp
    return renderFigures(r);
  });
}

}  // namespace polarview
