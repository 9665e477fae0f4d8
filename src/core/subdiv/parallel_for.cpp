// The worker pool behind runParts (parallel_for.h).
//
// A call publishes a job (its parts, a counter of parts claimed, one of parts finished) on the
// pool's queue and claims parts itself until none is left; parked workers wake and claim the
// others. The caller then waits for the parts the workers took. Nobody waits for a worker to
// become free, so a part may call runParts again (its caller runs the inner parts nobody else
// takes), and callers on several threads at once only share the workers.
#include "core/subdiv/parallel_for.h"

#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>

namespace polarview {

namespace {

struct PartsJob {
  void (*call)(void*, unsigned);
  void* context;
  unsigned parts;
  std::atomic<unsigned> next{0};  // the next part to claim
  std::mutex mutex;               // guards finished, error
  std::condition_variable allFinished;
  unsigned finished = 0;
  std::exception_ptr error;

  // Runs part k and counts it finished; the last one wakes the caller. After the unlock the job
  // may be gone (its caller returns): nothing of it is touched then.
  void run(unsigned k) {
    std::exception_ptr failed;
    try {
      call(context, k);
    } catch (...) {
      failed = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mutex);
    if (failed && !error) error = failed;
    if (++finished == parts) allFinished.notify_all();
  }
};

class WorkerPool {
 public:
  // Never destroyed: its workers stay parked until the process ends.
  static WorkerPool& instance() {
    static WorkerPool* pool = new WorkerPool;
    return *pool;
  }

  void run(PartsJob& job) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      while (workers_.size() + 1 < job.parts && workers_.size() < kMostWorkers) workers_.emplace_back([this] { work(); });
      queue_.push_back(&job);
    }
    for (unsigned k = 1; k < job.parts; ++k) wake_.notify_one();  // a worker a part, not all of them
    for (unsigned k = job.next.fetch_add(1); k < job.parts; k = job.next.fetch_add(1)) job.run(k);
    {
      std::lock_guard<std::mutex> lock(mutex_);  // no worker claims from it after this
      for (auto it = queue_.begin(); it != queue_.end(); ++it)
        if (*it == &job) {
          queue_.erase(it);
          break;
        }
    }
    std::unique_lock<std::mutex> lock(job.mutex);
    job.allFinished.wait(lock, [&] { return job.finished == job.parts; });
    if (job.error) std::rethrow_exception(job.error);
  }

 private:
  static constexpr size_t kMostWorkers = 255;

  void work() {
    for (;;) {
      PartsJob* job = nullptr;
      unsigned k = 0;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return !queue_.empty(); });
        job = queue_.front();
        k = job->next.fetch_add(1);  // claimed under the lock: the job is still queued, so alive
        if (k >= job->parts) {
          queue_.pop_front();  // exhausted: its caller finishes it
          continue;
        }
      }
      job->run(k);
    }
  }

  std::mutex mutex_;  // guards queue_, workers_
  std::condition_variable wake_;
  std::deque<PartsJob*> queue_;
  std::vector<std::thread> workers_;
};

}  // namespace

namespace detail {

void runPartsOnPool(unsigned parts, void (*call)(void*, unsigned), void* context) {
  PartsJob job;
  job.call = call;
  job.context = context;
  job.parts = parts;
  WorkerPool::instance().run(job);
}

}  // namespace detail

}  // namespace polarview
