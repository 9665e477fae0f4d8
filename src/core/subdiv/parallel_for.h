// Splits index ranges over a few threads (the refiner's passes write disjoint ranges of flat
// tables, so they need no locks). Results never depend on the thread count. The threads are a
// small pool started once (parallel_for.cpp): handing a part to a parked worker costs ~4 us here,
// starting and joining a std::thread ~50 us (docs/performance.md, Threads).
#pragma once

#include <algorithm>
#include <atomic>
#include <thread>
#include <type_traits>
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

namespace detail {
// Runs call(context, k) for k = 0..parts-1 on the pool's workers and this thread; returns when all
// have finished, rethrowing the first exception of any. [O(1) a part]
void runPartsOnPool(unsigned parts, void (*call)(void*, unsigned), void* context);
}  // namespace detail

// Calls fn(k) for k = 0..parts-1, at once on up to `parts` threads (this thread takes parts too;
// parts nobody else is free for, it runs itself, so a part may call runParts again), and waits
// for all; an exception from any part is rethrown here once all have finished.
template <class Fn>
void runParts(unsigned parts, Fn&& fn) {
  if (parts <= 1) {
    fn(0u);
    return;
  }
  using Callable = std::remove_reference_t<Fn>;
  detail::runPartsOnPool(parts, [](void* context, unsigned k) { (*static_cast<Callable*>(context))(k); },
                         const_cast<void*>(static_cast<const void*>(&fn)));
}

// Calls fn(begin, end) on `parts` contiguous pieces of [0, count), one thread each. [O(count / parts) wall time]
template <class Fn>
void parallelRanges(Index count, unsigned parts, Fn&& fn) {
  runParts(parts, [&](unsigned k) { fn(partBound(count, parts, k), partBound(count, parts, k + 1)); });
}

// Runs a() and b() at once when `parallel` (two parts of runParts), else a() then b(); an exception
// from either is rethrown here once both have finished. For two tasks that write disjoint data, so
// results never depend on `parallel`.
template <class A, class B>
void runBoth(bool parallel, A&& a, B&& b) {
  if (!parallel) {
    a();
    b();
    return;
  }
  runParts(2, [&](unsigned k) {
    if (k == 0)
      a();
    else
      b();
  });
}

}  // namespace polarview
