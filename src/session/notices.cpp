// The viewer's notices (notices.h).
#include "session/notices.h"

#include <utility>

namespace polarview {

void Notices::post(Notice notice) {
  // The same text again keeps its clock, as when the line was a plain string compared each frame.
  if (notice.text != latest_.text) since_ = std::chrono::steady_clock::now();
  history_.push_back(notice);
  if (history_.size() > kHistory) history_.pop_front();
  latest_ = std::move(notice);
}

void Notices::withdraw(std::string_view prefix) {
  if (latest_.text.compare(0, prefix.size(), prefix) == 0) latest_ = {};
}

void Notices::expire(std::chrono::steady_clock::time_point now) {
  if (!latest_.text.empty() && now - since_ > kLifetime) latest_ = {};
}

}  // namespace polarview
