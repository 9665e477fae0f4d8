// One background job type for the viewer's worker threads (refinements, reading a model, exports, pole
// inspections, levels made ahead): at most one run at a time, polled once a frame by its owner.
// A std::future from std::async blocks on destruction, so a job still running when its owner goes
// is waited for, never abandoned with references into freed memory.
#pragma once

#include <chrono>
#include <exception>
#include <future>
#include <optional>
#include <utility>

namespace polarview {

template <class Result>
class BackgroundJob {
 public:
  // Starts `work` on a worker thread; only when nothing runs (returns false otherwise).
  template <class Work>
  bool start(Work&& work) {
    if (running()) return false;
    future_ = std::async(std::launch::async, std::forward<Work>(work));
    started_ = std::chrono::steady_clock::now();
    return true;
  }
  bool running() const { return future_.valid(); }
  bool finished() const { return running() && future_.wait_for(std::chrono::seconds(0)) == std::future_status::ready; }
  double runningSeconds() const {
    return running() ? std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count() : 0.0;
  }
  // The result once the job has finished (rethrowing what the work threw); nullopt while it runs
  // or when none was started.
  std::optional<Result> poll() {
    if (!finished()) return std::nullopt;
    return future_.get();
  }
  // Blocks until a started job finishes and drops its result (an owner going away).
  void join() {
    if (running()) future_.wait();
  }
  // Blocks until a started job finishes; its result (or exception) as poll gives it.
  std::optional<Result> wait() {
    if (!running()) return std::nullopt;
    future_.wait();
    return future_.get();
  }

 private:
  std::future<Result> future_;
  std::chrono::steady_clock::time_point started_;
};

}  // namespace polarview
