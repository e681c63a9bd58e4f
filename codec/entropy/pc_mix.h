#pragma once
// The parent-context coder's adaptive probability (entropy coder 4, docs/bitstream.md): a fast
// and a slow estimate of the probability of a 0 mixed in the logistic (stretch) domain with
// weights that adapt per model (one-layer logistic mixing). The mix learns per context how much
// to trust each rate and sharpens estimates that are right more often than they say: with
// RDOQ against the models' costs it measured -0.9% BD-rate on the test photographs against
// one fixed-rate model (bench/results/rd_issue20.md). Integer throughout, so every platform
// decodes the same bits.

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>

#include "codec/entropy/bit_model.h"

namespace pupwave {

// Stretch domain: ln(p / (1 - p)) in units of 1/256, clamped to +-kPcStretchMax.
inline constexpr int kPcStretchMax = 2047;

// squash(d) = 2^15 / (1 + e^(-d / 256)), piecewise linear between its values at every half unit
// of d (kPcSquashKnots[i] = round(2^15 / (1 + e^(-(i - 16) / 2)))), clamped to the range coder's
// [kMinP, 2^15 - kMinP].
inline constexpr std::array<std::int32_t, 33> kPcSquashKnots = {
    11,    18,    30,    49,    81,    133,   219,   360,   589,   961,   1554,  2486,  3906,  5978,  8813,  12371, 16384,
    20397, 23955, 26790, 28862, 30282, 31214, 31807, 32179, 32408, 32549, 32635, 32687, 32719, 32738, 32750, 32757};

constexpr std::uint32_t pc_squash(std::int32_t d) {
  d = std::clamp(d, -kPcStretchMax, kPcStretchMax) + 2048;  // 1 .. 4095
  const std::int32_t i = d >> 7, f = d & 127;
  const std::int32_t p = (kPcSquashKnots[std::size_t(i)] * (128 - f) + kPcSquashKnots[std::size_t(i) + 1] * f + 64) >> 7;
  return std::uint32_t(std::clamp<std::int32_t>(p, BitModel::kMinP, kProbabilityOne - BitModel::kMinP));
}

// stretch(p) for p = p0 >> 3 (12 bits): the least d whose squash reaches p (squash's inverse).
inline constexpr std::array<std::int16_t, 4096> kPcStretch = [] {
  std::array<std::int16_t, 4096> t{};
  std::int32_t d = -kPcStretchMax;
  for (std::uint32_t p = 0; p < 4096; ++p) {
    while (d < kPcStretchMax && (pc_squash(d) >> 3) < p) ++d;
    t[p] = std::int16_t(d);
  }
  return t;
}();

// pc_squash over its whole domain (-kPcStretchMax .. kPcStretchMax): one load a prediction.
inline constexpr std::array<std::uint16_t, 2 * kPcStretchMax + 1> kPcSquash = [] {
  std::array<std::uint16_t, 2 * kPcStretchMax + 1> t{};
  for (std::int32_t d = -kPcStretchMax; d <= kPcStretchMax; ++d) t[std::size_t(d + kPcStretchMax)] = std::uint16_t(pc_squash(d));
  return t;
}();

// A fast (settling at 1/32) and a slow (1/512) count-started estimate of the probability of a
// 0, mixed with two adaptive weights (16.16 fixed point, starting at 1/2 each: the mean in the
// stretch domain). The mixed probability and its inputs are computed at each update and kept,
// so a coded bit waits for one load, as with BitModel, not for the mix.
struct PcBit {
  static constexpr int kFastShift = 5, kSlowShift = 9;
  // Weight step: (error x input) >> kRateShift, a learning rate of about 0.004.
  static constexpr int kRateShift = 15;
  // Weights stay within +-64 (no overflow on any input; measured weights stay below 4).
  static constexpr std::int32_t kMaxWeight = 1 << 22;

  std::uint16_t fast = 16384, slow = 16384;
  std::uint16_t count = 0;
  std::uint16_t p0 = 16384;      // squash(w0 s0 + w1 s1): the probability the coder uses
  std::int16_t s0 = 0, s1 = 0;  // stretch(fast), stretch(slow)
  std::int32_t w0 = 1 << 15, w1 = 1 << 15;

  void update(int bit) {
    const std::int32_t err = (bit ? 0 : std::int32_t(kProbabilityOne)) - std::int32_t(p0);
    w0 = std::clamp(w0 + ((err * s0) >> kRateShift), -kMaxWeight, kMaxWeight);
    w1 = std::clamp(w1 + ((err * s1) >> kRateShift), -kMaxWeight, kMaxWeight);
    const int warm = int(std::bit_width(unsigned(count) + 1u));
    step(fast, std::min(warm, kFastShift), bit);
    step(slow, std::min(warm, kSlowShift), bit);
    if (count < (1 << kSlowShift)) ++count;
    s0 = kPcStretch[fast >> 3];
    s1 = kPcStretch[slow >> 3];
    const std::int64_t dot = (std::int64_t(w0) * s0 + std::int64_t(w1) * s1) >> 16;
    p0 = kPcSquash[std::size_t(std::clamp<std::int64_t>(dot, -kPcStretchMax, kPcStretchMax) + kPcStretchMax)];
  }
  // p stays inside [1, 32767]: p >> s is 0 at p = 1 and (32768 - p) >> s is 0 at 32767.
  static void step(std::uint16_t& p, int shift, int bit) {
    p = std::uint16_t(bit ? p - (p >> shift) : p + ((kProbabilityOne - p) >> shift));
  }
};

}  // namespace pupwave
