#pragma once
// Internal to the volume codec: bricks as parallel tasks started in index order, shared by the
// encoder's and the decoder's brick passes.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <functional>

#include "transforms/executor.h"

namespace pupwave {

// Calls task(i) for every i in [0, count) on the executor's threads, each thread taking the next
// index when it is free, so bricks finish nearly in index order: what waits for earlier bricks
// stays small and each z-slab of the input or output is finished (and released) early, which a
// parallel_for's range splitting (one thread from the middle on) would not give. Results never
// depend on the order. After a task throws, the other threads take no more indices.
inline void run_in_index_order(const Executor& ex, std::size_t count,
                               const std::function<void(std::size_t)>& task) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  const std::size_t threads = std::clamp<std::size_t>(ex.concurrency(), 1, std::max<std::size_t>(count, 1));
  ex.run(threads, [&](std::size_t) {
    try {
      for (std::size_t i = next++; i < count && !failed.load(); i = next++) task(i);
    } catch (...) {
      failed = true;
      throw;
    }
  });
}

}  // namespace pupwave
