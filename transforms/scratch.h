#pragma once
// Per-thread scratch buffers, so 1-D transforms called on many lines do not allocate per line,
// and row buffers that are not zeroed when they grow.

#include <cstddef>
#include <memory>
#include <span>
#include <utility>
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

// An allocator that leaves the elements std::vector::resize adds uninitialised (for arithmetic
// T), for buffers whose every element is written before it is read: zeroing them first would be
// a whole extra pass over the strip coders' row buffers.
template <class T>
struct UninitializedAllocator : std::allocator<T> {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <class U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;  // default-initialisation: no value for arithmetic types
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// A vector of samples whose growth does not zero them (UninitializedAllocator).
template <class T>
using RowBuffer = std::vector<T, UninitializedAllocator<T>>;

// A buffer of at least n elements owned by the calling thread, not zeroed, for a task's
// working copy of a block of rows (the strip coders' column windows): it is allocated once per
// thread instead of once per task. Valid until the next call with the same T on that thread.
template <class T>
T* thread_rows(std::size_t n) {
  thread_local RowBuffer<T> buffer;
  if (buffer.size() < n) buffer.resize(n);
  return buffer.data();
}

}  // namespace pupwave
