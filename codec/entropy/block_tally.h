#pragma once
// The bits each block-coder context codes at the start of each block, by band class: what the
// context priors (ctx_priors.h) are trained from (tools/train/train_priors.cpp). Kept only where
// a caller passes a tally to encode_block (EncodeStats::tally for whole encodes).

#include <array>
#include <cstdint>
#include <mutex>
#include <unordered_map>

#include "codec/entropy/block_contexts.h"

namespace pupwave {

// Bits kept per context and block: a prior is worth a few bits (ctx_priors.h), so after this
// many the model has all but forgotten where it started.
inline constexpr int kTallyWindow = 32;

// A context's first bits in one block as a key: length << 32 | bits (bit i = i-th coded bit).
constexpr std::uint64_t tally_key(std::uint32_t bits, unsigned length) {
  return std::uint64_t(length) << 32 | bits;
}
constexpr unsigned tally_length(std::uint64_t key) { return unsigned(key >> 32); }
constexpr std::uint32_t tally_bits(std::uint64_t key) { return std::uint32_t(key); }

// The first kTallyWindow bits each context codes in one block, gathered while it is coded.
struct BlockStarts {
  std::array<std::uint8_t, kBlockContexts> seen{};   // bits kept per context (<= kTallyWindow)
  std::array<std::uint32_t, kBlockContexts> bits{};  // and the bits themselves

  void record(int ctx, int bit) {
    const auto k = std::size_t(ctx);
    if (seen[k] >= kTallyWindow) return;
    bits[k] |= std::uint32_t(bit) << seen[k];
    ++seen[k];
  }
};

// The blocks' starts of every encode that adds to it. The code-blocks of one encode are coded
// by several tasks at once, and several encodes may share one tally: add() locks.
struct ContextTally {
  // [band class][context]: how many blocks started that context with each bit sequence
  // (tally_key; contexts a block never codes are not counted). Band class 0 is low-pass, 1
  // high-pass along one axis, 2 along both (as kContextPriors).
  std::array<std::array<std::unordered_map<std::uint64_t, std::uint64_t>, kBlockContexts>, 3> starts;
  std::uint64_t blocks = 0;

  // Counts one block of band class `band_class`; safe from any thread.
  void add(std::size_t band_class, const BlockStarts& block);

 private:
  std::mutex mutex_;
};

// Band class of a subband orientation (bit a set: high-pass along axis a).
constexpr std::size_t prior_class_of(unsigned orientation) {
  const bool high_x = orientation & 1u, high_y = orientation & 2u;
  return orientation == 0 ? 0 : (high_x && high_y ? 2 : 1);
}

}  // namespace pupwave
