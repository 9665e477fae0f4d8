// Window input events, replayed to Dear ImGui at most one state change per key or mouse button per
// frame. ImGui 1.86 (Debian 12) reads key and button state once a frame, so a press and release
// that both arrive between two frames vanish: quick taps of Enter or Backspace in a text field, and
// fast double-clicks, were lost (more so at the software renderer's 50-500 ms a frame). Queued
// events are handed out in order, a frame's share ending before the second change of the same key
// or button; the rest wait for the next frame (the "trickle" later ImGui versions do themselves).
// Plain data: no GLFW or GL calls (the app's callbacks fill it and apply what it hands out).
#pragma once

#include <deque>
#include <vector>

namespace polarview {

struct InputEvent {
  enum class Kind { Key, Char, MouseButton, Scroll };
  Kind kind = Kind::Key;
  int code = 0;       // Key: GLFW key; MouseButton: button; Char: code point
  int scancode = 0;   // Key only
  int action = 0;     // Key / MouseButton: GLFW_PRESS, GLFW_RELEASE or GLFW_REPEAT
  int mods = 0;       // Key / MouseButton: modifier bits
  double dx = 0, dy = 0;  // Scroll offsets
  // MouseButton: the cursor (window coordinates) when the button changed. ImGui 1.86 reads the
  // cursor once a frame, so a press followed by motion within one frame would otherwise land
  // where the cursor went, not where it was pressed (a quick drag would miss a control vertex).
  double x = 0, y = 0;
};

class InputEventQueue {
 public:
  void push(const InputEvent& event) { pending_.push_back(event); }
  bool empty() const { return pending_.empty(); }
  // This frame's events, in arrival order: all of them up to (not including) the first that would
  // change a key or mouse button already changed in this frame. [O(events)]
  std::vector<InputEvent> takeFrame();

 private:
  std::deque<InputEvent> pending_;
};

}  // namespace polarview
