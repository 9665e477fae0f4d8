// The viewer's command queue: commands asked for by panels, keys and `view --do`, as text ("level 7",
// "camera.frame"), run in order once a frame by the command table (CommandTable::runQueued; this
// frame's run, when asked before it). Its own header so that the session owns a queue without
// depending on the table whose commands act on the session.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace polarview {

class CommandQueue {
 public:
  void push(std::string_view text) { texts_.emplace_back(text); }
  bool empty() const { return texts_.empty(); }
  // The commands queued so far, in order; the queue is empty after.
  std::vector<std::string> take() { return std::exchange(texts_, {}); }

 private:
  std::vector<std::string> texts_;
};

inline void queueCommand(CommandQueue& queue, std::string_view text) { queue.push(text); }

}  // namespace polarview
