// The viewer's messages to the user (a file opened, a level refused, a camera copied), typed, with
// one owner: commands, the document's results and the window post them; the status bar shows the
// latest until it expires. Errors also stay where their panel shows them (FileStatus::error,
// EditStatus::error); a notice is the short-lived line.
#pragma once

#include <chrono>
#include <deque>
#include <string>
#include <string_view>

namespace polarview {

struct Notice {
  enum class Kind { Info, Warning, Error };
  Kind kind = Kind::Info;
  std::string text;
};

inline Notice info(std::string text) { return {Notice::Kind::Info, std::move(text)}; }
inline Notice warning(std::string text) { return {Notice::Kind::Warning, std::move(text)}; }
inline Notice error(std::string text) { return {Notice::Kind::Error, std::move(text)}; }

class Notices {
 public:
  // How long the latest notice is shown (a newer one restarts the clock).
  static constexpr std::chrono::seconds kLifetime{8};
  // How many past notices history() keeps.
  static constexpr size_t kHistory = 20;

  void post(Notice notice);
  // The notice shown now; its text is empty when none is.
  const Notice& latest() const { return latest_; }
  const std::string& text() const { return latest_.text; }
  // The notices posted so far, oldest first (the last kHistory).
  const std::deque<Notice>& history() const { return history_; }
  // Hides the shown notice when its text starts with `prefix` (a refusal made stale by a success).
  void withdraw(std::string_view prefix);
  // Hides the shown notice once it has been shown kLifetime.
  void expire(std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now());

 private:
  Notice latest_;
  std::chrono::steady_clock::time_point since_;
  std::deque<Notice> history_;
};

}  // namespace polarview
