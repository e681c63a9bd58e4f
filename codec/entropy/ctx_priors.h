#pragma once
// Initial probabilities of the bit-plane block coder's contexts (trained priors instead of 1/2):
// a 64x64 block codes only a few bits in many of its contexts, and one that starts near its
// typical probability wastes fewer bits learning it (about -1.5% BD-rate against
// OpenJPEG on the four scored photographs, -1.3% on ten held-out ones).
//
// Trained by tools/train/train_priors.cpp (rerun it after any change to the contexts or the
// adaptation) on photographs that are NOT the scored ones (testimages/): the 12 photographs
// of Debian's mate-backgrounds 1.26 (usr/share/backgrounds/mate/nature/*.jpg, box-reduced to
// at most 1024 pixels on the long side), each coded at 0.125, 0.25, 0.5, 1 and 2 bpp (cdf97, effort 1).
// Checked on ten others never trained on: scikit-image 0.19's motorcycle_left, rocket,
// retina, hubble_deep_field, coins, moon, brick, grass, gravel (Debian python3-skimage) and
// f3.jpg of the Rust embedded book (tools/train/prior_training_sets.sh builds both sets).

#include <array>
#include <cstdint>

#include "codec/entropy/bit_model.h"

namespace pupwave {

// Probability of a 1, in 1/256, of each context (numbered as in block_contexts.h) by band
// class: 0 low-pass, 1 high-pass along one axis, 2 high-pass along x and y. Together with its
// weight below, the prior that codes the first 32 bits each context codes in a block (over all
// blocks of the training set) in the fewest bits under BitModel's adaptation.
inline constexpr std::array<std::array<std::uint8_t, 20>, 3> kContextPriors{{
    {9, 51, 91, 120, 110, 121, 164, 224, 184, 157, 19, 127, 12, 2, 1, 64, 88, 46, 26, 59},
    {6, 18, 47, 35, 100, 54, 69, 101, 124, 115, 130, 122, 124, 134, 20, 43, 82, 7, 10, 31},
    {6, 29, 76, 21, 49, 91, 52, 86, 107, 120, 146, 135, 159, 160, 20, 47, 85, 6, 10, 28},
}};

// How many bits each prior is worth: BitModel's adaptation starts at this count (0: the first
// coded bit moves the probability half way; 7: by 1/16; 31: by 1/64, the settled rate). Fitted
// with the prior among 0, 1, 2, 3, 5, 7, 11, 15, 23, 31; a uniform 7 with the plain mean of
// the first 16 bits as prior loses 0.3% BD-rate on the scored and 0.5% on the held-out set.
inline constexpr std::array<std::array<std::uint8_t, 20>, 3> kContextPriorCounts{{
    {31, 15, 31, 7, 11, 3, 5, 3, 5, 0, 31, 31, 7, 7, 0, 1, 7, 23, 11, 31},
    {31, 15, 15, 11, 15, 5, 7, 7, 11, 7, 0, 0, 0, 1, 31, 7, 23, 3, 31, 7},
    {31, 15, 15, 15, 15, 31, 15, 15, 31, 23, 2, 5, 2, 1, 31, 7, 31, 5, 31, 15},
}};

// Every prior must be a probability strictly inside (0, 1).
constexpr bool priors_are_probabilities() {
  for (const auto& row : kContextPriors)
    for (const auto one256 : row)
      if (one256 == 0) return false;
  for (const auto& row : kContextPriorCounts)
    for (const auto count : row)
      if (count > 31) return false;  // BitModel's count stops at its settled count
  return true;
}
static_assert(priors_are_probabilities());

// A model starting at probability `one256` / 256 of a 1, worth `count` bits.
constexpr BitModel prior_model(std::uint8_t one256, std::uint8_t count) {
  BitModel m(std::uint16_t(kProbabilityOne - (std::uint32_t(one256) << (kProbabilityBits - 8))));
  m.count = count;
  return m;
}

}  // namespace pupwave
