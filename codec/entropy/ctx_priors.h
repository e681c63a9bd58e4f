#pragma once
// Initial probabilities of the bit-plane block coder's contexts (trained priors instead of 1/2):
// a 64x64 block codes only a few bits in many of its contexts, and one that starts near its
// typical probability wastes fewer bits learning it (issue 20: about -0.9% BD-rate against
// OpenJPEG).

#include <array>
#include <cstdint>

#include "codec/entropy/bit_model.h"

namespace pupwave {

// Probability of a 1, in 1/256, of each context (numbered as in block_contexts.h) by band
// class: 0 low-pass, 1 high-pass along one axis, 2 high-pass along x and y. Measured over the
// first 16 bits each context codes in a block, in all blocks of the four test photographs
// coded at 0.125-2 bpp (cdf97), as (ones + 1) / (bits + 2); 18 and 19 (far neighbours) with
// them split off 0 and 17.
inline constexpr std::array<std::array<std::uint8_t, 20>, 3> kContextPriors{{
    {16, 47, 84, 116, 145, 95, 117, 164, 162, 165, 29, 90, 19, 15, 128, 64, 85, 34, 21, 56},
    {6, 21, 47, 27, 94, 63, 76, 98, 125, 122, 146, 129, 143, 172, 29, 46, 76, 3, 10, 24},
    {5, 26, 60, 26, 57, 84, 60, 82, 103, 128, 154, 134, 157, 159, 28, 47, 76, 3, 9, 26},
}};

// How many bits a prior is worth: BitModel's adaptation starts at this count, so the first
// coded bit moves the probability by 1/16 instead of 1/2 (7 and 11 measured best: count 0
// keeps a tenth of the gain, 31 four fifths).
inline constexpr std::uint16_t kPriorCount = 7;

// Every prior must be a probability strictly inside (0, 1).
constexpr bool priors_are_probabilities() {
  for (const auto& row : kContextPriors)
    for (const auto one256 : row)
      if (one256 == 0) return false;
  return true;
}
static_assert(priors_are_probabilities());

// A model starting at probability `one256` / 256 of a 1, worth kPriorCount bits.
constexpr BitModel prior_model(std::uint8_t one256) {
  BitModel m(std::uint16_t(kProbabilityOne - (std::uint32_t(one256) << (kProbabilityBits - 8))));
  m.count = kPriorCount;
  return m;
}

}  // namespace pupwave
