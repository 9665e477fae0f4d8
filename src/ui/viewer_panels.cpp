// Viewer panels, overlay and input (see viewer_panels.h): they edit settings, show status, queue commands.
#include "ui/viewer_panels.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <utility>
#include <filesystem>

#ifndef GLFW_INCLUDE_NONE
#define GLFW_INCLUDE_NONE
#endif
#include <glm/gtc/quaternion.hpp>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "pipeline/surface_export.h"
#include "session/command_ids.h"
#include "session/settings_rules.h"

namespace polarview {
namespace ids = command_ids;
namespace {

// [SECTION] Helpers

ImU32 toImColour(const glm::vec3& c, float alpha = 1.0f) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.x, c.y, c.z, alpha));
}

// Coloured text that wraps at the panel's edge (errors and refusals are long sentences).
void wrappedColoredText(const ImVec4& colour, const std::string& text) {
  ImGui::PushStyleColor(ImGuiCol_Text, colour);
  ImGui::TextWrapped("%s", text.c_str());
  ImGui::PopStyleColor();
}

const char* colourMapName(ShadingParams::ColorMap map) {
  switch (map) {
    case ShadingParams::ColorMap::Paper: return "paper";
    case ShadingParams::ColorMap::CoolWarm: return "coolwarm";
    case ShadingParams::ColorMap::Viridis: return "viridis";
    case ShadingParams::ColorMap::Magnitude: return "magnitude";
  }
  return "?";
}


// Ctrl+left drag: turns the light by the pixel deltas (0.4 degrees a pixel, as orbiting). Lit and
// curvature modes turn the key light in view space; highlight and zebra modes turn the light lines
// (direction and plane normal together) about world z and the screen's horizontal axis.
void moveLight(ShadingParams& shading, const OrbitCamera& camera, float dxPixels, float dyPixels) {
  const float yaw = glm::radians(0.4f * dxPixels), pitch = glm::radians(0.4f * dyPixels);
  if (shadingModeInfo(shading.mode).lightLines) {
    const glm::quat turn = glm::angleAxis(pitch, glm::vec3(camera.right())) * glm::angleAxis(yaw, glm::vec3(0, 0, 1));
    shading.highlightDir = glm::normalize(turn * shading.highlightDir);
    shading.highlightPlaneNormal = glm::normalize(turn * shading.highlightPlaneNormal);
  } else {
    const glm::quat turn = glm::angleAxis(pitch, glm::vec3(1, 0, 0)) * glm::angleAxis(yaw, glm::vec3(0, 1, 0));
    shading.keyLightView = glm::normalize(turn * shading.keyLightView);
  }
}



// Keeps a typed light direction usable (unit length, never zero).
void normaliseDirection(glm::vec3& d) {
  float length = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  d = length > 1e-6f ? d / length : glm::vec3(1.0f, 0.0f, 0.0f);
}

constexpr float kHistogramHeight = 18.0f;  // pixels above the colour bar
// The smallest typed range: curvatures of models of 1e150 (the OBJ reader's limit) are 1e-300.
constexpr double kSmallestRange = 1e-305;

// A tick label short enough for the bar: 3 significant digits, the exponent without '+' and
// leading zeros (1.23e20, 4.5e-7); 0 for what is below 1e-9 of the bar's `scale` (its rounding).
std::string formatTick(double value, double scale) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", std::abs(value) <= 1e-9 * scale ? 0.0 : value);
  std::string tick = buffer;
  const size_t e = tick.find('e');
  if (e == std::string::npos) return tick;
  std::string exponent = tick.substr(e + 1);
  const bool negative = exponent[0] == '-';
  exponent.erase(0, exponent.find_first_not_of("+-0"));
  return tick.substr(0, e + 1) + (negative ? "-" : "") + (exponent.empty() ? "0" : exponent);
}

// [SECTION] Panels

}  // namespace

void commandButton(CommandQueue& commands, std::string_view id) {
  const CommandCall call{&viewerCommands().at(id), 0};  // an id not in the table throws
  if (ImGui::Button(CommandTable::buttonLabel(call).c_str())) queueCommand(commands, call.text());
}

namespace {

void drawFilePanel(PanelContext& ui) {
  const FileStatus& file = ui.status.file;
  std::string& pathField = ui.settings.file.pathField;
  // The controls come first and keep their places: text whose height changes (the model's name,
  // errors, the loading line) goes below them, so a click never lands on a button that moved.
  const ImGuiStyle& style = ImGui::GetStyle();
  ImGui::SetNextItemWidth(-(ImGui::CalcTextSize("Open (Enter)").x + 2.0f * style.FramePadding.x + style.ItemSpacing.x));
  if (ImGui::InputText("##path", &pathField, ImGuiInputTextFlags_EnterReturnsTrue)) queueCommand(ui.commands, ids::kFileOpen);
  ImGui::SameLine();
  commandButton(ui.commands, ids::kFileOpen);
  commandButton(ui.commands, ids::kFileReload);
  ImGui::SameLine();
  commandButton(ui.commands, ids::kFileDefault);
  ImGui::SameLine();
  const bool canUndo = !file.previousModelName.empty();
  if (!canUndo) ImGui::BeginDisabled();
  commandButton(ui.commands, ids::kFilePreviousModel);
  if (!canUndo) ImGui::EndDisabled();
  if (canUndo && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("back to %s (also Ctrl+Z when no vertex drag is left to undo)", file.previousModelName.c_str());
  ImGui::TextWrapped("Model: %s (%d vertices, %d faces)", file.modelName.c_str(), file.modelVertices,
                     file.modelFaces);
  ImGui::TextDisabled("Or drop .obj files on the window.");
  if (file.loading) {
    wrappedColoredText(ImVec4(0.5f, 0.8f, 1.0f, 1.0f), "loading " + file.loadingPath + "... (the current model stays)");
  }
  if (!file.error.empty()) wrappedColoredText(ImVec4(1.0f, 0.4f, 0.35f, 1.0f), "Error: " + file.error);
  for (size_t i = 0; i < file.warnings.size() && i < 3; ++i) {
    wrappedColoredText(ImVec4(1.0f, 0.85f, 0.3f, 1.0f), "Warning: " + file.warnings[i]);
  }
  if (file.warnings.size() > 3) ImGui::TextDisabled("(%zu more warnings)", file.warnings.size() - 3);
  if (file.playlist.size() > 1 && ImGui::TreeNodeEx("Dropped files (PageDown / PageUp)", ImGuiTreeNodeFlags_DefaultOpen)) {
    for (size_t i = 0; i < file.playlist.size(); ++i) {
      ImGui::PushID(int(i));
      if (ImGui::Selectable(file.playlist[i].c_str(), int(i) == file.playlistIndex)) {
        pathField = file.playlist[i];  // the document marks the entry when it opens it
        queueCommand(ui.commands, ids::kFileOpen);
      }
      ImGui::PopID();
    }
    ImGui::TreePop();
  }
  if (!file.recent.empty() && ImGui::TreeNode("Recent files")) {
    for (const std::string& path : file.recent) {
      if (ImGui::Selectable(path.c_str())) {
        pathField = path;
        queueCommand(ui.commands, ids::kFileOpen);
      }
    }
    ImGui::TreePop();
  }
}

// A path field whose empty value stands for `fallback` (shown greyed as the hint), and the button of
// command `command`; true when either asks for it.
bool pathFieldAndButton(const char* id, std::string& path, const std::string& fallback, std::string_view command) {
  const std::string label = CommandTable::buttonLabel(CommandCall{&viewerCommands().at(command), 0});
  const char* button = label.c_str();
  const ImGuiStyle& style = ImGui::GetStyle();
  ImGui::SetNextItemWidth(-(ImGui::CalcTextSize(button).x + 2.0f * style.FramePadding.x + style.ItemSpacing.x));
  bool pressed = ImGui::InputTextWithHint(id, fallback.c_str(), &path, ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  pressed = ImGui::Button(button) || pressed;
  return pressed;
}

// The format Export surface writes: the extension of the default name, and of a typed one.
void drawSurfaceFormatChoice(EditSettings& edit) {
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 3.5f);
  if (!ImGui::BeginCombo("##surfaceFormat", edit.surfaceFormat.c_str())) {
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("the format of Export surface");
    return;
  }
  for (const ExportFormat& format : exportFormats()) {
    if (ImGui::Selectable(format.name, edit.surfaceFormat == format.name)) {
      edit.surfaceFormat = format.name;
      if (!edit.surfacePath.empty())
        edit.surfacePath = std::filesystem::path(edit.surfacePath).replace_extension(format.extensions.front()).string();
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", format.description);
  }
  ImGui::EndCombo();
}

void drawEditPanel(PanelContext& ui) {
  EditSettings& paths = ui.settings.edit;
  const EditStatus& edit = ui.status.edit;
  // Buttons first, at fixed places; text that changes length below them.
  const bool canUndo = edit.undoSteps > 0, canRedo = edit.redoSteps > 0;
  if (!canUndo) ImGui::BeginDisabled();
  commandButton(ui.commands, ids::kEditUndo);
  if (!canUndo) ImGui::EndDisabled();
  if (canUndo && ImGui::IsItemHovered()) ImGui::SetTooltip("undo: %s", edit.undoLabel.c_str());
  ImGui::SameLine();
  if (!canRedo) ImGui::BeginDisabled();
  commandButton(ui.commands, ids::kEditRedo);
  if (!canRedo) ImGui::EndDisabled();
  if (canRedo && ImGui::IsItemHovered()) ImGui::SetTooltip("redo: %s", edit.redoLabel.c_str());
  ImGui::SameLine();
  const bool edited = edit.movedVertices > 0;
  if (!edited) ImGui::BeginDisabled();
  commandButton(ui.commands, ids::kEditReset);
  if (!edited) ImGui::EndDisabled();
  if (edited && ImGui::IsItemHovered()) ImGui::SetTooltip("every control vertex back where the file had it (Ctrl+Z undoes it)");
  if (pathFieldAndButton("##savePath", paths.savePath, edit.defaultSavePath, ids::kEditSave))
    queueCommand(ui.commands, ids::kEditSave);
  drawSurfaceFormatChoice(paths);
  ImGui::SameLine();
  if (pathFieldAndButton("##surfacePath", paths.surfacePath, edit.defaultSurfacePath, ids::kExportSurface))
    queueCommand(ui.commands, ids::kExportSurface);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("the active view's limit surface (its scheme and level, feature-adaptive); the format from the "
                      "extension: %s", exportFormatExtensions().c_str());
  if (pathFieldAndButton("##refinedPath", paths.refinedObjPath, edit.defaultRefinedObjPath, ids::kExportRefinedObj))
    queueCommand(ui.commands, ids::kExportRefinedObj);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the active view's control mesh refined uniformly to its level, as OBJ");
  // Fig. 14: extraordinary vertices to polar configurations (the model is replaced; Ctrl+Z returns).
  commandButton(ui.commands, ids::kModelEvToPolar);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("each n-valent extraordinary vertex becomes a 2n-valent polar configuration with n 5-valent vertices");
  ImGui::SameLine();
  commandButton(ui.commands, ids::kModelEvToPolarPentagons);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("each n-valent extraordinary vertex becomes an n-valent pole ringed by n pentagons");
  commandButton(ui.commands, ids::kModelNgonToFan);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("each face of 5 or more sides becomes a fan of triangles around its centroid: n-gon caps ringed by "
                      "quads (a cylinder's) become poles");

  if (!ui.settings.display.controlNet) {
    ImGui::TextDisabled("Show the control net (N) to pick and drag its vertices.");
  } else if (edit.selectedVertex >= 0) {
    ImGui::Text("Vertex %d: (%.4g, %.4g, %.4g)%s", edit.selectedVertex, edit.selectedPosition.x, edit.selectedPosition.y,
                edit.selectedPosition.z, edit.dragging ? " moving" : "");
  } else {
    ImGui::TextDisabled("Click a control vertex to select it; drag it to move it.");
  }
  if (edited)
    ImGui::Text("%d %s moved, %d undo step%s", edit.movedVertices, edit.movedVertices == 1 ? "vertex" : "vertices",
                edit.undoSteps, edit.undoSteps == 1 ? "" : "s");
  if (!edit.exporting.empty()) wrappedColoredText(ImVec4(0.5f, 0.8f, 1.0f, 1.0f), "writing " + edit.exporting + "...");
  if (!edit.error.empty()) wrappedColoredText(ImVec4(1.0f, 0.4f, 0.35f, 1.0f), edit.error);
}

void drawViewsPanel(PanelContext& ui) {
  ImGui::SliderInt("Views (V)", &ui.settings.viewCount, 1, kMaxViews);
  ui.settings.viewCount = std::clamp(ui.settings.viewCount, 1, kMaxViews);
  ImGui::Checkbox("Link cameras (K)", &ui.settings.linkCameras);
  ImGui::SameLine();
  ImGui::Checkbox("Link levels", &ui.settings.linkLevels);
  for (int v = 0; v < ui.settings.viewCount; ++v) {
    ImGui::PushID(v);
    View& view = ui.settings.views[v];
    const ViewStatus& status = ui.status.views[size_t(v)];
    ImGui::Separator();
    ImGui::Text("View %d%s", v + 1, v == ui.settings.activeView ? " (active)" : "");
    int scheme = int(view.scheme);
    const char* names[kSchemeChoiceCount];
    for (int i = 0; i < kSchemeChoiceCount; ++i) names[i] = schemeChoiceLabel(static_cast<SchemeChoice>(i));
    if (ImGui::Combo("Scheme (S)", &scheme, names, kSchemeChoiceCount)) view.scheme = static_cast<SchemeChoice>(scheme);
    int level = view.level;
    const std::string levelLabel = "Level (0-" + std::to_string(status.deepestLevel) + ")";
    if (ImGui::SliderInt(levelLabel.c_str(), &level, 0, status.deepestLevel)) {
      ui.settings.activeView = v;
      requestLevel(ui.settings, ui.status, ui.notices, level);
    }
    if (ImGui::IsItemHovered() && !status.levelLimit.empty()) ImGui::SetTooltip("%s", status.levelLimit.c_str());
    if (status.refining) {
      ImGui::TextColored(ImVec4(0.5f, 0.8f, 1.0f, 1.0f), "refining %s %d... %.1f s", schemeChoiceLabel(view.scheme),
                         view.level, status.refiningSeconds);
    }
    if (!status.message.empty()) wrappedColoredText(ImVec4(1.0f, 0.6f, 0.3f, 1.0f), status.message);
    ImGui::PopID();
  }
}

void drawDisplayPanel(PanelContext& ui) {
  DisplayFlags& d = ui.settings.display;
  ImGui::Checkbox("Limit surface (U)", &d.surface);
  ImGui::Checkbox("Control net of the level (N)", &d.controlNet);
  ImGui::Checkbox("Patch / ring boundaries (B)", &d.patchBoundaries);
  if (d.patchBoundaries) {
    int colouring = d.boundaryColor == DisplayFlags::BoundaryColor::Kind ? 0 : 1;
    ImGui::Indent();
    ImGui::RadioButton("by patch kind", &colouring, 0);
    ImGui::SameLine();
    ImGui::RadioButton("by ring index", &colouring, 1);
    d.boundaryColor = colouring == 0 ? DisplayFlags::BoundaryColor::Kind : DisplayFlags::BoundaryColor::Ring;
    if (colouring == 0) {
      for (int k = 0; k < kPatchKindCount; ++k) {
        glm::vec3 c = patchKindColor(static_cast<PatchKind>(k));
        ImGui::ColorButton(patchKindName(static_cast<PatchKind>(k)), ImVec4(c.x, c.y, c.z, 1.0f),
                           ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
        ImGui::SameLine();
        ImGui::Text("%s", patchKindName(static_cast<PatchKind>(k)));
      }
    }
    ImGui::Unindent();
  }
  ImGui::Checkbox("Pole markers (P)", &d.poleMarkers);
  ImGui::Checkbox("Wireframe over surface (W)", &d.wireframe);
  ImGui::SliderFloat("Edge length (px)", &ui.settings.shading.tessPixels, 2.0f, 40.0f, "%.0f");
}

void drawShadingPanel(PanelContext& ui) {
  ShadingParams& s = ui.settings.shading;
  // The shade command's choices are the modes' table (pipeline/shading.h), in its order.
  const Command& shade = viewerCommands().at(ids::kShade);
  for (size_t i = 0; i < shadingModes().size(); ++i) {
    const ShadingParams::Mode mode = shadingModes()[i].mode;
    if (ImGui::RadioButton(CommandTable::buttonLabel(CommandCall{&shade, int(i)}).c_str(), s.mode == mode)) s.mode = mode;
  }
  if (shadingModeInfo(s.mode).lightLines) {
    if (ImGui::SliderFloat3("Light dir.", &s.highlightDir.x, -1.0f, 1.0f, "%.2f")) normaliseDirection(s.highlightDir);
    if (ImGui::SliderFloat3("Plane normal", &s.highlightPlaneNormal.x, -1.0f, 1.0f, "%.2f"))
      normaliseDirection(s.highlightPlaneNormal);
    // The light plane facing the active view (lines along screen y) puts stripes wherever the
    // viewer looks; the lines then stay fixed to the model while the camera moves on.
    if (ImGui::Button("Light plane facing the view")) {
      const OrbitCamera& camera = ui.settings.camera(ui.settings.activeView);
      s.highlightPlaneNormal = glm::vec3(-camera.forward());
      s.highlightDir = glm::vec3(camera.up());
    }
    if (s.mode == ShadingParams::Mode::Highlight)
      ImGui::SliderFloat("Spacing (x R)", &s.highlightSpacing, 0.01f, 1.0f, "%.3f", ImGuiSliderFlags_Logarithmic);
    else
      ImGui::SliderFloat("Period (turns)", &s.reflectionSpacing, 0.005f, 0.5f, "%.4f", ImGuiSliderFlags_Logarithmic);
    ImGui::SliderFloat("Line width", &s.highlightWidth, 0.02f, 0.98f, "%.2f");
  }
  if (ui.settings.showsColourBar()) ImGui::SliderFloat("Lighting", &s.curvatureLighting, 0.0f, 1.0f, "%.2f");
}

void drawColourPanel(PanelContext& ui) {
  ShadingParams& s = ui.settings.shading;
  int map = int(s.colormap);
  const char* maps[] = {"paper (Fig. 13)", "coolwarm", "viridis", "magnitude (Figs. 11-12)"};
  if (ImGui::Combo("Colour map (C)", &map, maps, 4)) s.colormap = static_cast<ShadingParams::ColorMap>(map);
  bool automatic = ui.settings.colour.automatic;
  if (ImGui::Checkbox("Automatic range (A)", &automatic)) setAutomaticRange(ui.settings, ui.status, automatic);
  if (ui.settings.colour.automatic) {
    float percent = ui.settings.colour.quantile * 100.0f;
    if (ImGui::SliderFloat("Percentile", &percent, 50.0f, 100.0f, "%.1f")) {
      ui.settings.colour.quantile = std::clamp(percent / 100.0f, 0.5f, 1.0f);
    }
    const ColourInterval range = colourInterval(ui.settings, ui.status);
    if (!range.oneSided() && ui.settings.colour.symmetric) ImGui::Text("Range: +-%.4g (shared by all views)", range.high);
    else ImGui::Text("Range: %.4g .. %.4g (shared by all views)", range.low, range.high);
    ImGui::PushTextWrapPos(0.0f);
    if (ui.status.colour.oneSign() != 0)
      ImGui::TextDisabled("P%.0f .. P%.0f over the half of the map of their sign; end caps at extraordinary vertices "
                          "are not counted.", 100.0f - percent, percent);
    else if (ui.settings.colour.symmetric)
      ImGui::TextDisabled("+-max(-P%.0f, P%.0f); end caps at extraordinary vertices are not counted.",
                          100.0f - percent, percent);
    else
      ImGui::TextDisabled("-P%.0f .. P%.0f; end caps at extraordinary vertices are not counted.", 100.0f - percent, percent);
    ImGui::PopTextWrapPos();
  } else if (ui.settings.colour.symmetric) {
    if (ImGui::InputDouble("Range +-", &ui.settings.colour.typedRange, 0.0, 0.0, "%.6g")) {
      ui.settings.colour.typedRange = std::max(std::abs(ui.settings.colour.typedRange), kSmallestRange);
    }
    if (ImGui::Button("Use automatic value")) ui.settings.colour.typedRange = ui.status.colour.sampled.symmetricRange;
  } else {
    ColourInterval& typed = ui.settings.colour.typedApart;
    // Min below max; zero between them keeps the map's middle, else the range is one-sided.
    if (ImGui::InputDouble("Min", &typed.low, 0.0, 0.0, "%.6g")) typed.low = std::min(typed.low, typed.high - kSmallestRange);
    if (ImGui::InputDouble("Max", &typed.high, 0.0, 0.0, "%.6g")) typed.high = std::max(typed.high, typed.low + kSmallestRange);
    if (ImGui::Button("Use automatic values")) typed = automaticInterval(ui.settings.colour, ui.status.colour);
  }
  if (const std::string note = colourRangeNote(ui.settings, ui.status); !note.empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(ImVec4(1.0f, 0.85f, 0.4f, 1.0f), "%s", note.c_str());
    ImGui::PopTextWrapPos();
  }
  bool symmetric = ui.settings.colour.symmetric;
  if (ImGui::Checkbox("Symmetric (+-R); off: min and max apart", &symmetric)) {
    if (!ui.settings.colour.automatic && !symmetric) ui.settings.colour.typedApart = ColourInterval::symmetric(ui.settings.colour.typedRange);
    ui.settings.colour.symmetric = symmetric;
  }
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("The histogram over the colour bar counts the area of the shown views' surfaces (what is on "
                      "screen at their levels, end caps left out), not the whole model.");
  ImGui::PopTextWrapPos();
}

void drawCameraPanel(PanelContext& ui) {
  for (const std::string_view id : {ids::kCameraFront, ids::kCameraTop, ids::kCameraSide, ids::kCameraIso}) {
    commandButton(ui.commands, id);
    if (id != ids::kCameraIso) ImGui::SameLine();
  }
  commandButton(ui.commands, ids::kCameraFrame);
  ImGui::SameLine();
  commandButton(ui.commands, ids::kCameraCopy);
  ImGui::SameLine();
  commandButton(ui.commands, ids::kCameraPaste);
  bool ortho = ui.settings.camera(ui.settings.activeView).orthographic;
  if (ImGui::Checkbox("Orthographic (O)", &ortho)) setOrthographic(ui.settings, ortho);
  float fov = float(ui.settings.camera(ui.settings.activeView).fovDeg);
  if (ImGui::SliderFloat("Field of view", &fov, 5.0f, 90.0f, "%.0f deg")) ui.settings.camera(ui.settings.activeView).fovDeg = fov;
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("Left drag orbits, right/middle drag pans, the wheel zooms towards the cursor, a "
                      "double-click sets the pivot, Ctrl+left drag moves the light.");
  ImGui::PopTextWrapPos();
}

void drawScreenshotPanel(PanelContext& ui) {
  commandButton(ui.commands, ids::kScreenshot);
  ImGui::SameLine();
  ImGui::RadioButton("1x", &ui.settings.screenshot.supersample, 1);
  ImGui::SameLine();
  ImGui::RadioButton("2x", &ui.settings.screenshot.supersample, 2);
  ImGui::SameLine();
  ImGui::RadioButton("4x", &ui.settings.screenshot.supersample, 4);
  ImGui::Checkbox("Transparent background", &ui.settings.screenshot.transparent);
  if (!ui.status.lastScreenshot.empty()) ImGui::TextWrapped("Last: %s", ui.status.lastScreenshot.c_str());
}

// Numbers under their names, one column each, so a number is never cut at the panel's edge nor
// wrapped in the middle (a text line of four timings was, with two views and a scroll bar).
void numberTable(const char* id, std::initializer_list<std::pair<const char*, double>> columns, const char* format) {
  if (!ImGui::BeginTable(id, int(columns.size()), ImGuiTableFlags_SizingStretchSame)) return;
  for (const auto& column : columns) ImGui::TableSetupColumn(column.first);
  ImGui::TableHeadersRow();
  ImGui::TableNextRow();
  for (const auto& column : columns) {
    ImGui::TableNextColumn();
    ImGui::Text(format, column.second);
  }
  ImGui::EndTable();
}

// One number a row under its name (a line of three was cut at the panel's edge, and ImGui wraps at
// a '.' too, inside a number).
void drawPointPanel(const ReadoutStatus& readout) {
  const PointReadout& r = readout.readout;
  ImGui::Text("view %d (marked with a cross)", readout.view + 1);
  if (!ImGui::BeginTable("##point", 2, ImGuiTableFlags_SizingFixedFit)) return;
  auto row = [](const char* name, const char* format, auto... values) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(name);
    ImGui::TableNextColumn();
    ImGui::Text(format, values...);
  };
  const SurfacePoint& p = r.point;
  row("x", "%.12g", p.position.x);
  row("y", "%.12g", p.position.y);
  row("z", "%.12g", p.position.z);
  row("normal", "(%.4f, %.4f, %.4f)", p.normal.x, p.normal.y, p.normal.z);
  row("K", "%.9g", p.gaussian);
  row("H", "%.9g", p.mean);
  row("k1", "%.9g", r.k1);
  row("k2", "%.9g", r.k2);
  row("patch", "%s %zu", patchKindName(r.kind), r.patchIndex);
  if (r.ring >= 0) row("level, ring", "%d, %d", r.level, r.ring);
  else row("level", "%d", r.level);
  row("u", "%.6f", r.u);
  row("v", "%.6f", r.v);
  ImGui::EndTable();
}

// Area and volume of the active view's surface, on demand (they take a while on deep levels).
void drawMeasures(PanelContext& ui) {
  commandButton(ui.commands, ids::kSurfaceMeasure);
  ImGui::SameLine();
  const MeasureStatus& m = ui.status.measures;
  if (m.computing) ImGui::TextDisabled("measuring...");
  else if (m.text.empty()) ImGui::TextDisabled("area, volume, centroid of the active view");
  else ImGui::TextWrapped("%s", m.text.c_str());
}

void drawStatsPanel(const ViewerSettings& settings, const ViewerStatus& status) {
  ImGui::Text("Frame: %.1f ms", status.frameMs);
  const EditStatus& edit = status.edit;
  // The cost of the last positions-only update, while the model holds an edit (an undo back to the
  // file's points leaves nothing it describes).
  if (edit.updatedViews > 0 && (edit.undoSteps > 0 || edit.movedVertices > 0)) {
    ImGui::Text("Last edit, %d view%s (ms):", edit.updatedViews, edit.updatedViews == 1 ? "" : "s");
    numberTable("##edit", {{"positions", edit.positionsMs}, {"patches", edit.patchesMs}, {"upload", edit.uploadMs},
                           {"all", edit.totalMs}}, "%.1f");
  }
  for (int v = 0; v < settings.viewCount; ++v) {
    const ViewStatus& s = status.views[size_t(v)];
    if (!s.hasSurface) {
      ImGui::Text("View %d: (nothing yet)", v + 1);
      continue;
    }
    ImGui::Text("View %d: %s level %d (ms)", v + 1, schemeChoiceLabel(s.shownScheme), s.shownLevel);
    ImGui::Indent();
    ImGui::PushID(v);
    numberTable("##timing", {{"built", s.refineMs + s.uploadMs}, {"refine", s.refineOnlyMs}, {"patches", s.patchesMs},
                             {"samples", s.samplesMs}, {"upload", s.uploadMs}}, "%.1f");
    ImGui::PopID();
    if (s.unparked)
      ImGui::TextWrapped("(a scheme toggle back: the surface stayed on the GPU, nothing was built)");
    else if (s.reshown)
      ImGui::TextWrapped("(back to the level shown before: nothing was built, %d patches stayed on the GPU)", s.keptPatches);
    else if (s.keptPatches > 0)
      ImGui::TextWrapped("(a level step: %d patches stayed on the GPU)", s.keptPatches);
    if (s.patchLevel > s.shownLevel)
      ImGui::TextWrapped("Poles closed at level %d: %s is not C2 there, so its cap at level %d would show a curvature "
                         "of its own; the rings between are the limit surface.",
                         s.patchLevel, schemeChoiceLabel(s.shownScheme), s.shownLevel);
    ImGui::TextWrapped("%d patches, %d control faces", s.patchCount, s.controlFaces);
    // The level of detail (pipeline/level_of_detail.h): refined to patchLevel, drawn at drawnLevel.
    if (s.drawnLevel < s.patchLevel)
      ImGui::TextWrapped("Drawn at level %d (%d patches): the deeper rings and caps are below a pixel here; "
                         "zoom in and they are drawn.", s.drawnLevel, s.drawnPatches);
    // Per region detail (pipeline/draw_selection.h): culled outside the view, sub-pixel ring
    // sectors drawn several to a primitive.
    if (s.drawnPrimitives > 0)
      ImGui::TextWrapped("Last frame: %d primitives for %d patches in view, %d outside it; drawn in %.1f ms",
                         s.drawnPrimitives, s.visiblePatches, s.culledPatches, s.drawMs);
    if (s.polesByCatmullClark > 0) {
      wrappedColoredText(ImVec4(1.0f, 0.85f, 0.3f, 1.0f),
                         std::to_string(s.polesByCatmullClark) + " of " +
                             std::to_string(s.polesByScheme + s.polesByCatmullClark) +
                             " poles refined by Catmull-Clark: " + s.fallbackReason);
    }
    std::string kinds;
    for (int k = 0; k < kPatchKindCount; ++k) {
      if (s.patchesPerKind[k] == 0) continue;
      kinds += std::string(kinds.empty() ? "" : ", ") + patchKindName(static_cast<PatchKind>(k)) + " " +
               std::to_string(s.patchesPerKind[k]);
    }
    ImGui::TextWrapped("%s", kinds.c_str());
    ImGui::Unindent();
  }
  if (!status.glInfo.empty()) wrappedColoredText(ImGui::GetStyle().Colors[ImGuiCol_TextDisabled], status.glInfo);
}

// The last notice, at the top of the view area where it is always in sight (the panel column may be
// scrolled or hidden). An ImGui window: screenshots, which draw only the views' overlay, leave it out.
void drawNotice(const ViewerSettings& settings, const Notices& notices) {
  if (notices.text().empty()) return;
  const ImGuiIO& io = ImGui::GetIO();
  const float left = std::min(panelColumnWidth(settings), io.DisplaySize.x * 0.5f);
  const float width = std::max(io.DisplaySize.x - left - 40.0f, 120.0f);
  ImGui::SetNextWindowPos(ImVec2(left + 20.0f, 40.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(width, io.DisplaySize.y * 0.5f));
  ImGui::SetNextWindowBgAlpha(0.85f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoFocusOnAppearing |
                                 ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoSavedSettings;
  if (ImGui::Begin("##notice", nullptr, flags)) {
    ImGui::PushTextWrapPos(width - 16.0f);
    ImGui::TextUnformatted(notices.text().c_str());
    ImGui::PopTextWrapPos();
  }
  ImGui::End();
}

void drawHelpWindow(PanelContext& ui) {
  if (!ui.settings.showHelp) return;
  // Within the window (a row a key, under its heading, is a long list): the list scrolls and the
  // help column wraps, so the id column stays in view at any window size.
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(380, 40), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(std::max(std::min(display.x - 400.0f, 1100.0f), 400.0f), std::max(display.y - 60.0f, 200.0f)),
                           ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Controls (?)", &ui.settings.showHelp)) {
    // The mouse gestures, then every command with a help line: the command table's rows.
    if (ImGui::BeginTable("keys", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_ScrollY,
                          ImVec2(0.0f, -ImGui::GetTextLineHeightWithSpacing()))) {
      ImGui::TableSetupColumn("keys", ImGuiTableColumnFlags_WidthFixed);
      ImGui::TableSetupColumn("action", ImGuiTableColumnFlags_WidthStretch);
      ImGui::TableSetupColumn("command", ImGuiTableColumnFlags_WidthFixed);
      auto row = [](const std::string& keys, const std::string& action) {
        ImGui::TableNextRow();
        ImGui::TableSetColumnIndex(0);
        ImGui::TextUnformatted(keys.c_str());
        ImGui::TableSetColumnIndex(1);
        ImGui::TextWrapped("%s", action.c_str());
      };
      auto heading = [](const std::string& title) {
        ImGui::TableNextRow();
        ImGui::TableSetColumnIndex(0);
        ImGui::TextDisabled("%s", title.c_str());
      };
      heading("mouse");
      for (const GestureHelp& gesture : gestureHelp()) row(gesture.gesture, gesture.action);
      // The command table's rows that have keys, under their headings (the third column: what
      // `view --do` calls them); the panels' buttons show the others.
      for (const HelpSection& section : viewerCommands().helpSections()) {
        bool headed = false;
        for (const Command* command : section.commands) {
          if (command->keys.empty()) continue;
          if (!std::exchange(headed, true)) heading(section.title);
          row(CommandTable::keysText(*command), command->help);
          ImGui::TableSetColumnIndex(2);
          ImGui::TextDisabled("%s", CommandTable::usage(*command).c_str());
        }
      }
      ImGui::EndTable();
    }
    ImGui::TextDisabled("Every command, buttons' too, with its `view --do` name: polarview help keys");
  }
  ImGui::End();
}

// The strip under the views: the colour bar's height whenever a view shows a curvature map or light
// lines, so switching between them keeps the views' size and the model does not move; a line
// legend alone sits in its middle, and above the colour bar when views show both.
constexpr float kColourBarStrip = 64.0f + kHistogramHeight + 4.0f;
float lineLegendReserve(const ViewerSettings& settings, float scale) {
  return settings.lineShade() && settings.showsColourBar() ? 30.0f * scale : 0.0f;
}
float colourBarOnlyReserve(const ViewerSettings& settings, float scale) {
  return settings.showsColourBar() || settings.lineShade() ? kColourBarStrip * scale : 0.0f;
}

// What the overlay draws with: the list, the font, its size and the scale (supersampled screenshots).
struct OverlayPen {
  ImDrawList* list;
  ImFont* font;
  float fontSize, scale;
};
constexpr ImU32 kOverlayText = IM_COL32(255, 255, 255, 255);
constexpr ImU32 kOverlayBox = IM_COL32(20, 20, 24, 190);

// Labels "scheme · level" at the top of each view, centred, and the lines between views; returns
// the labels' boxes (x0, y0, x1, y1).
std::vector<ImVec4> drawViewLabels(const OverlayPen& pen, const ViewerSettings& settings, const ViewerStatus& status, const std::vector<ScreenRect>& views,
                                   const ScreenRect& frame) {
  ImDrawList* list = pen.list;
  ImFont* font = pen.font;
  const float fontSize = pen.fontSize, scale = pen.scale;
  std::vector<ImVec4> labelBoxes;
  for (size_t v = 0; v < views.size(); ++v) {
    const ScreenRect& r = views[v];
    const ViewStatus& shown = status.views[v];
    const View& wanted = settings.views[v];
    std::string label = viewTitle(shown);
    if (!wanted.caption.empty()) label = wanted.caption;
    else if (wanted.shade) label += " \xC2\xB7 " + std::string(shadeModeName(*wanted.shade));
    if (shown.refining) {
      label += "   refining " + std::string(schemeChoiceLabel(wanted.scheme)) + " \xC2\xB7 " +
               std::to_string(wanted.level) + "...";
    }
    if (v == 0 && status.file.loading) label += "   loading " + status.file.loadingPath + "...";
    // Wraps in a narrow view instead of running past its sides.
    const float wrap = std::max(r.w - 24.0f * scale, 40.0f * scale);
    ImVec2 size = font->CalcTextSizeA(fontSize, 1e9f, wrap, label.c_str());
    ImVec2 at(r.x + 0.5f * (r.w - size.x), r.y + 8.0f * scale);
    list->AddRectFilled(ImVec2(at.x - 6 * scale, at.y - 3 * scale), ImVec2(at.x + size.x + 6 * scale, at.y + size.y + 3 * scale),
                        kOverlayBox, 4.0f * scale);
    list->AddText(font, fontSize, at, kOverlayText, label.c_str(), nullptr, wrap);
    labelBoxes.emplace_back(at.x - 6 * scale, at.y - 3 * scale, at.x + size.x + 6 * scale, at.y + size.y + 3 * scale);
    if (r.x > frame.x) list->AddLine(ImVec2(r.x, r.y), ImVec2(r.x, r.y + r.h), IM_COL32(128, 128, 128, 160), scale);
    if (r.y > frame.y) list->AddLine(ImVec2(r.x, r.y), ImVec2(r.x + r.w, r.y), IM_COL32(128, 128, 128, 160), scale);
  }

  return labelBoxes;
}

void drawPoleRings(const OverlayPen& pen, const std::vector<PoleMarker>& poles, const std::vector<ImVec4>& labelBoxes) {
  ImDrawList* list = pen.list;
  const float scale = pen.scale;
  // Pole rings: an outline only (white over a dark rim, readable on every colour map) so the
  // colour at the pole itself, the value the paper's Taylor expansion gives, stays visible.
  const float ringRadius = 7.0f * scale;
  for (const PoleMarker& pole : poles) {
    const ImVec2 centre(pole.x, pole.y);
    const bool underLabel = std::any_of(labelBoxes.begin(), labelBoxes.end(), [&](const ImVec4& b) {
      return centre.x > b.x - ringRadius && centre.x < b.z + ringRadius && centre.y > b.y - ringRadius &&
             centre.y < b.w + ringRadius;
    });
    if (underLabel) continue;
    list->AddCircle(centre, 7.0f * scale, IM_COL32(0, 0, 0, 200), 24, 3.0f * scale);
    list->AddCircle(centre, 7.0f * scale, IM_COL32(255, 255, 255, 230), 24, 1.3f * scale);
  }
}

void drawPointMarkers(const OverlayPen& pen, const std::vector<PointMarker>& points) {
  // The Point panel's surface point: a cross in a ring (white on a dark rim), unlike the round
  // control-vertex and pole marks.
  const float scale = pen.scale, r = 7.0f * scale;
  for (const PointMarker& point : points) {
    const ImVec2 c(point.x, point.y);
    for (const auto& [colour, width] : {std::pair{IM_COL32(0, 0, 0, 220), 3.5f}, std::pair{IM_COL32(255, 255, 255, 255), 1.5f}}) {
      pen.list->AddCircle(c, r, colour, 20, width * scale);
      pen.list->AddLine(ImVec2(c.x - 1.8f * r, c.y), ImVec2(c.x - 0.5f * r, c.y), colour, width * scale);
      pen.list->AddLine(ImVec2(c.x + 0.5f * r, c.y), ImVec2(c.x + 1.8f * r, c.y), colour, width * scale);
      pen.list->AddLine(ImVec2(c.x, c.y - 1.8f * r), ImVec2(c.x, c.y - 0.5f * r), colour, width * scale);
      pen.list->AddLine(ImVec2(c.x, c.y + 0.5f * r), ImVec2(c.x, c.y + 1.8f * r), colour, width * scale);
    }
  }
}

void drawVertexMarkers(const OverlayPen& pen, const std::vector<VertexMarker>& vertices) {
  ImDrawList* list = pen.list;
  const float scale = pen.scale;
  // Control vertices: the selected one filled (orange on a dark rim), the one under the cursor ringed.
  for (const VertexMarker& vertex : vertices) {
    const ImVec2 centre(vertex.x, vertex.y);
    if (vertex.selected) {
      list->AddCircleFilled(centre, 6.0f * scale, IM_COL32(0, 0, 0, 220), 20);
      list->AddCircleFilled(centre, 4.5f * scale, IM_COL32(255, 150, 30, 255), 20);
    } else {
      list->AddCircle(centre, kPickRadiusPixels * scale, IM_COL32(0, 0, 0, 200), 20, 3.0f * scale);
      list->AddCircle(centre, kPickRadiusPixels * scale, IM_COL32(255, 200, 80, 255), 20, 1.5f * scale);
    }
  }
}

void drawLineLegend(const OverlayPen& pen, const ViewerSettings& settings, const ScreenRect& frame) {
  ImDrawList* list = pen.list;
  ImFont* font = pen.font;
  const float fontSize = pen.fontSize, scale = pen.scale;
  // Highlight / reflection modes: a one-line legend instead of the colour bar, so screenshots
  // still say what they show.
  ShadingParams lines = settings.shading;
  lines.mode = settings.lineShade().value_or(ShadingParams::Mode::Shaded);
  if (std::string legend = lineLegend(lines); !legend.empty()) {
    const float legendSize = fontSize * 0.9f;
    // Wraps in a narrow window; extra lines grow the box upwards over the views' bottom edge.
    const float wrap = std::max(frame.w - 24.0f * scale, 60.0f * scale);
    ImVec2 size = font->CalcTextSizeA(legendSize, 1e9f, wrap, legend.c_str());
    const float oneLine = font->CalcTextSizeA(legendSize, 1e9f, 0.0f, "M").y;
    const float strip = colourBarReserve(settings, scale);
    const float below = settings.showsColourBar() ? 7.0f * scale : 0.5f * (strip - oneLine);  // from the strip's top
    ImVec2 at(frame.x + 0.5f * (frame.w - size.x), frame.y + frame.h - strip + below - (size.y - oneLine));
    list->AddRectFilled(ImVec2(at.x - 8 * scale, at.y - 4 * scale), ImVec2(at.x + size.x + 8 * scale, at.y + size.y + 4 * scale),
                        kOverlayBox, 4.0f * scale);
    list->AddText(font, legendSize, at, IM_COL32(225, 225, 225, 255), legend.c_str(), nullptr, wrap);
  }
}

void drawColourBar(const OverlayPen& pen, const ViewerSettings& settings, const ViewerStatus& status, const ScreenRect& frame) {
  ImDrawList* list = pen.list;
  ImFont* font = pen.font;
  const float fontSize = pen.fontSize, scale = pen.scale;
  // Colour bar: one range for all views, ticks at its ends, middle and quarters (with zero inside
  // the range: -below, 0, above and halfway; one-sided: evenly from low to high).
  const ColourInterval range = colourInterval(settings, status);
  const float barWidth = std::min(frame.w * 0.6f, 520.0f * scale);
  const float barHeight = 14.0f * scale;
  const float reserve = colourBarOnlyReserve(settings, scale);
  const float left = frame.x + 0.5f * (frame.w - barWidth);
  const float top = frame.y + frame.h - reserve + (8.0f + kHistogramHeight + 4.0f) * scale;
  const bool gaussian = settings.curvatureShade() == ShadingParams::Mode::Gaussian;
  std::string title = gaussian ? "Gaussian curvature K" : "mean curvature H";
  const std::string note = colourRangeNote(settings, status);  // "all K > 0: range 0.8 .. 1.2, one-sided"
  const std::string fullTitle = title + "  (" + colourMapName(settings.shading.colormap) + ", " +
                                (note.empty() ? std::string("saturates beyond the ends") : note) + ")";
  ImVec2 titleSize = font->CalcTextSizeA(fontSize, 1e9f, 0.0f, fullTitle.c_str());
  if (titleSize.x * 0.9f <= frame.w - 16.0f * scale) {
    title = fullTitle;
  } else {  // a narrow window: the short form fits on the one line the strip has
    title = std::string(gaussian ? "K" : "H") + " (" + colourMapName(settings.shading.colormap) +
            (range.oneSided() ? ", one-sided)" : ")");
    titleSize = font->CalcTextSizeA(fontSize, 1e9f, 0.0f, title.c_str());
  }
  const float histogramHeight = kHistogramHeight * scale;
  list->AddRectFilled(ImVec2(left - 40 * scale, top - histogramHeight - 6 * scale),
                      ImVec2(left + barWidth + 40 * scale, frame.y + frame.h - 2 * scale), kOverlayBox, 4.0f * scale);
  // The bar's position t in [-1, 1] -> value (two slopes around zero, or one-sided).
  auto valueAt = [&](double t) { return colourBarValue(0.5 * (t + 1.0), range); };
  // Histogram of the shown values above the bar: where the surface's curvature lies on the map.
  const std::vector<float>& bins = status.colour.histogram;
  for (size_t b = 0; b < bins.size(); ++b) {
    const float x0 = left + barWidth * float(b) / float(bins.size()), x1 = left + barWidth * float(b + 1) / float(bins.size());
    const float h = std::sqrt(std::clamp(bins[b], 0.0f, 1.0f)) * histogramHeight;  // sqrt: small bins stay visible
    if (h > 0.0f) list->AddRectFilled(ImVec2(x0 + 0.5f * scale, top - 2 * scale - h), ImVec2(x1 - 0.5f * scale, top - 2 * scale),
                                      IM_COL32(200, 200, 205, 220));
  }
  const int segments = 96;
  for (int i = 0; i < segments; ++i) {
    const double v0 = valueAt(-1.0 + 2.0 * i / segments), v1 = valueAt(-1.0 + 2.0 * (i + 1) / segments);
    ImU32 c0 = toImColour(colorMapCpu(settings.shading.colormap, v0, range));
    ImU32 c1 = toImColour(colorMapCpu(settings.shading.colormap, v1, range));
    float x0 = left + barWidth * float(i) / segments, x1 = left + barWidth * float(i + 1) / segments;
    list->AddRectFilledMultiColor(ImVec2(x0, top), ImVec2(x1 + 0.5f, top + barHeight), c0, c1, c1, c0);
  }
  list->AddRect(ImVec2(left, top), ImVec2(left + barWidth, top + barHeight), IM_COL32(230, 230, 230, 255), 0.0f, 0, scale);
  for (int t = 0; t <= 4; ++t) {
    float x = left + barWidth * float(t) / 4.0f;
    const double value = valueAt(-1.0 + 2.0 * t / 4.0);
    list->AddLine(ImVec2(x, top + barHeight), ImVec2(x, top + barHeight + 4 * scale), kOverlayText, scale);
    std::string tick = formatTick(value, std::max(-range.low, range.high));
    ImVec2 tickSize = font->CalcTextSizeA(fontSize, 1e9f, 0.0f, tick.c_str());
    list->AddText(font, fontSize, ImVec2(x - 0.5f * tickSize.x, top + barHeight + 5 * scale), kOverlayText, tick.c_str());
  }
  list->AddText(font, fontSize * 0.9f, ImVec2(left + 0.5f * (barWidth - titleSize.x * 0.9f), top + barHeight + 5 * scale + fontSize),
                IM_COL32(210, 210, 210, 255), title.c_str());
}

}  // namespace

// [SECTION] Public functions


std::string viewTitle(const ViewStatus& status) {
  if (!status.hasSurface) return "(no surface)";
  const std::string scheme = schemeChoiceLabel(status.shownScheme);
  std::string level = " \xC2\xB7 " + std::to_string(status.shownLevel);
  if (status.zoomRing >= 0)
    level += " \xC2\xB7 rings " + std::to_string(status.zoomRing) + "-" + std::to_string(status.zoomRing + 2) + " x2^" +
             std::to_string(status.zoomRing);
  if (status.polesByCatmullClark == 0) return scheme + level;
  // The scheme fell back to Catmull-Clark at some poles: the title must not claim it drew them.
  if (status.polesByScheme == 0) {
    // Why, in a word: the valence (RTS, BPS need 5), a crease or corner tag or a hole at the pole.
    const bool tags = status.fallbackReason.find("crease or corner tag") != std::string::npos;
    const bool hole = status.fallbackReason.find("hole face") != std::string::npos;
    return scheme + level + " \xC2\xB7 poles by CC (" + (tags ? "creases" : hole ? "holes" : "valence < 5") + ")";
  }
  return scheme + level + " \xC2\xB7 " + std::to_string(status.polesByCatmullClark) + " of " +
         std::to_string(status.polesByScheme + status.polesByCatmullClark) + " poles by CC";
}

float viewTitleHeight(float scale) { return 34.0f * scale; }

float panelColumnWidth(const ViewerSettings& settings) { return settings.showPanels ? 370.0f : 0.0f; }


float colourBarReserve(const ViewerSettings& settings, float scale) {
  return lineLegendReserve(settings, scale) + colourBarOnlyReserve(settings, scale);
}

std::string lineLegend(const ShadingParams& shading) {
  const glm::vec3& d = shading.highlightDir;
  char text[200];
  if (shading.mode == ShadingParams::Mode::Highlight) {
    std::snprintf(text, sizeof text, "highlight lines: light direction (%.2f, %.2f, %.2f), spacing %.3g x model radius, dark %.0f%%",
                  d.x, d.y, d.z, shading.highlightSpacing, 100.0f * shading.highlightWidth);
  } else if (shading.mode == ShadingParams::Mode::Reflection) {
    std::snprintf(text, sizeof text, "reflection lines (zebra): stripe direction (%.2f, %.2f, %.2f), period %.3g deg, dark %.0f%%",
                  d.x, d.y, d.z, 360.0f * shading.reflectionSpacing, 100.0f * shading.highlightWidth);
  } else {
    return {};
  }
  return text;
}

std::vector<ScreenRect> layoutViews(int count, const ScreenRect& frame, float bottomReserve) {
  count = std::clamp(count, 1, kMaxViews);
  const float height = std::max(frame.h - bottomReserve, 1.0f);
  // Side by side in a row, or a full grid when that gives each view a clearly larger square (4 views
  // in a 16:9 window: 2 x 2).
  int columns = count;
  float best = 0.0f;
  for (int c = count; c >= 1; --c) {  // full grids only; from one row down so ties keep the row
    if (count % c != 0) continue;
    float side = std::min(frame.w / float(c), height / float(count / c));
    if (side > best * 1.15f) {  // a grid must be clearly better than the row
      best = side;
      columns = c;
    }
  }
  const int rows = (count + columns - 1) / columns;
  std::vector<ScreenRect> rects(static_cast<size_t>(count));
  for (int v = 0; v < count; ++v) {
    int column = v % columns, row = v / columns;
    // Integer edges so neighbouring views share a pixel boundary exactly.
    float left = std::floor(frame.x + frame.w * float(column) / float(columns));
    float right = std::floor(frame.x + frame.w * float(column + 1) / float(columns));
    float top = std::floor(frame.y + height * float(row) / float(rows));
    float bottom = std::floor(frame.y + height * float(row + 1) / float(rows));
    rects[size_t(v)] = {left, top, right - left, bottom - top};
  }
  return rects;
}



void drawViewerPanels(PanelContext& ui) {
  drawHelpWindow(ui);
  drawNotice(ui.settings, ui.notices);
  if (!ui.settings.showPanels) return;
  // A fixed column on the left; the views share the rest of the window.
  ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(panelColumnWidth(ui.settings), ImGui::GetIO().DisplaySize.y), ImGuiCond_Always);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse;
  if (ImGui::Begin("polarview (Tab hides, ? for help)", nullptr, flags)) {
    // Widgets leave a fixed 120 px to their labels, so the labels are not cut.
    ImGui::PushItemWidth(-120.0f);
    if (ImGui::CollapsingHeader("File", ImGuiTreeNodeFlags_DefaultOpen)) drawFilePanel(ui);
    if (ImGui::CollapsingHeader("Views and subdivision", ImGuiTreeNodeFlags_DefaultOpen)) drawViewsPanel(ui);
    if (ImGui::CollapsingHeader("Edit and export")) drawEditPanel(ui);
    if (ImGui::CollapsingHeader("Display")) drawDisplayPanel(ui);
    if (ImGui::CollapsingHeader("Shading", ImGuiTreeNodeFlags_DefaultOpen)) drawShadingPanel(ui);
    if (ImGui::CollapsingHeader("Colour scale")) drawColourPanel(ui);
    if (ImGui::CollapsingHeader("Camera")) drawCameraPanel(ui);
    if (ImGui::CollapsingHeader("Screenshot")) drawScreenshotPanel(ui);
    if (ui.settings.poleInspector.openRequested) {
      ImGui::SetNextItemOpen(true);
      ui.settings.poleInspector.scrollFrames = 120;
    }
    ui.settings.poleInspector.openRequested = false;
    if (ImGui::CollapsingHeader("Poles")) {
      if (ui.settings.poleInspector.scrollFrames > 0) {
        --ui.settings.poleInspector.scrollFrames;
        ImGui::SetScrollHereY(0.0f);  // the header at the top of the column
      }
      drawPoleInspectorPanel(ui);
    }
    if (ImGui::CollapsingHeader("Spectrum (Fig. 1)")) drawSpectrumPanel(ui);
    if (ui.status.readout.valid && ImGui::CollapsingHeader("Point (Alt+click)", ImGuiTreeNodeFlags_DefaultOpen)) {
      drawPointPanel(ui.status.readout);
      if (ImGui::SmallButton("Copy##readout")) ImGui::SetClipboardText(ui.status.readout.text.c_str());
    }
    if (ImGui::CollapsingHeader("Stats", ImGuiTreeNodeFlags_DefaultOpen)) {
      drawStatsPanel(ui.settings, ui.status);
      drawMeasures(ui);
    }
    ImGui::PopItemWidth();
  }
  ImGui::End();
}

void drawViewOverlay(ImDrawList* list, ImFont* font, const ViewerSettings& settings, const ViewerStatus& status, const std::vector<ScreenRect>& views,
                     const ScreenRect& frame, float scale, const std::vector<PoleMarker>& poles,
                     const std::vector<VertexMarker>& vertices, const std::vector<PointMarker>& points) {
  const OverlayPen pen{list, font, 15.0f * scale, scale};
  // The pole rings leave the labels alone.
  const std::vector<ImVec4> labelBoxes = drawViewLabels(pen, settings, status, views, frame);
  drawPoleRings(pen, poles, labelBoxes);
  drawVertexMarkers(pen, vertices);
  drawPointMarkers(pen, points);
  drawLineLegend(pen, settings, frame);
  if (settings.showsColourBar()) drawColourBar(pen, settings, status, frame);
}

void zoomTowardsCursor(ViewerSettings& settings, const ScreenRect& view, int v, float notches) {
  // Towards the point of the target's plane under the cursor, as map and CAD viewers zoom.
  const ImGuiIO& io = ImGui::GetIO();
  const double ndcX = 2.0 * (io.MousePos.x - view.x) / std::max(view.w, 1.0f) - 1.0;
  const double ndcY = 1.0 - 2.0 * (io.MousePos.y - view.y) / std::max(view.h, 1.0f);
  settings.camera(v).zoomAt(notches, ndcX, ndcY, double(view.w) / std::max(double(view.h), 1.0));
}

InputResult ViewerInput::handle(PanelContext& ui, const std::vector<ScreenRect>& views, const VertexPicker& pickVertex) {
  ImGuiIO& io = ImGui::GetIO();
  InputResult result;
  // Every press since the last frame, in order (a press shorter than a frame still counts); while
  // a text field has the keyboard they were typing, not shortcuts.
  if (!io.WantCaptureKeyboard) {
    const CommandTable& commands = viewerCommands();
    for (ImWchar c : io.InputQueueCharacters)
      if (const std::optional<CommandCall> call = commands.forCharacter(c, ui.status)) queueCommand(ui.commands, call->text());
    for (const auto& [key, mods] : pendingKeys_)
      if (const std::optional<CommandCall> call = commands.forKey(key, mods, ui.status)) queueCommand(ui.commands, call->text());
  }
  pendingKeys_.clear();
  ui.settings.viewCount = std::clamp(ui.settings.viewCount, 1, kMaxViews);

  // A vertex drag follows the cursor wherever it goes until the left button comes up.
  if (vertexDrag_) {
    const bool released = !ImGui::IsMouseDown(0);
    if (released || ImGui::IsMousePosValid()) {
      result.vertexDrag = VertexDragEvent{dragView_, io.MousePos.x, io.MousePos.y, released};
    }
    if (released) {
      vertexDrag_ = false;
      dragView_ = -1;
    }
    return result;
  }

  // A click on a view that picked nothing and did not drag clears the selection.
  if (pressedOnEmpty_ && ImGui::IsMouseReleased(0)) {
    result.deselect = io.MouseDragMaxDistanceSqr[0] < 9.0f;
    pressedOnEmpty_ = false;
  }
  bool anyDown = ImGui::IsMouseDown(0) || ImGui::IsMouseDown(1) || ImGui::IsMouseDown(2);
  if (!anyDown) dragView_ = -1;
  if (io.WantCaptureMouse) return result;

  int hovered = -1;
  for (size_t v = 0; v < views.size(); ++v) {
    if (views[v].contains(io.MousePos.x, io.MousePos.y)) hovered = int(v);
  }
  result.hoveredView = hovered;
  // A plain left press on a control vertex (net shown) edits it instead of orbiting.
  if (dragView_ < 0 && hovered >= 0 && ImGui::IsMouseClicked(0) && !io.KeyCtrl && !io.KeyShift) {
    if (ui.settings.display.controlNet && pickVertex && pickVertex(hovered, io.MousePos.x, io.MousePos.y)) {
      vertexDrag_ = true;
      dragView_ = hovered;
      ui.settings.activeView = hovered;
      result.vertexDrag = VertexDragEvent{hovered, io.MousePos.x, io.MousePos.y, false};
      return result;
    }
    pressedOnEmpty_ = true;
  }
  if (dragView_ < 0 && hovered >= 0 && (ImGui::IsMouseClicked(0) || ImGui::IsMouseClicked(1) || ImGui::IsMouseClicked(2))) {
    dragView_ = hovered;
  }
  if (hovered >= 0 && !anyDown) ui.settings.activeView = hovered;
  if (dragView_ >= 0 && dragView_ < int(views.size())) {
    OrbitCamera& camera = ui.settings.camera(dragView_);
    ImVec2 delta = io.MouseDelta;
    bool pan = ImGui::IsMouseDown(1) || ImGui::IsMouseDown(2) || (ImGui::IsMouseDown(0) && io.KeyShift);
    if (delta.x != 0.0f || delta.y != 0.0f) {
      if (ImGui::IsMouseDown(0) && io.KeyCtrl) moveLight(ui.settings.shading, camera, delta.x, delta.y);
      else if (pan) camera.pan(delta.x, delta.y, views[size_t(dragView_)].h);
      else if (ImGui::IsMouseDown(0)) camera.orbit(delta.x, delta.y);
    }
  }
  if (hovered >= 0 && ImGui::IsMouseDoubleClicked(0)) {
    if (io.MouseWheel != 0.0f) zoomTowardsCursor(ui.settings, views[size_t(hovered)], hovered, io.MouseWheel);
    result.pivot = PivotPick{hovered, io.MousePos.x, io.MousePos.y, 0.0f, true, true};
    return result;
  }
  // Alt+click reads the surface point under the cursor without moving the camera.
  if (hovered >= 0 && io.KeyAlt && ImGui::IsMouseReleased(0) &&
      io.MouseDragMaxDistanceSqr[0] <= io.MouseDragThreshold * io.MouseDragThreshold) {
    result.pivot = PivotPick{hovered, io.MousePos.x, io.MousePos.y, 0.0f, true, false};
    return result;
  }
  // The wheel zooms towards the surface point under the cursor: the app reads the depth there.
  if (hovered >= 0 && io.MouseWheel != 0.0f) result.pivot = PivotPick{hovered, io.MousePos.x, io.MousePos.y, io.MouseWheel};
  return result;
}

}  // namespace polarview
