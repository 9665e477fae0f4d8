#include "ui/input_events.h"

#include <algorithm>
#include <utility>

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
