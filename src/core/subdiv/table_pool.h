// Recycles the big flat tables of refinements that are gone, so refining again (a level or scheme
// change in the viewer, the bench's repetitions) writes into memory the process already has
// instead of asking the kernel for fresh pages: on this project's machines a fresh page costs
// several times more than writing it (fault, zeroing, then std::vector's own zero fill).
// Thread-safe. The pool holds at most maxPooledBytes(); clearTablePool() frees it.
//
// Fresh buffers (nothing pooled fits) are pre-faulted in one madvise(MADV_POPULATE_WRITE) call:
// measured here (Firecracker VM, 4 KiB pages) it maps 1 GiB in ~240 ms against ~330 ms of
// one-by-one faults. Transparent huge pages were measured slower (seconds per GiB with
// defrag=madvise: compaction), so they are not asked for. docs/performance.md has the numbers.
#pragma once

#include <cstddef>
#include <vector>

namespace polarview {

// The most the pool keeps: a quarter of the machine's memory, at least 1 GiB, so a whole uniform
// refinement (10M faces: ~3 GB) is reused by the next one instead of faulted in again.
size_t maxPooledBytes();
// Sets maxPooledBytes() (0: back to the default); for tests and memory-tight callers.
void setMaxPooledBytes(size_t bytes);
constexpr size_t kMinPooledBytes = size_t(1) << 20;  // smaller tables: malloc recycles them well

// Makes table.capacity() >= size, taking the best-fitting pooled buffer when `table` is smaller.
// The size is unchanged unless a pooled buffer was taken: then it is that buffer's old size, with
// its old contents, so a later resize(size) writes nothing that the caller will overwrite anyway.
template <class T>
void reserveFromPool(std::vector<T>& table, size_t size);

// Hands the table's buffer to the pool (or frees it when small or the pool is full); leaves it empty.
template <class T>
void releaseToPool(std::vector<T>& table);

// Frees every pooled buffer. [O(buffers)]
void clearTablePool();

// Bytes held by the pool now.
size_t pooledBytes();

}  // namespace polarview
