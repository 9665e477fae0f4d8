// The viewer's command table (command_table.h): one row a command.
#include "session/command_table.h"

#include <algorithm>
#include <optional>

#include "session/keys.h"

namespace polarview {
namespace {

using keys::kControl;
using keys::kShift;

KeyChord key(int code, int mods = 0) { return KeyChord{code, mods, 0}; }

// "CC, C2PS, C2PS-U, RTS, RTS-U, BPS": the order S steps through.
std::string schemeLabels() {
  std::string text;
  for (int s = 0; s < kSchemeChoiceCount; ++s) text += (s ? ", " : "") + std::string(schemeChoiceLabel(SchemeChoice(s)));
  return text;
}


// The rows that set a state field or flip a flag, as (id, label, key, help, setter).
Command stateCommand(std::string id, std::string label, std::vector<KeyChord> chords, std::string help,
                     std::function<void(ViewerState&)> set) {
  Command command{std::move(id), std::move(label), std::move(chords), std::move(help), {}, nullptr, nullptr};
  command.action = [set = std::move(set)](ViewerState& state, CommandHost&) { set(state); };
  return command;
}

Command hostCommand(std::string id, std::string label, std::vector<KeyChord> chords, std::string help,
                    std::function<void(CommandHost&)> run) {
  Command command{std::move(id), std::move(label), std::move(chords), std::move(help), {}, nullptr, nullptr};
  command.action = [run = std::move(run)](ViewerState&, CommandHost& host) { run(host); };
  return command;
}

void addFileCommands(std::vector<Command>& rows) {
  rows.push_back(Command{"file.open", "Open (Enter)", {}, "", {}, nullptr,
                         [](ViewerState& state, CommandHost& host) { host.openFile(state.file.pathField); }});
  rows.push_back(hostCommand("file.reload", "Reload", {key('R', kControl)}, "reload the model file",
                             [](CommandHost& host) { host.reloadModel(); }));
  rows.push_back(hostCommand("file.default", "Default model", {}, "", [](CommandHost& host) { host.loadDefaultModel(); }));
  rows.push_back(hostCommand("file.previous-model", "Previous model", {}, "",
                             [](CommandHost& host) { host.undoModelReplacement(); }));
  // PageDown / PageUp step through dropped files when there are several, else they step the level.
  auto hasPlaylist = [](const ViewerState& state) { return state.file.playlist.size() > 1; };
  Command next{"file.next", "Next file", {key(keys::kPageDown)}, "next / previous of several dropped files",
               "PageDown / PageUp", hasPlaylist, [](ViewerState& state, CommandHost& host) {
                 host.openPlaylistEntry(state.file.playlistIndex + 1);
               }};
  Command previous{"file.previous", "Previous file", {key(keys::kPageUp)}, "", {}, hasPlaylist,
                   [](ViewerState& state, CommandHost& host) { host.openPlaylistEntry(state.file.playlistIndex - 1); }};
  rows.push_back(std::move(next));
  rows.push_back(std::move(previous));
}

void addEditCommands(std::vector<Command>& rows) {
  rows.push_back(hostCommand("edit.undo", "Undo", {key('Z', kControl)},
                             "undo the last vertex drag; with none left, back to the previous model (after Open, "
                             "Default model, a drop)",
                             [](CommandHost& host) { host.undo(); }));
  rows.push_back(hostCommand("edit.redo", "Redo", {key('Z', kControl | kShift), key('Y', kControl)},
                             "redo the vertex drag undone last", [](CommandHost& host) { host.redo(); }));
  rows.push_back(hostCommand("edit.reset", "Reset", {}, "", [](CommandHost& host) { host.resetEdits(); }));
  rows.push_back(hostCommand("edit.save", "Save OBJ", {key('S', kControl)},
                             "save the edited control mesh as OBJ (path in the Edit panel)",
                             [](CommandHost& host) { host.saveEditedMesh(); }));
  rows.push_back(hostCommand("export.surface", "Export surface", {}, "", [](CommandHost& host) { host.exportSurface(true); }));
  rows.push_back(hostCommand("export.refined-obj", "Export refined OBJ", {}, "",
                             [](CommandHost& host) { host.exportSurface(false); }));
  rows.push_back(hostCommand("model.ev-to-polar", "EVs to poles (Fig. 14a)", {}, "",
                             [](CommandHost& host) { host.convertToPolar(false); }));
  rows.push_back(hostCommand("model.ev-to-polar-pentagons", "with pentagons (14c)", {}, "",
                             [](CommandHost& host) { host.convertToPolar(true); }));
  rows.push_back(hostCommand("model.ngon-to-fan", "N-gons to triangle fans", {}, "",
                             [](CommandHost& host) { host.convertToFans(); }));
  rows.push_back(hostCommand("model.eigenvector", "Show v_k as the model", {}, "",
                             [](CommandHost& host) { host.showEigenvector(); }));
}

void addCameraCommands(std::vector<Command>& rows) {
  rows.push_back(hostCommand("camera.frame", "Frame model", {key('F')}, "frame the model",
                             [](CommandHost& host) { host.frameModel(); }));
  const std::pair<const char*, ViewPreset> presets[] = {
      {"front", ViewPreset::Front}, {"top", ViewPreset::Top}, {"side", ViewPreset::Side}, {"iso", ViewPreset::Iso}};
  for (int i = 0; i < 4; ++i) {
    std::string label = presets[i].first;
    label[0] = char(label[0] - 'a' + 'A');
    const ViewPreset preset = presets[i].second;
    rows.push_back(Command{std::string("camera.") + presets[i].first, label, {key(keys::kF1 + i)},
                           i == 0 ? "view preset front / top / side / iso" : "", i == 0 ? "F1 / F2 / F3 / F4" : "",
                           nullptr, [preset](ViewerState& state, CommandHost& host) {
                             // A preset turns the cameras and shows the whole model again (from a close-up too).
                             for (int v = 0; v < kMaxViews; ++v) state.camera(v).applyPreset(preset);
                             host.frameModel();
                           }});
  }
  rows.push_back(Command{"camera.copy", "Copy", {key('C', kControl)}, "copy / paste the camera as JSON",
                         "Ctrl+C / Ctrl+V", nullptr, [](ViewerState& state, CommandHost& host) {
                           const std::string json = cameraToJson(state.camera(state.activeView));
                           host.setClipboard(json);
                           state.notice = "camera copied: " + json;
                         }});
  rows.push_back(Command{"camera.paste", "Paste", {key('V', kControl)}, "", {}, nullptr,
                         [](ViewerState& state, CommandHost& host) {
                           OrbitCamera& active = state.camera(state.activeView);
                           std::string error;
                           if (std::optional<OrbitCamera> camera = cameraFromJson(host.clipboard(), active, &error)) {
                             active = *camera;
                             state.notice = "camera pasted";
                           } else {
                             state.notice = error;
                           }
                         }});
  rows.push_back(stateCommand("camera.orthographic", "Orthographic", {key('O')}, "orthographic / perspective projection",
                              [](ViewerState& state) { setOrthographic(state, !state.camera(state.activeView).orthographic); }));
  rows.push_back(stateCommand("camera.link", "Link cameras", {key('K')}, "link / unlink the cameras of the views",
                              [](ViewerState& state) { state.linkCameras = !state.linkCameras; }));
}

void addLevelCommands(std::vector<Command>& rows) {
  for (int level = 0; level <= 9; ++level)
    rows.push_back(stateCommand("level." + std::to_string(level), "Level " + std::to_string(level),
                                {key('0' + level), key(keys::kKeypad0 + level)},
                                level == 0 ? "subdivision level (all views when levels are linked, else the active one)" : "",
                                [level](ViewerState& state) { requestLevel(state, level); }));
  rows[rows.size() - 10].helpKeys = "0 - 9";
  // Levels past 9 (feature-adaptive refinement goes to 24): one level deeper / shallower.
  rows.push_back(stateCommand("level.deeper", "Deeper", {key(']'), key(keys::kPageUp), key(keys::kKeypadAdd)},
                              "one level deeper / shallower (levels past 9, to the model's limit)", [](ViewerState& state) {
                                requestLevel(state, state.views[size_t(state.activeView)].level + 1);
                              }));
  rows.back().helpKeys = "] [  PgUp PgDn";
  rows.push_back(stateCommand("level.shallower", "Shallower", {key('['), key(keys::kPageDown), key(keys::kKeypadSubtract)}, "",
                              [](ViewerState& state) { requestLevel(state, state.views[size_t(state.activeView)].level - 1); }));
  rows.push_back(stateCommand("scheme.next", "Next scheme", {key('S')},
                              "next / previous scheme of the active view (" + schemeLabels() + ")",
                              [](ViewerState& state) { cycleScheme(state, state.activeView, 1); }));
  rows.back().helpKeys = "S / Shift+S";
  rows.push_back(stateCommand("scheme.previous", "Previous scheme", {key('S', kShift)}, "",
                              [](ViewerState& state) { cycleScheme(state, state.activeView, -1); }));
  rows.push_back(stateCommand("views.cycle", "Views", {key('V')}, "number of views 1..4",
                              [](ViewerState& state) { state.viewCount = state.viewCount % kMaxViews + 1; }));
}

void addShadingCommands(std::vector<Command>& rows) {
  for (const ShadingModeInfo& mode : shadingModes()) {
    const ShadingParams::Mode value = mode.mode;
    rows.push_back(stateCommand(shadingCommandId(value), mode.label, {key(mode.key)}, "",
                                [value](ViewerState& state) { state.shading.mode = value; }));
  }
  const size_t kModes = shadingModes().size();
  rows[rows.size() - kModes].help = "lit / Gaussian / mean / highlight lines / reflection lines (zebra)";
  rows[rows.size() - kModes].helpKeys = "L / G / M / H / Z";
  rows.push_back(stateCommand("colour.map", "Next colour map", {key('C')}, "next colour map (paper, coolwarm, viridis, magnitude)",
                              [](ViewerState& state) {
                                state.shading.colormap = static_cast<ShadingParams::ColorMap>((int(state.shading.colormap) + 1) % 4);
                              }));
  rows.push_back(stateCommand("colour.automatic", "Automatic range", {key('A')}, "automatic colour range on / off",
                              [](ViewerState& state) { setAutomaticRange(state, !state.colour.automatic); }));
  struct Toggle {
    const char* id;
    const char* label;
    int key;
    bool DisplayFlags::*flag;
  };
  const Toggle toggles[] = {{"show.surface", "Limit surface", 'U', &DisplayFlags::surface},
                            {"show.net", "Control net", 'N', &DisplayFlags::controlNet},
                            {"show.boundaries", "Patch boundaries", 'B', &DisplayFlags::patchBoundaries},
                            {"show.poles", "Pole markers", 'P', &DisplayFlags::poleMarkers},
                            {"show.wireframe", "Wireframe", 'W', &DisplayFlags::wireframe}};
  for (const Toggle& toggle : toggles)
    rows.push_back(stateCommand(toggle.id, toggle.label, {key(toggle.key)}, "",
                                [flag = toggle.flag](ViewerState& state) { state.display.*flag = !(state.display.*flag); }));
  rows[rows.size() - 5].help = "limit surface / control net / patch boundaries / pole markers / wireframe";
  rows[rows.size() - 5].helpKeys = "U / N / B / P / W";
}

void addWindowCommands(std::vector<Command>& rows) {
  rows.push_back(hostCommand("screenshot", "Screenshot", {key('X')},
                             "screenshot polarview_NNNN.png (colour bar and labels included)",
                             [](CommandHost& host) { host.takeScreenshot(); }));
  rows.push_back(stateCommand("panels", "Panels", {key(keys::kTab)}, "hide / show the panels",
                              [](ViewerState& state) { state.showPanels = !state.showPanels; }));
  rows.push_back(stateCommand("help", "Help", {KeyChord{0, 0, U'?'}}, "this help",
                              [](ViewerState& state) { state.showHelp = !state.showHelp; }));
  rows.push_back(stateCommand("poles.inspect", "Inspect poles", {}, "",
                              [](ViewerState& state) { state.poleInspector.openRequested = true; }));
}

std::string keyName(const KeyChord& chord) {
  if (chord.character) return std::string(1, char(chord.character));
  std::string name;
  if (chord.mods & kControl) name += "Ctrl+";
  if (chord.mods & kShift) name += "Shift+";
  if (chord.mods & keys::kAlt) name += "Alt+";
  const int k = chord.key;
  if (k >= keys::kF1 && k <= keys::kF4) return name + "F" + std::to_string(k - keys::kF1 + 1);
  if (k >= keys::kKeypad0 && k < keys::kKeypad0 + 10) return name + "Keypad " + std::to_string(k - keys::kKeypad0);
  if (k == keys::kTab) return name + "Tab";
  if (k == keys::kPageUp) return name + "PageUp";
  if (k == keys::kPageDown) return name + "PageDown";
  if (k == keys::kKeypadAdd) return name + "Keypad +";
  if (k == keys::kKeypadSubtract) return name + "Keypad -";
  return name + char(k);
}

bool enabledIn(const Command& command, const ViewerState& state) { return !command.enabled || command.enabled(state); }

}  // namespace

const std::vector<GestureHelp>& gestureHelp() {
  static const std::vector<GestureHelp> gestures = {
      {"Left drag", "orbit around the pivot"},
      {"Right / middle drag, Shift+left drag", "pan"},
      {"Wheel", "zoom towards the point under the cursor"},
      {"Ctrl+left drag", "move the light (lit: key light; highlight / zebra: the light lines)"},
      {"Left drag on a control vertex", "with the control net shown (N): move the vertex in the view plane; every view follows"},
      {"Double-click", "set the pivot to the surface point under the cursor (and read it, as Alt+click)"},
      {"Alt+click", "read the surface point under the cursor: position, K, H, principal curvatures, patch (panel Point)"},
      {"Drop files", "open the first dropped .obj, list the others"},
  };
  return gestures;
}

CommandTable::CommandTable() {
  addFileCommands(commands_);
  addEditCommands(commands_);
  addCameraCommands(commands_);
  addLevelCommands(commands_);
  addShadingCommands(commands_);
  addWindowCommands(commands_);
}

const Command* CommandTable::find(std::string_view id) const {
  for (const Command& command : commands_)
    if (command.id == id) return &command;
  return nullptr;
}

const Command* CommandTable::forKey(int code, int mods, const ViewerState& state) const {
  mods &= kShift | kControl | keys::kAlt;
  for (const int wanted : {mods, mods & ~kShift}) {
    for (const Command& command : commands_)
      for (const KeyChord& chord : command.keys)
        if (!chord.character && chord.key == code && chord.mods == wanted && enabledIn(command, state)) return &command;
    if (wanted == (mods & ~kShift)) break;
  }
  return nullptr;
}

const Command* CommandTable::forCharacter(char32_t character, const ViewerState& state) const {
  for (const Command& command : commands_)
    for (const KeyChord& chord : command.keys)
      if (chord.character == character && enabledIn(command, state)) return &command;
  return nullptr;
}

bool CommandTable::run(std::string_view id, ViewerState& state, CommandHost& host) const {
  const Command* command = find(id);
  if (!command) {
    state.notice = "unknown command '" + std::string(id) + "'";
    return false;
  }
  if (!enabledIn(*command, state)) {
    state.notice = command->label + ": not available now";
    return false;
  }
  command->action(state, host);
  return true;
}

void CommandTable::runQueued(ViewerState& state, CommandHost& host) const {
  // A command may queue another (it runs in the same pass).
  for (size_t i = 0; i < state.queuedCommands.size(); ++i) {
    const std::string id = state.queuedCommands[i];
    run(id, state, host);
  }
  state.queuedCommands.clear();
}

std::string CommandTable::helpKeysText(const Command& command) {
  return command.helpKeys.empty() ? keysText(command) : command.helpKeys;
}

std::string CommandTable::keysText(const Command& command) {
  std::string text;
  for (const KeyChord& chord : command.keys) {
    if (chord.key >= keys::kKeypad0 && chord.key <= keys::kKeypadAdd) continue;  // the keypad twins
    text += (text.empty() ? "" : " / ") + keyName(chord);
  }
  return text;
}

std::string CommandTable::buttonLabel(const Command& command) {
  if (command.keys.empty()) return command.label;
  return command.label + " (" + keyName(command.keys.front()) + ")";
}

std::string shadingCommandId(ShadingParams::Mode mode) { return std::string("shade.") + shadeModeName(mode); }

const CommandTable& viewerCommands() {
  static const CommandTable table;
  return table;
}

void queueCommand(ViewerState& state, std::string id) { state.queuedCommands.push_back(std::move(id)); }

}  // namespace polarview
