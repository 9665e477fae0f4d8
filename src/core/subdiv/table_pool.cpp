// Table pool (see table_pool.h): one list of idle buffers per element type, under one mutex.
#include "core/subdiv/table_pool.h"

#include <mutex>

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

}  // namespace

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
    std::lock_guard<std::mutex> lock(poolMutex());
    if (poolBytes() + bytes <= kMaxPooledBytes) {
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
