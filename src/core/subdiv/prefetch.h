// Memory hints. Software prefetch: asks for the cache line at `address`, which a later iteration
// reads at a data-dependent place (the point rules' and ring builder's gathers are latency-bound).
// Non-temporal stores: below.
#pragma once

#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace polarview {

inline void prefetch(const void* address) {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(address);
#else
  (void)address;
#endif
}

// Non-temporal stores, for tables written once and not read again soon (a finest level's faces):
// they skip the read-for-ownership of each line and leave the caches to the data still to be read.
// `to` of streamStore4 is 16-byte aligned. storeFence() orders them before the results are used
// (another thread's reads after the pool's join). Plain stores where SSE2 is missing.
inline void streamStore4(int32_t* to, int32_t a, int32_t b, int32_t c, int32_t d) {
#if defined(__SSE2__)
  _mm_stream_si128(reinterpret_cast<__m128i*>(to), _mm_setr_epi32(a, b, c, d));
#else
  to[0] = a, to[1] = b, to[2] = c, to[3] = d;
#endif
}
inline void streamStore(int32_t* to, int32_t value) {
#if defined(__SSE2__)
  _mm_stream_si32(to, value);
#else
  *to = value;
#endif
}
inline void storeFence() {
#if defined(__SSE2__)
  _mm_sfence();
#endif
}

}  // namespace polarview
