#include "pipeline/surface_job.h"

namespace polarview {

void SurfaceJob::start(const Model& model, const SurfaceKey& key, size_t faceBudget, std::shared_ptr<SurfaceHierarchy> reuse) {
  if (job_.start([model, key, faceBudget, reuse] { return buildSurface(model, key, faceBudget, reuse); })) key_ = key;
}

std::optional<SurfaceJob::Outcome> SurfaceJob::poll() { return outcome(false); }
std::optional<SurfaceJob::Outcome> SurfaceJob::wait() { return outcome(true); }

std::optional<SurfaceJob::Outcome> SurfaceJob::outcome(bool block) {
  if (!(block ? job_.running() : job_.finished())) return std::nullopt;
  Outcome outcome;
  outcome.key = key_;
  try {
    outcome.surface = *job_.wait();
  } catch (const std::exception& e) {
    // InputError (budget, unsupported mesh) and bad_alloc alike: the view keeps what it shows.
    outcome.error = e.what();
  }
  return outcome;
}

}  // namespace polarview
