#pragma once
// Adaptive probability of one binary context, shared by the range encoder and decoder.

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>

namespace pupwave {

// Probabilities are 15-bit fixed point (32768 = certainty).
inline constexpr int kProbabilityBits = 15;
inline constexpr std::uint32_t kProbabilityOne = 1u << kProbabilityBits;

// Probability that the next bit is 0, adapted after every coded bit. The adaptation rate
// starts fast (about 1/(n+1), like a count-based estimate) and settles at 1/2^kMaxShift, so
// a context learns quickly in a small code-block yet stays stable in a large one.
struct BitModel {
  std::uint16_t p0 = std::uint16_t(kProbabilityOne / 2);
  std::uint16_t count = 0;  // not a char type: its stores would alias every other value

  static constexpr int kMaxShift = 6;
  static constexpr std::uint32_t kMinP = 31;  // keeps both sub-ranges non-empty

  constexpr BitModel() = default;
  constexpr explicit BitModel(std::uint16_t initial_p0) : p0(initial_p0) {}

  void update(int bit) {
    const std::uint32_t p = p0;
    if (count >= kSettled) {
      // Settled (the common case): at the capped shift a probability inside [kMinP,
      // kProbabilityOne - kMinP] stays inside, so no clamp is needed. The step is selected
      // by a mask, not a branch: GCC otherwise splits the coder's paths on the bit, a
      // mispredicted jump for every unpredictable bit.
      const std::uint32_t one = 0u - std::uint32_t(bit != 0);
      p0 = std::uint16_t(p +
                         ((((kProbabilityOne - p) >> kMaxShift) & ~one) | ((0u - (p >> kMaxShift)) & one)));
      return;
    }
    // shift = 1 + floor(log2(count + 1)): 1, 2, 2, 3, 3, 3, 3, 4, ... up to kMaxShift at
    // count kSettled, where the count stops.
    const int shift = kShift[count];
    const std::uint32_t down = p - (p >> shift);
    const std::uint32_t up = p + ((kProbabilityOne - p) >> shift);
    p0 = std::uint16_t(std::clamp<std::uint32_t>(bit ? down : up, kMinP, kProbabilityOne - kMinP));
    ++count;
  }

 private:
  static constexpr int kSettled = (1 << (kMaxShift - 1)) - 1;  // first count with the capped shift
  static constexpr std::array<std::uint8_t, kSettled + 1> kShift = [] {
    std::array<std::uint8_t, kSettled + 1> t{};
    for (int c = 0; c <= kSettled; ++c)
      t[std::size_t(c)] = std::uint8_t(std::min(int(std::bit_width(unsigned(c) + 1u)), kMaxShift));
    return t;
  }();
};

}  // namespace pupwave
