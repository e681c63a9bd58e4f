#include "codec/entropy/block_tally.h"

#include <atomic>
#include <stdexcept>

namespace pupwave {
namespace {
std::atomic<ContextTally*> g_tally{nullptr};
}  // namespace

BlockTallyScope::BlockTallyScope(ContextTally& tally) {
  ContextTally* none = nullptr;
  if (!g_tally.compare_exchange_strong(none, &tally))
    throw std::logic_error("BlockTallyScope: one is already active");
}

BlockTallyScope::~BlockTallyScope() { g_tally.store(nullptr); }

ContextTally* active_block_tally() { return g_tally.load(std::memory_order_acquire); }

std::mutex& block_tally_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace pupwave
