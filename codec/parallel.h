#pragma once
// A minimal fork-join loop: code-blocks are independent, so they are spread over threads.
// Each index writes only its own result slot, so output never depends on scheduling.

#include <cstddef>
#include <functional>

namespace pupwave {

// Runs fn(i) for i in [0, count) on up to `threads` threads (0 = all hardware threads).
// The first exception thrown by any fn is rethrown after all threads stop.
void parallel_for(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& fn);

}  // namespace pupwave
