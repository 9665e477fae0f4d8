// Table pool (see table_pool.h): one list of idle buffers per element type, under one mutex.
#include "core/subdiv/table_pool.h"

#include <algorithm>
#include <mutex>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

#include "core/mesh/poly_mesh.h"

namespace polarview {

namespace {

std::mutex& poolMutex() {
  static std::mutex mutex;
  return mutex;
}
size_t& poolBytes() {
  static size_t bytes = 0;
  return bytes;
}
template <class T>
std::vector<std::vector<T>>& idleBuffers() {
  static std::vector<std::vector<T>> buffers;
  return buffers;
}
template <class T>
size_t bytesOf(const std::vector<T>& buffer) {
  return buffer.capacity() * sizeof(T);
}
size_t& poolLimit() {
  static size_t limit = 0;  // 0: the default
  return limit;
}

}  // namespace

void prefault(void* data, size_t bytes) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  const uintptr_t page = uintptr_t(sysconf(_SC_PAGESIZE));
  const uintptr_t begin = (uintptr_t(data) + page - 1) & ~(page - 1), end = (uintptr_t(data) + bytes) & ~(page - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);  // best effort
#else
  (void)data;
  (void)bytes;
#endif
}

size_t maxPooledBytes() {
  std::lock_guard<std::mutex> lock(poolMutex());
  if (poolLimit()) return poolLimit();
  size_t physical = 0;
#if defined(__linux__)
  physical = size_t(sysconf(_SC_PHYS_PAGES)) * size_t(sysconf(_SC_PAGESIZE));
#endif
  return std::max(size_t(1) << 30, physical / 2);
}

void setMaxPooledBytes(size_t bytes) {
  std::lock_guard<std::mutex> lock(poolMutex());
  poolLimit() = bytes;
}

template <class T>
void reserveFromPool(std::vector<T>& table, size_t size) {
  if (table.capacity() >= size) return;
  if (size * sizeof(T) >= kMinPooledBytes) {
    std::lock_guard<std::mutex> lock(poolMutex());
    std::vector<std::vector<T>>& idle = idleBuffers<T>();
    size_t best = idle.size();
    for (size_t i = 0; i < idle.size(); ++i)
      if (idle[i].capacity() >= size && (best == idle.size() || idle[i].capacity() < idle[best].capacity())) best = i;
    if (best < idle.size()) {
      poolBytes() -= bytesOf(idle[best]);
      table.swap(idle[best]);
      idle[best].swap(idle.back());
      idle.pop_back();  // the table's old (smaller) buffer goes with it
      return;
    }
  }
  std::vector<T>().swap(table);  // drop the old contents rather than copy them
  table.reserve(size);
}

template <class T>
void releaseToPool(std::vector<T>& table) {
  const size_t bytes = bytesOf(table);
  if (bytes >= kMinPooledBytes) {
    const size_t limit = maxPooledBytes();
    std::lock_guard<std::mutex> lock(poolMutex());
    if (poolBytes() + bytes <= limit) {
      poolBytes() += bytes;
      idleBuffers<T>().emplace_back().swap(table);
      return;
    }
  }
  std::vector<T>().swap(table);
}

void clearTablePool() {
  std::lock_guard<std::mutex> lock(poolMutex());
  idleBuffers<Index>().clear();
  idleBuffers<uint8_t>().clear();
  idleBuffers<Point>().clear();
  poolBytes() = 0;
}

size_t pooledBytes() {
  std::lock_guard<std::mutex> lock(poolMutex());
  return poolBytes();
}

template void reserveFromPool<Index>(std::vector<Index>&, size_t);
template void reserveFromPool<uint8_t>(std::vector<uint8_t>&, size_t);
template void reserveFromPool<Point>(std::vector<Point>&, size_t);
template void releaseToPool<Index>(std::vector<Index>&);
template void releaseToPool<uint8_t>(std::vector<uint8_t>&);
template void releaseToPool<Point>(std::vector<Point>&);

}  // namespace polarview
