// The command table without a window: every key reaches the command it names, commands with
// arguments read "level 7" and "level.7" alike and refuse bad arguments with one line, buttons and
// help come from the same rows, every id the code names is a row, and commands act on the
// session's state and document, and on the window for the rest, as the viewer's keys did.
#include <doctest/doctest.h>

#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "session/command_ids.h"
#include "session/command_table.h"
#include "session/keys.h"
#include "session/session.h"

using namespace polarview;

namespace {

// The window's part, recorded.
struct RecordingWindow : WindowServices {
  std::vector<std::string> calls;
  std::string clipboardText;
  void frameModel() override { calls.push_back("frame"); }
  void setClipboard(const std::string& text) override { clipboardText = text; }
  std::string clipboard() override { return clipboardText; }
  void takeScreenshot() override { calls.push_back("screenshot"); }
};

SessionOptions quiet() {
  SessionOptions options;
  options.persistRecent = false;  // tests leave ~/.config alone
  options.prepareNextLevel = false;
  return options;
}

std::string pressed(const ViewerStatus& status, int key, int mods = 0) {
  const std::optional<CommandCall> call = viewerCommands().forKey(key, mods, status);
  REQUIRE(call.has_value());
  return call->text();
}

// What `text` parses to, as "id argument", or the refusal.
std::string parsed(const std::string& text) {
  std::string error;
  const std::optional<CommandCall> call = viewerCommands().parse(text, &error);
  if (!call) return "error: " + error;
  return call->command->id + " " + std::to_string(call->argument);
}

}  // namespace

TEST_CASE(
    "command table: ids are unique, every row has an action, a help line and a group, and no chord runs two commands") {
  const CommandTable& table = viewerCommands();
  std::set<std::string> ids;
  std::set<std::tuple<int, int, char32_t, bool>> chords;
  for (const Command& command : table.commands()) {
    CAPTURE(command.id);
    CHECK(ids.insert(command.id).second);
    CHECK(command.action);
    CHECK_FALSE(command.label.empty());
    CHECK_FALSE(command.help.empty());
    CHECK_FALSE(command.group.empty());
    // No id reads as another row with an argument ("level.deeper" is a row: "deeper" is no level).
    const size_t dot = command.id.rfind('.');
    if (const Command* prefix = dot == std::string::npos ? nullptr : table.find(command.id.substr(0, dot)))
      CHECK_FALSE(prefix->argument.parse(command.id.substr(dot + 1)).has_value());
    // Two rows may share a key only when one of them is enabled on a condition (PageDown: the
    // dropped files when there are several, else the level).
    for (const KeyChord& chord : command.keys) {
      CHECK(chords.insert({chord.key, chord.mods, chord.character, bool(command.enabled)}).second);
      if (command.argument.taken())
        CHECK(command.argument.parse(command.argument.text(chord.argument)) == chord.argument);
    }
  }
  CHECK(table.find("shade") != nullptr);
  CHECK(table.find("shade.gaussian") == nullptr);  // a row with an argument, not a row of its own
  CHECK(table.find("no.such.command") == nullptr);
}

TEST_CASE("command table: every id the panels, the input code and the app name is a row") {
  for (const std::string_view id : command_ids::kAll) {
    CAPTURE(id);
    CHECK(viewerCommands().find(id) != nullptr);
  }
  // Any other id fails loudly (commandButton draws with at()).
  CHECK_THROWS_AS(viewerCommands().at("no.such.command"), std::out_of_range);
}

TEST_CASE("command table: the viewer's keys reach their commands, with the argument the key gives") {
  ViewerStatus status;
  CHECK(pressed(status, 'G') == "shade gaussian");
  CHECK(pressed(status, 'G', keys::kShift) == "shade gaussian");  // Shift alone does not change a key
  CHECK(pressed(status, 'L') == "shade shaded");
  CHECK(pressed(status, 'S') == "scheme.next");
  CHECK(pressed(status, 'S', keys::kShift) == "scheme.previous");
  CHECK(pressed(status, 'S', keys::kControl) == "edit.save");
  CHECK(pressed(status, 'Z') == "shade reflection");
  CHECK(pressed(status, 'Z', keys::kControl) == "edit.undo");
  CHECK(pressed(status, 'Z', keys::kControl | keys::kShift) == "edit.redo");
  CHECK(pressed(status, 'Y', keys::kControl) == "edit.redo");
  CHECK(pressed(status, keys::kF2) == "camera.top");
  CHECK(pressed(status, '7') == "level 7");
  CHECK(pressed(status, '0') == "level 0");
  CHECK(pressed(status, keys::kKeypad0 + 7) == "level 7");
  CHECK_FALSE(viewerCommands().forKey('G', keys::kControl, status).has_value());  // Ctrl+G: nothing
  CHECK(viewerCommands().forCharacter(U'?', status)->text() == "help");
  // PageDown steps the level, or the dropped files when there are several.
  CHECK(pressed(status, keys::kPageDown) == "level.shallower");
  status.file.playlist = {"a.obj", "b.obj"};
  CHECK(pressed(status, keys::kPageDown) == "file.next");
  CHECK(pressed(status, keys::kPageUp) == "file.previous");
}

TEST_CASE("command table: a command with an argument reads the same after a space or a dot") {
  CHECK(parsed("level 7") == "level 7");
  CHECK(parsed("level.7") == "level 7");
  CHECK(parsed("  level   7 ") == "level 7");
  CHECK(parsed("level 24") == "level 24");
  CHECK(parsed("shade gaussian") == "shade 1");
  CHECK(parsed("shade.gaussian") == "shade 1");
  CHECK(parsed("shade Gaussian") == "shade 1");
  CHECK(parsed("shade zebra") == parsed("shade reflection"));  // the modes' aliases too
  CHECK(parsed("shade.lit") == parsed("shade.shaded"));
  CHECK(parsed("level.deeper") == "level.deeper 0");  // a row of its own, not level with "deeper"
  CHECK(parsed("camera.frame") == "camera.frame 0");
  // What a call reads back as is what parse takes.
  const std::optional<CommandCall> call = viewerCommands().parse("shade.highlight");
  REQUIRE(call);
  CHECK(call->text() == "shade highlight");
  CHECK(parsed(call->text()) == parsed("shade.highlight"));
}

TEST_CASE("command table: bad arguments are refused with one line naming what is accepted") {
  CHECK(parsed("level 25") == "error: level N: N is 0..24, not '25'");
  CHECK(parsed("level.-1") == "error: level N: N is 0..24, not '-1'");
  CHECK(parsed("level x") == "error: level N: N is 0..24, not 'x'");
  CHECK(parsed("level") == "error: level N: N is 0..24, missing");
  CHECK(parsed("shade foo") == "error: shade MODE: MODE is shaded|gaussian|mean|highlight|reflection, not 'foo'");
  CHECK(parsed("shade.foo") == parsed("shade foo"));
  CHECK(parsed("camera.frame 3") == "error: camera.frame takes no argument, got '3'");
  CHECK(parsed("no.such.command") == "error: unknown viewer command 'no.such.command'");
  CHECK(parsed("") == "error: unknown viewer command ''");
  // The names accepted are the shading modes' table's (pipeline/shading.h), not a list of their own.
  const CommandArgument& modes = viewerCommands().at("shade").argument;
  REQUIRE(modes.choices.size() == shadingModes().size());
  for (size_t i = 0; i < modes.choices.size(); ++i) CHECK(modes.choices[i].name == shadingModes()[i].name);
}

TEST_CASE(
    "command table: commands change the state as the keys always did, and ask the document and window for the rest") {
  RecordingWindow window;
  Session session(quiet(), window);
  ViewerSettings& settings = session.settings();
  ViewerStatus& status = session.status();
  const CommandTable& table = viewerCommands();
  for (ViewStatus& view : status.views) view.deepestLevel = 6;
  CHECK(table.run("shade mean", session));
  CHECK(settings.shading.mode == ShadingParams::Mode::Mean);
  CHECK(table.run("shade.highlight", session));
  CHECK(settings.shading.mode == ShadingParams::Mode::Highlight);
  CHECK(table.run("level 5", session));
  for (const View& view : settings.views) CHECK(view.level == 5);  // levels linked
  CHECK(table.run("level.4", session));
  CHECK(settings.views[0].level == 4);
  CHECK(table.run("level.deeper", session));
  CHECK(table.run("level.deeper", session));
  CHECK(settings.views[0].level == 6);
  CHECK(table.run("level.deeper", session));  // past the deepest level: refused, said
  CHECK(settings.views[0].level == 6);
  CHECK(session.notices().text().find("level 7 refused") == 0);
  // A bad argument: the notice says why, nothing changes.
  CHECK_FALSE(table.run("level 30", session));
  CHECK(session.notices().text() == "level N: N is 0..24, not '30'");
  CHECK(settings.views[0].level == 6);
  const SchemeChoice before = settings.views[0].scheme;
  table.run("scheme.next", session);
  table.run("scheme.previous", session);
  CHECK(settings.views[0].scheme == before);
  table.run("show.net", session);
  CHECK(settings.display.controlNet);
  table.run("views.cycle", session);
  CHECK(settings.viewCount == 2);

  table.run("camera.copy", session);
  CHECK(window.clipboardText.find("\"target\"") != std::string::npos);
  const OrbitCamera copied = settings.camera(0);
  settings.camera(0).orbit(40.0f, 10.0f);
  table.run("camera.paste", session);
  CHECK(settings.camera(0).eye().x == doctest::Approx(copied.eye().x));
  for (const char* command : {"camera.iso", "screenshot"}) table.run(command, session);
  CHECK(window.calls == std::vector<std::string>{"frame", "screenshot"});

  // The document's operations run on the session's document.
  CHECK(table.run("edit.undo", session));
  CHECK(session.notices().text() == "nothing to undo");
  settings.file.pathField = "no such model.obj";
  CHECK(table.run("file.open", session));
  CHECK(status.file.loadingPath == "no such model.obj");
  // Disabled: stepping dropped files without a list.
  CHECK_FALSE(table.run("file.next", session));
  CHECK_FALSE(table.run("no.such.command", session));
  CHECK(session.notices().text() == "unknown viewer command 'no.such.command'");
}

TEST_CASE("command table: queued commands run once, in order") {
  RecordingWindow window;
  Session session(quiet(), window);
  ViewerSettings& settings = session.settings();
  session.queueCommand("shade gaussian");
  session.queueCommand("shade.highlight");
  session.queueCommand("screenshot");
  viewerCommands().runQueued(session);
  CHECK(settings.shading.mode == ShadingParams::Mode::Highlight);
  CHECK(window.calls == std::vector<std::string>{"screenshot"});
  CHECK(session.commandQueue().empty());
  viewerCommands().runQueued(session);
  CHECK(window.calls.size() == 1);
}

TEST_CASE("command table: button texts and keys come from the rows") {
  const CommandTable& table = viewerCommands();
  CHECK(CommandTable::buttonLabel({&table.at("camera.frame"), 0}) == "Frame model (F)");
  CHECK(CommandTable::buttonLabel({&table.at("shade"), 1}) == "Gaussian K (G)");
  CHECK(CommandTable::buttonLabel({&table.at("level"), 12}) == "Level 12");
  CHECK(CommandTable::buttonLabel({&table.at("level"), 3}) == "Level 3 (3)");
  CHECK(CommandTable::keysText(table.at("edit.redo")) == "Ctrl+Shift+Z / Ctrl+Y");
  CHECK(CommandTable::keysText(table.at("level")) == "0 - 9");
  CHECK(CommandTable::keysText(table.at("shade")) == "L / G / M / H / Z");
  CHECK(CommandTable::usage(table.at("level")) == "level N");
  CHECK(table.at("scheme.next").help.find("CC, C2PS, C2PS-U, RTS, RTS-U, BPS") != std::string::npos);
}

TEST_CASE("command table: help lists every row once, under its group's heading") {
  const CommandTable& table = viewerCommands();
  std::vector<const Command*> listed;
  std::set<std::string> titles;
  for (const HelpSection& section : table.helpSections()) {
    CHECK(titles.insert(section.title).second);  // one heading a group
    for (const Command* command : section.commands) {
      CHECK(command->group == section.title);
      listed.push_back(command);
    }
  }
  REQUIRE(listed.size() == table.commands().size());
  for (size_t i = 0; i < listed.size(); ++i) CHECK(listed[i] == &table.commands()[i]);
  for (const char* group : {"file", "edit", "camera", "level", "views", "shading", "display"})
    CHECK(titles.count(group));
  // `polarview help keys`: every row by its usage and keys, a named argument's choices as the
  // dotted ids scripts use (tests/cli/viewer_do.sh reads "shade.gaussian  G").
  const std::string text = commandListText();
  for (const Command& command : table.commands()) {
    CAPTURE(command.id);
    CHECK(text.find("  " + CommandTable::usage(command) + " ") != std::string::npos);
  }
  CHECK(text.find("\nshading:\n") != std::string::npos);
  CHECK(text.find("  shade.gaussian              G ") != std::string::npos);
  CHECK(text.find("  level N                     0 - 9 ") != std::string::npos);
}

TEST_CASE("command table: docs/viewer.md lists every command") {
  std::ifstream in(std::string(POLARVIEW_ASSET_DIR) + "/../docs/viewer.md");
  REQUIRE(in.good());
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const Command& command : viewerCommands().commands()) {
    CAPTURE(command.id);
    CHECK(doc.find("`" + CommandTable::usage(command) + "`") != std::string::npos);
  }
}
