#include "transforms/executor.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>

namespace pupwave {
namespace {

class SerialExecutor final : public Executor {
 public:
  void run(std::size_t count, const std::function<void(std::size_t)>& task) const override {
    for (std::size_t i = 0; i < count; ++i) task(i);
  }
  unsigned concurrency() const override { return 1; }
};

// oneTBB's worker pool is created once per process and shared; an arena caps how many of its
// threads one call may use. parallel_for propagates the first exception and cancels the rest.
class PoolExecutor final : public Executor {
 public:
  explicit PoolExecutor(unsigned threads) : arena_(int(threads)), threads_(threads) {}
  void run(std::size_t count, const std::function<void(std::size_t)>& task) const override {
    if (count <= 1 || threads_ <= 1) return serial_executor().run(count, task);
    arena_.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1),
                        [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i < r.end(); ++i) task(i);
                        });
    });
  }
  unsigned concurrency() const override { return threads_; }

 private:
  mutable tbb::task_arena arena_;  // execute() is logically const: it only schedules work
  unsigned threads_;
};

unsigned hardware_threads() { return unsigned(std::max(1, tbb::this_task_arena::max_concurrency())); }

}  // namespace

const Executor& serial_executor() {
  static const SerialExecutor serial;
  return serial;
}

const Executor& default_executor() {
  static const PoolExecutor pool(hardware_threads());
  return pool;
}

std::unique_ptr<Executor> make_pool_executor(unsigned threads) {
  if (threads == 1) return std::make_unique<SerialExecutor>();
  return std::make_unique<PoolExecutor>(threads == 0 ? hardware_threads() : threads);
}

}  // namespace pupwave
