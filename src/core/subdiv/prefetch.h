// Software prefetch: asks for the cache line at `address`, which a later iteration reads at a
// data-dependent place (the point rules' and ring builder's gathers are latency-bound).
#pragma once

namespace polarview {

inline void prefetch(const void* address) {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(address);
#else
  (void)address;
#endif
}

}  // namespace polarview
