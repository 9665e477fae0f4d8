// The input event queue hands ImGui at most one change per key or mouse button a frame, in order.
#include <doctest/doctest.h>

#include <GLFW/glfw3.h>

#include "ui/input_events.h"

namespace polarview {
namespace {

InputEvent key(int code, int action) { return {InputEvent::Kind::Key, code, 0, action, 0}; }
InputEvent button(int code, int action) { return {InputEvent::Kind::MouseButton, code, 0, action, 0}; }
InputEvent character(int c) { return {InputEvent::Kind::Char, c}; }

TEST_CASE("input events: a tap between two frames becomes a press in one frame and a release in the next") {
  InputEventQueue queue;
  // Three quick Backspaces, a typed 'a', then Enter, all before the next frame.
  for (int i = 0; i < 3; ++i) {
    queue.push(key(GLFW_KEY_BACKSPACE, GLFW_PRESS));
    queue.push(key(GLFW_KEY_BACKSPACE, GLFW_RELEASE));
  }
  queue.push(character('a'));
  queue.push(key(GLFW_KEY_ENTER, GLFW_PRESS));
  queue.push(key(GLFW_KEY_ENTER, GLFW_RELEASE));
  std::vector<std::vector<InputEvent>> frames;
  while (!queue.empty()) frames.push_back(queue.takeFrame());
  // Each Backspace press and release gets its own frame, so ImGui sees three presses; the order
  // of all events is kept (the 'a' after the last Backspace, Enter after the 'a').
  REQUIRE(frames.size() == 7);
  int presses = 0;
  for (const auto& frame : frames) {
    int backspaceChanges = 0;
    for (const InputEvent& e : frame) {
      backspaceChanges += e.kind == InputEvent::Kind::Key && e.code == GLFW_KEY_BACKSPACE;
      presses += e.kind == InputEvent::Kind::Key && e.code == GLFW_KEY_BACKSPACE && e.action == GLFW_PRESS;
    }
    CHECK(backspaceChanges <= 1);
  }
  CHECK(presses == 3);
  const std::vector<InputEvent>& last = frames[5];  // release of the 3rd Backspace, 'a', Enter press
  REQUIRE(last.size() == 3);
  CHECK(last[1].kind == InputEvent::Kind::Char);
  CHECK(last[2].code == GLFW_KEY_ENTER);
  CHECK(frames[6].size() == 1);  // Enter's release
}

TEST_CASE("input events: a fast double-click reaches ImGui as press, release, press over three frames") {
  InputEventQueue queue;
  for (int i = 0; i < 2; ++i) {
    queue.push(button(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS));
    queue.push(button(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE));
  }
  queue.push({InputEvent::Kind::Scroll, 0, 0, 0, 0, 0.0, 1.0});
  std::vector<int> actions;
  int frames = 0;
  while (!queue.empty()) {
    const std::vector<InputEvent> frame = queue.takeFrame();
    ++frames;
    int changes = 0;
    for (const InputEvent& e : frame)
      if (e.kind == InputEvent::Kind::MouseButton) {
        ++changes;
        actions.push_back(e.action);
      }
    CHECK(changes <= 1);
  }
  CHECK(frames == 4);
  CHECK(actions == std::vector<int>{GLFW_PRESS, GLFW_RELEASE, GLFW_PRESS, GLFW_RELEASE});
  // Different keys change in the same frame (a chord is not split).
  queue.push(key(GLFW_KEY_LEFT_CONTROL, GLFW_PRESS));
  queue.push(key(GLFW_KEY_Z, GLFW_PRESS));
  CHECK(queue.takeFrame().size() == 2);
}

}  // namespace
}  // namespace polarview
