#pragma once
// Adaptive binary range encoder (carry-propagating, byte-oriented, 32-bit range) with exact
// truncation points: after any bit the encoder can say which bytes form a complete codeword
// for everything coded so far. Those codewords are prefixes of the final stream plus a few
// tail bytes, so rate allocation can cut a code-block after any coding pass without
// re-encoding. The decoder (range_decoder.h) pads a codeword with zero bytes.

#include <cstdint>
#include <span>
#include <vector>

#include "codec/entropy/bit_model.h"

namespace pupwave {

// A complete codeword for the bits coded up to some moment: the first `prefix` bytes of the
// encoder's final stream followed by `tail`. Trailing zero bytes are dropped.
struct TruncationPoint {
  std::size_t prefix = 0;
  std::vector<std::uint8_t> tail;
  std::size_t size() const { return prefix + tail.size(); }
};

class RangeEncoder {
 public:
  // Codes `bit` (0 or 1) with the adaptive probability `model`, then adapts it.
  void encode(int bit, BitModel& model) {
    encode_with(bit, model.p0);
    model.update(bit);
  }
  // Codes `bit` with probability p0 / 2^15 of a 0 (p0 in 1 .. 2^15 - 1), for models that
  // keep their own probability (the lossless coder's two-rate models).
  void encode_probability(int bit, std::uint32_t p0) { encode_with(bit, p0); }
  // Codes a bit with probability one half (no adaptation).
  void encode_equiprobable(int bit) { encode_with(bit, std::uint16_t(kProbabilityOne / 2)); }
  // Codes the low `n` (1..16) bits of `value` raw, all at once (the coefficient coder's
  // bypass bits): the range is split into 2^n equal parts, no model, one renormalisation.
  void encode_raw(std::uint32_t value, int n) {
    const std::uint32_t part = range_ >> n;
    low_ += std::uint64_t(value & ((1u << n) - 1u)) * part;
    range_ = part;
    while (range_ < (1u << 24)) {
      range_ <<= 8;
      shift_low();
    }
  }

  // The codeword that decodes every bit coded so far.
  TruncationPoint truncation_point() const;

  // Bytes emitted so far that can no longer change (the prefix truncation points refer to).
  std::span<const std::uint8_t> committed() const;

  // Complete codeword of everything coded: the final stream.
  std::vector<std::uint8_t> finish() const;

  // Bytes of `point`'s codeword, given the final stream `stream` (from finish()) or any
  // stream that shares the committed prefix.
  static std::vector<std::uint8_t> codeword(std::span<const std::uint8_t> stream,
                                            const TruncationPoint& point);

 private:
  // Without a branch on the bit: refinement bits are coin tosses to a branch predictor.
  void encode_with(int bit, std::uint32_t p0) {
    const std::uint32_t bound = (range_ >> kProbabilityBits) * p0;
    low_ += bound & (0u - std::uint32_t(bit != 0));
    range_ = bit ? range_ - bound : bound;
    while (range_ < (1u << 24)) {
      range_ <<= 8;
      shift_low();
    }
  }
  void shift_low();

  std::uint64_t low_ = 0;  // 32-bit window plus a carry bit
  std::uint32_t range_ = 0xFFFFFFFFu;
  std::uint8_t cache_ = 0;         // last byte not yet final (a carry may still reach it)
  std::uint64_t pending_ = 1;      // cache byte plus following 0xFF bytes awaiting a carry
  std::vector<std::uint8_t> out_;  // out_[0] is always 0 and is not part of the stream
};

}  // namespace pupwave
