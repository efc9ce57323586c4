// What the heap holds for an allocation: the model behind the engine's memory
// estimates (Database::memoryBytes()), so that they can be compared with the
// process's resident set. A keyframe owns many small vectors, whose
// allocation overhead is a sizable part of its memory.
#pragma once

#include <cstddef>
#include <deque>
#include <vector>

namespace bowg {

/// Bytes glibc's malloc takes for a request of `requested` bytes (64-bit):
/// a chunk of the request plus one size word, rounded up to 16 bytes, at
/// least 32; requests of 128 KiB and more are mapped in whole 4 KiB pages.
/// 0 for 0 (an empty vector allocates nothing).
std::size_t heapBlockBytes(std::size_t requested);

/// The heap block of a vector's storage (its capacity, not its size).
template <typename T>
std::size_t vectorHeapBytes(const std::vector<T>& v) {
  return heapBlockBytes(v.capacity() * sizeof(T));
}

/// The heap blocks of a deque grown by push_back (libstdc++'s layout):
/// nodes of 512 bytes' worth of elements (one element where it is larger),
/// size / per_node + 1 of them, and the map of node pointers, counted at its
/// least, max(8, nodes + 2) pointers (it may hold up to about twice that:
/// under 8 bytes per node).
template <typename T>
std::size_t dequeHeapBytes(const std::deque<T>& d) {
  const std::size_t per_node = sizeof(T) < 512 ? 512 / sizeof(T) : 1;
  const std::size_t nodes = d.size() / per_node + 1;
  const std::size_t map = nodes + 2 > 8 ? nodes + 2 : 8;
  return nodes * heapBlockBytes(per_node * sizeof(T)) + heapBlockBytes(map * sizeof(T*));
}

}  // namespace bowg
