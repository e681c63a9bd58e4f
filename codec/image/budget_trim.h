#pragma once
// Internal to the image encoder (image_encoder.cpp): holds the coded blocks of a byte-budget
// encode with only the passes rate control can still choose (the blocks are coded
// finer than the budget keeps, and holding every pass of a gigapixel image would take 0.4 GB).

#include <cstddef>
#include <mutex>
#include <vector>

#include "codec/entropy/block_encoder.h"
#include "codec/image/kept_block.h"
#include "codec/rate/pcrd.h"

namespace pupwave {

// Takes each block as it is coded and keeps its passes up to pcrd.h's points_to_keep for a
// slope bound that rises as blocks arrive: passes past a block's last hull point are never
// chosen, and once the blocks so far hold more than the budget at some threshold
// (overflow_slope), PCRD's threshold for the whole image lies above it. The cut changes no
// truncation that fits the budget, so the stream is byte for byte the one from every pass,
// whatever order the blocks arrive in (threads). Only for a single base-step family cut by
// one slope threshold (encode_for_size at effort 1, or where the families do not fit).
class BudgetTrim {
 public:
  BudgetTrim(std::vector<KeptBlock>& blocks, std::vector<std::vector<HullPoint>>& hulls, double budget);

  // Installs block i (from any thread) with its hull, cut to the current bound.
  void add(std::size_t i, EncodedBlock&& coded, std::vector<HullPoint>&& hull);

 private:
  // Raises the bound from the blocks held and cuts them all to it; under lock_.
  void tighten();
  // Cuts block i's hull and passes to the bound; returns the bytes it still holds.
  std::size_t cut(std::size_t i);

  std::vector<KeptBlock>& blocks_;
  std::vector<std::vector<HullPoint>>& hulls_;
  const double budget_;
  std::mutex lock_;
  double bound_ = 0.0;      // PCRD's threshold is known to be above this
  std::size_t held_ = 0;    // codeword bytes of the blocks held
  std::size_t next_check_;  // held_ at which the bound is raised next
};

}  // namespace pupwave
