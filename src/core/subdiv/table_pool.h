// Recycles the big flat tables of refinements that are gone, so refining again (a level or scheme
// change in the viewer, the bench's repetitions) writes into memory the process already has
// instead of asking the kernel for fresh pages: on this project's machines a fresh page costs
// several times more than writing it (fault, zeroing, then std::vector's own zero fill).
// Thread-safe. The pool holds at most kMaxPooledBytes; clearTablePool() frees it.
#pragma once

#include <cstddef>
#include <vector>

namespace polarview {

constexpr size_t kMaxPooledBytes = size_t(1) << 30;  // about one refinement of 2.5M faces
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
