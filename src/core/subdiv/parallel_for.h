// Splits index ranges over a few std::threads (the refiner's passes write disjoint ranges of flat
// tables, so they need no locks). Results never depend on the thread count.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

#include "core/mesh/poly_mesh.h"

namespace polarview {

// The most threads a pass starts: setThreadLimit's number (the CLI's --threads, POLARVIEW_THREADS),
// else the hardware's concurrency up to 8 (measured to pay; more only when asked). Results never
// depend on it.
inline std::atomic<unsigned>& threadLimitSetting() {
  static std::atomic<unsigned> limit{0};
  return limit;
}
inline void setThreadLimit(unsigned threads) { threadLimitSetting() = threads; }
inline unsigned threadLimit() {
  const unsigned set = threadLimitSetting();
  return set ? set : std::max(1u, std::min(8u, std::thread::hardware_concurrency()));
}

// Threads worth using for `work` elements: 1 below a size where starting threads costs more than it
// saves, else up to threadLimit(). [O(1)]
inline unsigned threadsFor(size_t work) {
  constexpr size_t kMinWorkPerThread = size_t(1) << 15;
  return unsigned(std::min<size_t>(threadLimit(), std::max<size_t>(1, work / kMinWorkPerThread)));
}

// The start of piece k of [0, count) cut into `parts` contiguous pieces (k = parts gives count). [O(1)]
inline Index partBound(Index count, unsigned parts, unsigned k) { return Index(int64_t(count) * k / parts); }

// Calls fn(k) for k = 0..parts-1, each on its own thread (the caller's thread takes k = 0), and
// waits for all. [O(1) threads started per part]
template <class Fn>
void runParts(unsigned parts, Fn&& fn) {
  if (parts <= 1) {
    fn(0u);
    return;
  }
  std::vector<std::thread> workers;
  workers.reserve(parts - 1);
  for (unsigned k = 1; k < parts; ++k) workers.emplace_back([&fn, k] { fn(k); });
  fn(0u);
  for (std::thread& worker : workers) worker.join();
}

// Calls fn(begin, end) on `parts` contiguous pieces of [0, count), one thread each. [O(count / parts) wall time]
template <class Fn>
void parallelRanges(Index count, unsigned parts, Fn&& fn) {
  runParts(parts, [&](unsigned k) { fn(partBound(count, parts, k), partBound(count, parts, k + 1)); });
}

// Runs a() on this thread and b() on a second one at once when `parallel`, else a() then b(); an
// exception from either is rethrown here once both have finished. For two tasks that write
// disjoint data, so results never depend on `parallel`. [one thread started]
template <class A, class B>
void runBoth(bool parallel, A&& a, B&& b) {
  if (!parallel) {
    a();
    b();
    return;
  }
  std::exception_ptr failed;
  std::thread worker([&] {
    try {
      b();
    } catch (...) {
      failed = std::current_exception();
    }
  });
  try {
    a();
  } catch (...) {
    worker.join();
    throw;
  }
  worker.join();
  if (failed) std::rethrow_exception(failed);
}

}  // namespace polarview
