#pragma once
// Parallelism is injected: every encode, decode and transform that can use several threads
// takes an Executor from its caller (the model is libjxl's caller-supplied parallel runner), so
// no thread state is process-global and independent calls on different threads never interfere.
// The default is one persistent pool shared by the process (oneTBB's), limited per call to the
// thread count an option asks for. Work is always split into tasks that each write their own
// output, so results never depend on the executor or the thread count.

#include <cstddef>
#include <functional>
#include <memory>

namespace pupwave {

class Executor {
 public:
  virtual ~Executor() = default;
  // Calls task(i) exactly once for every i in [0, count), possibly concurrently, and returns
  // when all have returned. If tasks throw, the first exception is rethrown after the others
  // finished or were cancelled (some tasks may then not run).
  virtual void run(std::size_t count, const std::function<void(std::size_t)>& task) const = 0;
  // Most tasks that may run at once; callers use it only to size their work.
  virtual unsigned concurrency() const = 0;
};

// Runs the tasks on the calling thread, in index order.
const Executor& serial_executor();

// The process's shared pool on all hardware threads, created on first use.
const Executor& default_executor();

// An executor on the shared pool that runs at most `threads` tasks at once (0: all hardware
// threads, 1: serial on the calling thread).
std::unique_ptr<Executor> make_pool_executor(unsigned threads);

}  // namespace pupwave
