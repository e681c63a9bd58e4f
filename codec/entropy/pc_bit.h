#pragma once
// The parent-context coder's adaptive probability (entropy coder 4, docs/bitstream.md): the
// shared BitModel's count-started estimate with the final adaptation rate chosen per model.
// The coder's unary models of activity class 0 (no non-zero neighbour, parent or luma parent)
// settle at 1/32 instead of 1/64: whether a coefficient in a silent neighbourhood is zero
// changes from region to region (flat sky, texture), and the faster estimate follows it
// (-0.3% BD-rate on the test photographs, -0.2% on held-out ones).

#include <algorithm>
#include <bit>
#include <cstdint>

#include "codec/entropy/bit_model.h"

namespace pupwave {

struct PcBit {
  std::uint16_t p0 = std::uint16_t(kProbabilityOne / 2);  // probability of a 0, 15 bits
  std::uint8_t count = 0;                                 // bits seen, saturating
  std::uint8_t max_shift = BitModel::kMaxShift;           // final rate 1 / 2^max_shift

  // As BitModel::update with kMaxShift = max_shift (identical at 6): rate 1 / 2^min(bit_width(
  // count + 1), max_shift), the probability kept inside [kMinP, 2^15 - kMinP].
  void update(int bit) {
    const int ramp = int(std::bit_width(unsigned(count) + 1u));
    const std::uint32_t p = p0;
    count = std::uint8_t(count + (count < 255 ? 1 : 0));
    if (ramp >= max_shift) {
      // Settled (the common case): at the final shift (5 or 6, kMinShift) a probability inside
      // [kMinP, 2^15 - kMinP] stays inside, so no clamp is needed; the step is selected by a
      // mask, not a branch, as in BitModel::update.
      const std::uint32_t one = 0u - std::uint32_t(bit != 0);
      p0 = std::uint16_t(p +
                         ((((kProbabilityOne - p) >> max_shift) & ~one) | ((0u - (p >> max_shift)) & one)));
      return;
    }
    const std::uint32_t down = p - (p >> ramp), up = p + ((kProbabilityOne - p) >> ramp);
    p0 = std::uint16_t(
        std::clamp<std::uint32_t>(bit ? down : up, BitModel::kMinP, kProbabilityOne - BitModel::kMinP));
  }
  // The smallest final shift update() may skip the clamp at (a step of p >> 5 never crosses kMinP).
  static constexpr int kMinShift = 5;
};

}  // namespace pupwave
