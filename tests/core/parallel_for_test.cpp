// The worker pool behind runParts (parallel_for.h): every part runs exactly once, on several
// threads at once, nested calls and callers on many threads at once finish, and a part's
// exception reaches the caller after every part has finished.
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/subdiv/parallel_for.h"

using namespace polarview;

namespace {

// Restores the thread limit a test changes.
struct ThreadLimit {
  explicit ThreadLimit(unsigned threads) : before(threadLimitSetting()) { setThreadLimit(threads); }
  ~ThreadLimit() { setThreadLimit(before); }
  unsigned before;
};

}  // namespace

TEST_CASE("runParts: each part once; parts run at once on the pool's threads") {
  ThreadLimit limit(4);
  for (unsigned parts : {1u, 2u, 3u, 7u, 64u}) {
    CAPTURE(parts);
    std::vector<std::atomic<int>> runs(parts);
    runParts(parts, [&](unsigned k) { ++runs[k]; });
    for (unsigned k = 0; k < parts; ++k) CHECK(runs[k] == 1);
  }
  // Four parts that each wait for all four to have started: only possible on four threads at once.
  std::atomic<int> started{0};
  std::mutex mutex;
  std::set<std::thread::id> threads;
  runParts(4, [&](unsigned) {
    ++started;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);  // fails, never hangs
    while (started < 4 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
    std::lock_guard<std::mutex> lock(mutex);
    threads.insert(std::this_thread::get_id());
  });
  CHECK(threads.size() == 4);
}

TEST_CASE("runParts: nested calls and many callers at once finish with every part run") {
  ThreadLimit limit(3);
  std::atomic<long> sum{0};
  auto nested = [&] {
    runParts(3, [&](unsigned i) {
      runParts(3, [&](unsigned j) {
        runBoth(true, [&] { sum += long(9 * i + 3 * j); }, [&] { sum += long(9 * i + 3 * j + 1); });
      });
    });
  };
  std::vector<std::thread> callers;
  for (int c = 0; c < 6; ++c) callers.emplace_back(nested);
  nested();
  for (std::thread& caller : callers) caller.join();
  long once = 0;
  for (long i = 0; i < 3; ++i)
    for (long j = 0; j < 3; ++j) once += 2 * (9 * i + 3 * j) + 1;
  CHECK(sum == 7 * once);
}

TEST_CASE("runParts: a part's exception reaches the caller once every part has finished") {
  ThreadLimit limit(4);
  std::atomic<int> finished{0};
  CHECK_THROWS_AS(runParts(4,
                           [&](unsigned k) {
                             if (k == 1) throw std::runtime_error("part 1");
                             std::this_thread::sleep_for(std::chrono::milliseconds(20));
                             ++finished;
                           }),
                  std::runtime_error);
  CHECK(finished == 3);
  CHECK_THROWS_AS(runBoth(true, [] {}, [] { throw std::logic_error("b"); }), std::logic_error);
  // The pool still works afterwards.
  std::atomic<int> runs{0};
  runParts(4, [&](unsigned) { ++runs; });
  CHECK(runs == 4);
}
