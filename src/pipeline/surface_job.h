// One view's surface built off the GL thread: at most one job a view in flight (std::async), so
// the window never waits on it.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "pipeline/background_job.h"
#include "pipeline/surface_build.h"

namespace polarview {

// One view's background job (a BackgroundJob with its key): at most one in flight; a newer
// request waits for it (jobs are never dropped, only their results).
class SurfaceJob {
 public:
  bool running() const { return job_.running(); }
  const SurfaceKey& runningKey() const { return key_; }
  double runningSeconds() const { return job_.runningSeconds(); }
  // Starts building `key` (only when nothing is running), from `reuse` where it fits (buildSurface).
  void start(const Model& model, const SurfaceKey& key, size_t faceBudget, std::shared_ptr<SurfaceHierarchy> reuse = nullptr);
  // The finished result, or nullopt while running / idle. On failure: the error message.
  struct Outcome {
    std::shared_ptr<const BuiltSurface> surface;
    std::string error;
    SurfaceKey key;
  };
  std::optional<Outcome> poll();
  // Blocks until the running job (if any) has finished and returns its outcome.
  std::optional<Outcome> wait();

 private:
  std::optional<Outcome> outcome(bool block);
  BackgroundJob<std::shared_ptr<const BuiltSurface>> job_;
  SurfaceKey key_;
};

}  // namespace polarview
