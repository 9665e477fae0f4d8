// The viewer's command table (command_table.h): one row a command.
#include "session/command_table.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <stdexcept>

#include "session/keys.h"
#include "session/session.h"
#include "session/settings_rules.h"

namespace polarview {
namespace {

using keys::kControl;
using keys::kShift;

KeyChord key(int code, int mods = 0) { return KeyChord{code, mods, 0, 0}; }

// "CC, C2PS, C2PS-U, RTS, RTS-U, BPS": the order S steps through.
std::string schemeLabels() {
  std::string text;
  for (int s = 0; s < kSchemeChoiceCount; ++s)
    text += (s ? ", " : "") + std::string(schemeChoiceLabel(SchemeChoice(s)));
  return text;
}

std::string lowercase(std::string_view text) {
  std::string lower(text);
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  return lower;
}

// Adds the rows of one help heading.
class Rows {
 public:
  Rows(std::vector<Command>& rows, std::string group) : rows_(rows), group_(std::move(group)) {}

  // A row acting on the session.
  Command& add(std::string id, std::string label, std::vector<KeyChord> chords, std::string help,
               std::function<void(Session&)> run) {
    return push(std::move(id), std::move(label), std::move(chords), std::move(help), {},
                [run = std::move(run)](Session& session, int) { run(session); });
  }
  // A row acting on the document: the session shows what the operation reports.
  Command& document(std::string id, std::string label, std::vector<KeyChord> chords, std::string help,
                    std::function<DocumentResult(Session&)> run) {
    return add(std::move(id), std::move(label), std::move(chords), std::move(help),
               [run = std::move(run)](Session& session) { session.apply(run(session)); });
  }
  // A row that sets a setting or flips a flag.
  Command& setting(std::string id, std::string label, std::vector<KeyChord> chords, std::string help,
                   std::function<void(ViewerSettings&)> set) {
    return add(std::move(id), std::move(label), std::move(chords), std::move(help),
               [set = std::move(set)](Session& session) { set(session.settings()); });
  }
  // A row taking `argument`, acting on the session with its value.
  Command& withArgument(std::string id, std::string label, std::vector<KeyChord> chords, std::string help,
                        CommandArgument argument, std::function<void(Session&, int)> run) {
    return push(std::move(id), std::move(label), std::move(chords), std::move(help), std::move(argument),
                std::move(run));
  }

 private:
  Command& push(std::string id, std::string label, std::vector<KeyChord> chords, std::string help,
                CommandArgument argument, std::function<void(Session&, int)> action) {
    rows_.push_back(Command{std::move(id), std::move(label), std::move(chords), std::move(help), group_,
                            std::move(argument), nullptr, std::move(action)});
    return rows_.back();
  }

  std::vector<Command>& rows_;
  std::string group_;
};

void addFileCommands(Rows rows) {
  rows.document("file.open", "Open (Enter)", {},
           "open the path typed in the File panel (Enter there; the model stays on failure)",
           [](Session& s) { return s.document().requestLoad(s.settings().file.pathField); });
  rows.document("file.reload", "Reload", {key('R', kControl)}, "reload the model file",
           [](Session& s) { return s.document().reloadModel(); });
  rows.document("file.default", "Default model", {}, "the built-in default model",
           [](Session& s) { return s.document().loadDefaultModel(); });
  rows.document("file.previous-model", "Previous model", {}, "the model the last Open / Default model / drop replaced",
           [](Session& s) { return s.document().undoModelReplacement(); });
  // PageDown / PageUp step through dropped files when there are several, else they step the level.
  auto hasPlaylist = [](const ViewerStatus& status) { return status.file.playlist.size() > 1; };
  for (const int step : {1, -1}) {
    const bool next = step > 0;
    rows.add(next ? "file.next" : "file.previous", next ? "Next file" : "Previous file",
             {key(next ? keys::kPageDown : keys::kPageUp)},
             std::string(next ? "next" : "previous") + " of several dropped files (else the key steps the level)",
             [step](Session& s) { return s.document().openPlaylistEntry(s.status().file.playlistIndex + step); })
        .enabled = hasPlaylist;
  }
}

void addEditCommands(Rows rows) {
  rows.document("edit.undo", "Undo", {key('Z', kControl)},
           "undo the last vertex drag; with none left, back to the previous model (after Open, Default model, a drop)",
           [](Session& s) { return s.document().undo(); });
  rows.document("edit.redo", "Redo", {key('Z', kControl | kShift), key('Y', kControl)}, "redo the vertex drag undone last",
           [](Session& s) { return s.document().redo(); });
  rows.document("edit.reset", "Reset", {}, "every control vertex back where the file had it",
           [](Session& s) { return s.document().resetEdits(); });
  rows.document("edit.save", "Save OBJ", {key('S', kControl)},
           "save the edited control mesh as OBJ (path in the Edit panel)",
           [](Session& s) { return s.document().saveEditedMesh(s.settings().edit); });
  rows.document("export.surface", "Export surface", {},
           "the active view's limit surface (.bv; the format from the Edit panel's path)",
           [](Session& s) { return s.document().startExport(SurfaceExport::LimitSurface, s.activeSurface(), s.settings()); });
  rows.document("export.refined-obj", "Export refined OBJ", {},
           "the active view's control mesh refined to its level, as OBJ",
           [](Session& s) { return s.document().startExport(SurfaceExport::RefinedMesh, s.activeSurface(), s.settings()); });
}

void addModelCommands(Rows rows) {
  rows.document("model.ev-to-polar", "EVs to poles (Fig. 14a)", {},
           "extraordinary vertices become polar configurations (paper Fig. 14a)",
           [](Session& s) { return s.document().convertToPolar(false); });
  rows.document("model.ev-to-polar-pentagons", "with pentagons (14c)", {},
           "extraordinary vertices become poles ringed by pentagons (Fig. 14c)",
           [](Session& s) { return s.document().convertToPolar(true); });
  rows.document("model.ngon-to-fan", "N-gons to triangle fans", {},
           "faces of 5 or more sides become triangle fans around their centroids",
           [](Session& s) { return s.document().convertToFans(); });
  rows.document("model.eigenvector", "Show v_k as the model", {}, "the Spectrum panel's eigenvector net as the model",
           [](Session& s) { return s.document().showEigenvector(s.settings().spectrum); });
}

void addCameraCommands(Rows rows) {
  rows.add("camera.frame", "Frame model", {key('F')}, "frame the model", [](Session& s) { s.window().frameModel(); });
  const ViewPreset presets[] = {ViewPreset::Front, ViewPreset::Top, ViewPreset::Side, ViewPreset::Iso};
  for (int i = 0; i < 4; ++i) {
    const ViewPreset preset = presets[i];
    std::string label = viewPresetName(preset);
    label[0] = char(std::toupper(static_cast<unsigned char>(label[0])));
    rows.add(std::string("camera.") + viewPresetName(preset), label, {key(keys::kF1 + i)},
             std::string("view preset ") + viewPresetName(preset) + " (the model framed again)", [preset](Session& s) {
               // A preset turns the cameras and shows the whole model again (from a close-up too).
               for (int v = 0; v < kMaxViews; ++v) s.settings().camera(v).applyPreset(preset);
               s.window().frameModel();
             });
  }
  rows.add("camera.copy", "Copy", {key('C', kControl)}, "copy the camera as JSON", [](Session& s) {
    const ViewerSettings& settings = s.settings();
    const std::string json = cameraToJson(settings.camera(settings.activeView));
    s.window().setClipboard(json);
    s.notices().post(info("camera copied: " + json));
  });
  rows.add("camera.paste", "Paste", {key('V', kControl)}, "paste a camera copied as JSON", [](Session& s) {
    OrbitCamera& active = s.settings().camera(s.settings().activeView);
    std::string why;
    if (std::optional<OrbitCamera> camera = cameraFromJson(s.window().clipboard(), active, &why)) {
      active = *camera;
      s.notices().post(info("camera pasted"));
    } else {
      s.notices().post(error(why));
    }
  });
  rows.setting("camera.orthographic", "Orthographic", {key('O')}, "orthographic / perspective projection",
             [](ViewerSettings& settings) { setOrthographic(settings, !settings.camera(settings.activeView).orthographic); });
  rows.setting("camera.link", "Link cameras", {key('K')}, "link / unlink the cameras of the views",
             [](ViewerSettings& settings) { settings.linkCameras = !settings.linkCameras; });
}

void addLevelCommands(Rows rows) {
  // Keys 0-9 (and the keypad's) give levels 0-9; deeper ones are typed or stepped to.
  std::vector<KeyChord> digits;
  for (int level = 0; level <= 9; ++level) {
    digits.push_back(KeyChord{'0' + level, 0, 0, level});
    digits.push_back(KeyChord{keys::kKeypad0 + level, 0, 0, level});
  }
  rows.withArgument("level", "Level", std::move(digits),
                    "subdivision level N (all views when levels are linked, else the active one)",
                    CommandArgument{"N", 0, kMaxLevel, {}},
                    [](Session& s, int level) { requestLevel(s.settings(), s.status(), s.notices(), level); });
  // Levels past 9 (feature-adaptive refinement goes to 24): one level deeper / shallower.
  for (const int step : {1, -1}) {
    const bool deeper = step > 0;
    rows.add(deeper ? "level.deeper" : "level.shallower", deeper ? "Deeper" : "Shallower",
             deeper ? std::vector<KeyChord>{key(']'), key(keys::kPageUp), key(keys::kKeypadAdd)}
                    : std::vector<KeyChord>{key('['), key(keys::kPageDown), key(keys::kKeypadSubtract)},
             deeper ? "one level deeper (past 9 too, to the model's limit)" : "one level shallower",
             [step](Session& s) {
               ViewerSettings& settings = s.settings();
               requestLevel(settings, s.status(), s.notices(), settings.views[size_t(settings.activeView)].level + step);
             });
  }
}

void addViewCommands(Rows rows) {
  rows.setting("scheme.next", "Next scheme", {key('S')}, "next scheme of the active view (" + schemeLabels() + ")",
             [](ViewerSettings& settings) { cycleScheme(settings, settings.activeView, 1); });
  rows.setting("scheme.previous", "Previous scheme", {key('S', kShift)}, "previous scheme of the active view",
             [](ViewerSettings& settings) { cycleScheme(settings, settings.activeView, -1); });
  rows.setting("views.cycle", "Views", {key('V')}, "number of views 1..4",
             [](ViewerSettings& settings) { settings.viewCount = settings.viewCount % kMaxViews + 1; });
}

void addShadingCommands(Rows rows) {
  // The modes' table (pipeline/shading.h) gives the argument's names, aliases and labels and the
  // keys; the argument's value is an index into it.
  CommandArgument modes{"MODE", 0, int(shadingModes().size()) - 1, {}};
  std::vector<KeyChord> modeKeys;
  std::string labels;
  for (const ShadingModeInfo& mode : shadingModes()) {
    modeKeys.push_back(KeyChord{mode.key, 0, 0, int(modes.choices.size())});
    modes.choices.push_back({mode.name, mode.alias, mode.label});
    labels += (labels.empty() ? "" : " / ") + std::string(mode.label);
  }
  rows.withArgument("shade", "Shading", std::move(modeKeys), "shading: " + labels, std::move(modes),
                    [](Session& s, int mode) { s.settings().shading.mode = shadingModes()[size_t(mode)].mode; });
  rows.setting("colour.map", "Next colour map", {key('C')}, "next colour map (paper, coolwarm, viridis, magnitude)",
             [](ViewerSettings& settings) {
               settings.shading.colormap = static_cast<ShadingParams::ColorMap>((int(settings.shading.colormap) + 1) % 4);
             });
  rows.add("colour.automatic", "Automatic range", {key('A')}, "automatic colour range on / off",
             [](Session& s) { setAutomaticRange(s.settings(), s.status(), !s.settings().colour.automatic); });
}

void addDisplayCommands(Rows rows) {
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
    rows.setting(toggle.id, toggle.label, {key(toggle.key)}, lowercase(toggle.label) + " on / off",
               [flag = toggle.flag](ViewerSettings& settings) { settings.display.*flag = !(settings.display.*flag); });
}

void addWindowCommands(Rows rows) {
  rows.add("screenshot", "Screenshot", {key('X')}, "screenshot polarview_NNNN.png (colour bar and labels included)",
           [](Session& s) { s.window().takeScreenshot(); });
  rows.setting("panels", "Panels", {key(keys::kTab)}, "hide / show the panels",
             [](ViewerSettings& settings) { settings.showPanels = !settings.showPanels; });
  rows.setting("help", "Help", {KeyChord{0, 0, U'?', 0}}, "this help",
             [](ViewerSettings& settings) { settings.showHelp = !settings.showHelp; });
  rows.add("surface.measure", "Measure", {}, "area, enclosed volume and centroid of the active view's surface (Stats panel)",
           [](Session& s) { s.startMeasure(); });
  rows.setting("poles.inspect", "Inspect poles", {}, "open the Poles panel",
             [](ViewerSettings& settings) { settings.poleInspector.openRequested = true; });
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

bool keypadTwin(const KeyChord& chord) { return chord.key >= keys::kKeypad0 && chord.key <= keys::kKeypadAdd; }

bool enabledIn(const Command& command, const ViewerStatus& status) { return !command.enabled || command.enabled(status); }

// The key of `command` that gives `argument` (its first key for a row without one); nullptr: none.
const KeyChord* keyFor(const Command& command, int argument) {
  for (const KeyChord& chord : command.keys)
    if (!command.argument.taken() || chord.argument == argument) return &chord;
  return nullptr;
}

std::string_view trimmed(std::string_view text) {
  const size_t first = text.find_first_not_of(' ');
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(' ') - first + 1);
}

}  // namespace

std::string CommandArgument::accepted() const {
  if (choices.empty()) return std::to_string(min) + ".." + std::to_string(max);
  std::string names;
  for (const ArgumentChoice& choice : choices) names += (names.empty() ? "" : "|") + choice.name;
  return names;
}

std::optional<int> CommandArgument::parse(std::string_view text) const {
  if (choices.empty()) {
    if (text.empty() || text.size() > 3 || text.find_first_not_of("0123456789") != std::string_view::npos)
      return std::nullopt;
    const int value = std::stoi(std::string(text));
    if (value < min || value > max) return std::nullopt;
    return value;
  }
  const std::string name = lowercase(text);
  for (size_t i = 0; i < choices.size(); ++i)
    if (!name.empty() && (name == choices[i].name || name == choices[i].alias)) return int(i);
  return std::nullopt;
}

std::string CommandArgument::text(int value) const {
  return choices.empty() ? std::to_string(value) : choices[size_t(value)].name;
}

std::string CommandCall::text() const {
  return command->argument.taken() ? command->id + " " + command->argument.text(argument) : command->id;
}

const std::vector<GestureHelp>& gestureHelp() {
  static const std::vector<GestureHelp> gestures = {
      {"Left drag", "orbit around the pivot"},
      {"Right / middle drag, Shift+left drag", "pan"},
      {"Wheel", "zoom towards the point under the cursor"},
      {"Ctrl+left drag", "move the light (lit: key light; highlight / zebra: the light lines)"},
      {"Left drag on a control vertex",
       "with the control net shown (N): move the vertex in the view plane; every view follows"},
      {"Double-click", "set the pivot to the surface point under the cursor (and read it, as Alt+click)"},
      {"Alt+click",
       "read the surface point under the cursor: position, K, H, principal curvatures, patch (panel Point)"},
      {"Drop files", "open the first dropped .obj, list the others"},
  };
  return gestures;
}

CommandTable::CommandTable() {
  addFileCommands(Rows(commands_, "file"));
  addEditCommands(Rows(commands_, "edit"));
  addModelCommands(Rows(commands_, "model"));
  addCameraCommands(Rows(commands_, "camera"));
  addLevelCommands(Rows(commands_, "level"));
  addViewCommands(Rows(commands_, "views"));
  addShadingCommands(Rows(commands_, "shading"));
  addDisplayCommands(Rows(commands_, "display"));
  addWindowCommands(Rows(commands_, "window"));
}

const Command* CommandTable::find(std::string_view id) const {
  for (const Command& command : commands_)
    if (command.id == id) return &command;
  return nullptr;
}

const Command& CommandTable::at(std::string_view id) const {
  if (const Command* command = find(id)) return *command;
  throw std::out_of_range("no viewer command '" + std::string(id) + "' in the command table");
}

std::pair<std::string_view, std::string_view> CommandTable::split(std::string_view text) const {
  text = trimmed(text);
  const size_t space = text.find(' ');
  if (space != std::string_view::npos) return {text.substr(0, space), trimmed(text.substr(space))};
  // "level.7": the id before arguments, the argument after its last dot.
  const size_t dot = text.rfind('.');
  if (find(text) || dot == std::string_view::npos) return {text, {}};
  const Command* prefix = find(text.substr(0, dot));
  if (!prefix || !prefix->argument.taken()) return {text, {}};
  return {text.substr(0, dot), text.substr(dot + 1)};
}

std::optional<CommandCall> CommandTable::parse(std::string_view text, std::string* error) const {
  const auto fail = [error](std::string message) -> std::optional<CommandCall> {
    if (error) *error = std::move(message);
    return std::nullopt;
  };
  const auto [id, argument] = split(text);
  const Command* command = find(id);
  if (!command) return fail("unknown viewer command '" + std::string(trimmed(text)) + "'");
  const CommandArgument& accepts = command->argument;
  if (!accepts.taken()) {
    if (!argument.empty()) return fail(command->id + " takes no argument, got '" + std::string(argument) + "'");
    return CommandCall{command, 0};
  }
  const std::optional<int> value = accepts.parse(argument);
  if (!value)
    return fail(usage(*command) + ": " + accepts.placeholder + " is " + accepts.accepted() +
                (argument.empty() ? ", missing" : ", not '" + std::string(argument) + "'"));
  return CommandCall{command, *value};
}

std::optional<CommandCall> CommandTable::forKey(int code, int mods, const ViewerStatus& status) const {
  mods &= kShift | kControl | keys::kAlt;
  for (const int wanted : {mods, mods & ~kShift}) {
    for (const Command& command : commands_)
      for (const KeyChord& chord : command.keys)
        if (!chord.character && chord.key == code && chord.mods == wanted && enabledIn(command, status))
          return CommandCall{&command, chord.argument};
    if (wanted == (mods & ~kShift)) break;
  }
  return std::nullopt;
}

std::optional<CommandCall> CommandTable::forCharacter(char32_t character, const ViewerStatus& status) const {
  for (const Command& command : commands_)
    for (const KeyChord& chord : command.keys)
      if (chord.character == character && enabledIn(command, status)) return CommandCall{&command, chord.argument};
  return std::nullopt;
}

bool CommandTable::run(std::string_view text, Session& session) const {
  std::string error;
  const std::optional<CommandCall> call = parse(text, &error);
  if (!call) {
    session.notices().post(polarview::error(error));
    return false;
  }
  return run(*call, session);
}

bool CommandTable::run(const CommandCall& call, Session& session) const {
  if (!enabledIn(*call.command, session.status())) {
    session.notices().post(info(call.command->label + ": not available now"));
    return false;
  }
  call.command->action(session, call.argument);
  return true;
}

void CommandTable::runQueued(Session& session) const {
  // A command may queue another (it runs in the same pass, after those queued before it).
  while (!session.commandQueue().empty())
    for (const std::string& text : session.commandQueue().take()) run(text, session);
}

std::vector<HelpSection> CommandTable::helpSections() const {
  std::vector<HelpSection> sections;
  for (const Command& command : commands_) {
    auto section =
        std::find_if(sections.begin(), sections.end(), [&](const HelpSection& s) { return s.title == command.group; });
    if (section == sections.end()) section = sections.insert(sections.end(), HelpSection{command.group, {}});
    section->commands.push_back(&command);
  }
  return sections;
}

std::string CommandTable::keysText(const Command& command) {
  std::string text;
  const KeyChord* runStart = nullptr;  // a run of digit keys 0, 1, 2, ... reads "0 - 9"
  const KeyChord* previous = nullptr;
  auto closeRun = [&] {
    if (runStart && previous != runStart) text += " - " + keyName(*previous);
  };
  for (const KeyChord& chord : command.keys) {
    if (keypadTwin(chord)) continue;
    const bool digit = !chord.character && chord.key >= '0' && chord.key <= '9';
    if (digit && previous && runStart && chord.key == previous->key + 1 && chord.mods == previous->mods) {
      previous = &chord;
      continue;
    }
    closeRun();
    text += (text.empty() ? "" : " / ") + keyName(chord);
    runStart = digit ? &chord : nullptr;
    previous = &chord;
  }
  closeRun();
  return text;
}

std::string CommandTable::buttonLabel(const CommandCall& call) {
  const Command& command = *call.command;
  const CommandArgument& argument = command.argument;
  std::string label = command.label;
  if (argument.taken())
    label = argument.choices.empty() ? command.label + " " + argument.text(call.argument)
                                     : argument.choices[size_t(call.argument)].label;
  const KeyChord* chord = keyFor(command, call.argument);
  return chord ? label + " (" + keyName(*chord) + ")" : label;
}

std::string CommandTable::usage(const Command& command) {
  return command.argument.taken() ? command.id + " " + command.argument.placeholder : command.id;
}

const CommandTable& viewerCommands() {
  static const CommandTable table;
  return table;
}

std::string commandListText() {
  std::string text =
      "the viewer's commands by heading: id (and argument), keys, what it does; `view --do CMD[,CMD...]` runs them\n"
      "(an argument after a space or a dot: `level 7` or `level.7`, `shade gaussian` or `shade.gaussian`)\n";
  auto line = [&text](const std::string& name, const std::string& keys, const std::string& help) {
    text += "  " + name + std::string(name.size() < 28 ? 28 - name.size() : 1, ' ') + keys +
            std::string(keys.size() < 24 ? 24 - keys.size() : 1, ' ') + help + "\n";
  };
  for (const HelpSection& section : viewerCommands().helpSections()) {
    text += section.title + ":\n";
    for (const Command* command : section.commands) {
      const CommandArgument& argument = command->argument;
      line(CommandTable::usage(*command), CommandTable::keysText(*command),
           command->help + (argument.taken() ? " (" + argument.placeholder + ": " + argument.accepted() + ")" : ""));
      for (size_t i = 0; i < argument.choices.size(); ++i) {
        const KeyChord* chord = keyFor(*command, int(i));
        line(command->id + "." + argument.choices[i].name, chord ? keyName(*chord) : "", argument.choices[i].label);
      }
    }
  }
  return text;
}


}  // namespace polarview
