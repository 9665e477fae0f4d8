// Recycles the big flat tables of refinements that are gone, so refining again (a level or scheme
// change in the viewer, the bench's repetitions) writes into memory the process already has
// instead of asking the kernel for fresh pages: on this project's machines a fresh page costs
// several times more than writing it (fault, zeroing, then std::vector's own zero fill).
// Thread-safe. The pool holds at most maxPooledBytes(); clearTablePool() frees it.
//
// Memory the pool cannot supply is fresh: prefault() maps its pages in one call, per table on the
// thread that fills it. docs/performance.md has the measurements behind these choices.
#pragma once

#include <cstddef>
#include <vector>

namespace polarview {

// The most the pool keeps: half the machine's memory, at least 1 GiB, so a whole uniform refinement
// (torus level 6, 41M faces: ~9 GB of tables, all levels) is reused by the next one instead of
// faulted in again; a process keeps what it once needed, as malloc arenas do. Only uniform
// refinements (Refinement) release to it; a long-lived caller can clearTablePool() after a big one.
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

// Maps the pages of [data, data + bytes) writable in one madvise(MADV_POPULATE_WRITE) call instead of
// one fault per page (measured here, 4 KiB pages in a Firecracker VM: 1 GiB in ~240 ms against
// ~330 ms of demand faults). Transparent huge pages are not asked for: with defrag=madvise they
// took seconds per GiB here (compaction). Best effort; a no-op where unsupported. [O(bytes)]
void prefault(void* data, size_t bytes);

// Frees every pooled buffer. [O(buffers)]
void clearTablePool();

// Bytes held by the pool now.
size_t pooledBytes();

}  // namespace polarview
