// The viewer's one table of commands (F3D's idea): each row names a command (its id), its argument
// if it takes one, the keys that run it, its help line and group, when it is enabled and what it
// does. Hotkeys, the help window, `polarview help keys`, the panels' buttons and `view --do` all go
// through it, so adding a command is one row here (and its line in docs/viewer.md).
//
// A command is named as text: its id, then its argument where it takes one ("level 7", "shade
// gaussian"); "level.7" and "shade.gaussian", the ids before arguments, are the same commands.
// Keys bind to a row with a fixed argument (7: level 7, G: shade gaussian).
//
// Commands act on a Session (session.h): its settings, its document (files, edits, exports) and,
// for what needs the window (clipboard, framing in the view's shape, screenshots), its
// WindowServices. No command needs a method of its own on an interface.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "session/command_queue.h"
#include "session/viewer_status.h"

namespace polarview {

class Session;

// A key with modifier bits (session/keys.h), or a typed character such as '?'; on a row that takes
// an argument, the argument the key gives (7 for key 7 of `level`).
struct KeyChord {
  int key = 0;
  int mods = 0;
  char32_t character = 0;
  int argument = 0;
};

// A named value of an argument: shade's "gaussian" (another accepted name: "zebra" for "reflection"),
// and the label its button shows ("Gaussian K").
struct ArgumentChoice {
  std::string name;
  std::string alias;
  std::string label;
};

// What a row's argument accepts: an integer from min to max, or one of `choices` (the value is its
// index). A row whose max is below its min takes none.
struct CommandArgument {
  std::string placeholder;  // "N", "MODE": how help and messages name it
  int min = 0, max = -1;
  std::vector<ArgumentChoice> choices;

  bool taken() const { return max >= min; }
  // "0..24", or the names: "shaded|gaussian|mean|highlight|reflection".
  std::string accepted() const;
  // The value `text` names (a number, or a choice's name or alias, any case); none: not accepted.
  std::optional<int> parse(std::string_view text) const;
  // "7", "gaussian".
  std::string text(int value) const;
};

struct Command {
  std::string id;     // what `view --do`, the panels and help name: "level", "camera.frame"
  std::string label;  // a button's text ("Frame model"); a choice's label where it has one
  std::vector<KeyChord> keys;
  std::string help;   // its line in the help window and `polarview help keys`
  std::string group;  // the help's heading it is listed under ("file", "camera", "level", ...)
  CommandArgument argument;
  std::function<bool(const ViewerStatus&)> enabled;  // null: always (else by what the session reports)
  std::function<void(Session&, int argument)> action;
};

// A row with its argument: what a key, a button or a line of `view --do` asks for.
struct CommandCall {
  const Command* command = nullptr;
  int argument = 0;
  // "level 7", "shade gaussian", "camera.frame": what queueCommand takes and parse reads back.
  std::string text() const;
};

// The rows of one help heading, in table order.
struct HelpSection {
  std::string title;
  std::vector<const Command*> commands;
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
  // The row `id` names exactly ("level", not "level.7"); nullptr: none.
  const Command* find(std::string_view id) const;
  // The row `id` names; throws std::out_of_range when there is none (code that names a command
  // fails loudly rather than drawing no button).
  const Command& at(std::string_view id) const;
  // "level 7", "level.7", "camera.frame": the row and its argument. None: `error` (when given) says
  // why in one line, naming what is accepted ("level N: N is 0..24, not '30'").
  std::optional<CommandCall> parse(std::string_view text, std::string* error = nullptr) const;
  // The first enabled command bound to `key` with exactly `mods` (Shift, Control, Alt); failing
  // that, to `key` with the same mods but Shift (Shift+G is G).
  std::optional<CommandCall> forKey(int key, int mods, const ViewerStatus& status) const;
  std::optional<CommandCall> forCharacter(char32_t character, const ViewerStatus& status) const;
  // Runs the command `text` names when it is enabled; else the notice says why. False: unknown,
  // a bad argument, or disabled.
  bool run(std::string_view text, Session& session) const;
  bool run(const CommandCall& call, Session& session) const;
  // Runs and clears the commands queued in the session (panels, keys, `view --do`), in order: once
  // a frame, by the frame loop (the session does not call the table, which acts on it).
  void runQueued(Session& session) const;
  // The rows under their help headings, the headings in the order the table first uses them.
  std::vector<HelpSection> helpSections() const;

  // The command's keys: "Ctrl+Shift+Z / Ctrl+Y", "0 - 9" (keypad twins left out).
  static std::string keysText(const Command& command);
  // "Frame model (F)", "Gaussian K (G)": a button's label with its first key.
  static std::string buttonLabel(const CommandCall& call);
  // "level N", "camera.frame": the row as help and usage name it.
  static std::string usage(const Command& command);

 private:
  // The id and the argument text: "level 7" and "level.7" give ("level", "7"); "camera.frame"
  // gives ("camera.frame", "").
  std::pair<std::string_view, std::string_view> split(std::string_view text) const;

  std::vector<Command> commands_;
};

// The table every viewer uses (built once).
const CommandTable& viewerCommands();

// `polarview help keys`: every row under its heading (id, keys, help), and a line per named
// argument's choice ("shade.gaussian  G  Gaussian K").
std::string commandListText();

}  // namespace polarview
