// The viewer's one table of commands (F3D's idea): each row names a command (its id), the keys
// that run it, the help text, when it is enabled and what it does. Hotkeys, the help window, the
// panels' buttons and `view --do id,...` all go through it, so adding a command is one row here.
// Commands act on the ViewerState and, for what needs more (files, edits, exports, the camera on
// the clipboard, screenshots), on a CommandHost: the window application.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "session/viewer_state.h"

namespace polarview {

// What commands ask of the application beyond the state: the document's operations and those
// that need the window (clipboard, framing in the view's shape, screenshots).
class CommandHost {
 public:
  virtual ~CommandHost() = default;
  virtual void openFile(const std::string& path) = 0;  // in the background; the model stays on failure
  virtual void reloadModel() = 0;
  virtual void loadDefaultModel() = 0;
  virtual void undoModelReplacement() = 0;  // back to the model shown before the last replacement
  virtual void undo() = 0;                  // the last vertex drag, or (none left) the model replacement
  virtual void redo() = 0;
  virtual void resetEdits() = 0;
  virtual void saveEditedMesh() = 0;
  virtual void exportSurface(bool bezierView) = 0;  // .bv, or the refined control mesh as OBJ
  virtual void openPlaylistEntry(int index) = 0;    // wraps around
  virtual void convertToPolar(bool pentagons) = 0;  // paper Fig. 14 a / c
  virtual void convertToFans() = 0;                 // n-gons into triangle fans (core/mesh/ngon_to_fan.h)
  virtual void showEigenvector() = 0;               // the Spectrum panel's v_k as the model
  virtual void frameModel() = 0;
  virtual void setClipboard(const std::string& text) = 0;
  virtual std::string clipboard() = 0;
  virtual void takeScreenshot() = 0;
};

// A key with modifier bits (session/keys.h), or a typed character such as '?'.
struct KeyChord {
  int key = 0;
  int mods = 0;
  char32_t character = 0;
};

struct Command {
  std::string id;     // "shade.gaussian": what `view --do` and the panels name
  std::string label;  // a button's text ("Gaussian K")
  std::vector<KeyChord> keys;
  std::string help;      // the help window's line; empty: listed under another row's help
  std::string helpKeys;  // the keys column when one line stands for several rows ("0 - 9")
  std::function<bool(const ViewerState&)> enabled;  // null: always
  std::function<void(ViewerState&, CommandHost&)> action;
};

// A mouse gesture of the help window (not a command: the input handler reads the mouse itself).
struct GestureHelp {
  const char* gesture;
  const char* action;
};
const std::vector<GestureHelp>& gestureHelp();

class CommandTable {
 public:
  CommandTable();  // the viewer's commands
  const std::vector<Command>& commands() const { return commands_; }
  const Command* find(std::string_view id) const;
  // The first enabled command bound to `key` with exactly `mods` (Shift, Control, Alt); failing
  // that, to `key` with the same mods but Shift (Shift+G is G). nullptr: none.
  const Command* forKey(int key, int mods, const ViewerState& state) const;
  const Command* forCharacter(char32_t character, const ViewerState& state) const;
  // Runs command `id` when it is enabled; else the notice says why. False: unknown or disabled.
  bool run(std::string_view id, ViewerState& state, CommandHost& host) const;
  // Runs and clears the commands queued in `state` (panels, keys, `view --do`), in order.
  void runQueued(ViewerState& state, CommandHost& host) const;
  // The command's keys: "Ctrl+Shift+Z / Ctrl+Y" (keypad twins left out).
  static std::string keysText(const Command& command);
  // The help window's keys column: the row's helpKeys where one line stands for several ("0 - 9").
  static std::string helpKeysText(const Command& command);
  // "Gaussian K (G)": a button's label with its first key.
  static std::string buttonLabel(const Command& command);

 private:
  std::vector<Command> commands_;
};

// The table every viewer uses (built once).
const CommandTable& viewerCommands();

// "shade.gaussian": the command that sets a shading mode.
std::string shadingCommandId(ShadingParams::Mode mode);

// Queues command `id` for the app's next runQueued (this frame's, when asked before it).
void queueCommand(ViewerState& state, std::string id);

}  // namespace polarview
