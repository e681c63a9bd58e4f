#pragma once
// Per-thread scratch buffers, so 1-D transforms called on many lines do not allocate per line.

#include <cstddef>
#include <span>
#include <vector>

namespace pupwave {

// Returns a span of at least n elements owned by the calling thread; valid until the next
// call with the same T and slot on that thread. slot lets one function hold two buffers.
template <class T>
std::span<T> thread_scratch(std::size_t n, unsigned slot = 0) {
  thread_local std::vector<T> buffers[2];
  auto& b = buffers[slot & 1u];
  if (b.size() < n) b.resize(n);
  return {b.data(), n};
}

}  // namespace pupwave
