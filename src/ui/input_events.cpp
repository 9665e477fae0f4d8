#include "ui/input_events.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <utility>

#include "session/keys.h"

namespace polarview {

std::vector<InputEvent> InputEventQueue::takeFrame() {
  std::vector<InputEvent> frame;
  std::vector<std::pair<InputEvent::Kind, int>> changed;  // keys and buttons changed this frame
  while (!pending_.empty()) {
    const InputEvent& event = pending_.front();
    const bool isState = event.kind == InputEvent::Kind::Key || event.kind == InputEvent::Kind::MouseButton;
    if (isState) {
      const std::pair<InputEvent::Kind, int> id{event.kind, event.code};
      if (std::find(changed.begin(), changed.end(), id) != changed.end()) break;  // next frame
      changed.push_back(id);
    }
    frame.push_back(event);
    pending_.pop_front();
  }
  return frame;
}

}  // namespace polarview

// The command table names keys without GLFW (session/keys.h): its codes must be GLFW's, which the
// window hands over unchanged.
static_assert(polarview::keys::kTab == GLFW_KEY_TAB && polarview::keys::kPageUp == GLFW_KEY_PAGE_UP &&
              polarview::keys::kPageDown == GLFW_KEY_PAGE_DOWN && polarview::keys::kF1 == GLFW_KEY_F1 &&
              polarview::keys::kF4 == GLFW_KEY_F4 && polarview::keys::kKeypad0 == GLFW_KEY_KP_0 &&
              polarview::keys::kKeypadSubtract == GLFW_KEY_KP_SUBTRACT && polarview::keys::kKeypadAdd == GLFW_KEY_KP_ADD);
static_assert(polarview::keys::kShift == GLFW_MOD_SHIFT && polarview::keys::kControl == GLFW_MOD_CONTROL &&
              polarview::keys::kAlt == GLFW_MOD_ALT);
static_assert('A' == GLFW_KEY_A && '0' == GLFW_KEY_0 && '[' == GLFW_KEY_LEFT_BRACKET && ']' == GLFW_KEY_RIGHT_BRACKET);
