#include "codec/entropy/block_tally.h"

namespace pupwave {

void ContextTally::add(std::size_t band_class, const BlockStarts& block) {
  const std::lock_guard lock(mutex_);
  for (std::size_t k = 0; k < std::size_t(kBlockContexts); ++k)
    if (block.seen[k] != 0) ++starts[band_class][k][tally_key(block.bits[k], block.seen[k])];
  ++blocks;
}

}  // namespace pupwave
