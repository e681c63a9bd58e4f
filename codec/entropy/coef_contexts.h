#pragma once
// Contexts of the non-embedded coefficient coder (coef_encoder.h / coef_decoder.h), shared by
// both sides so that they cannot drift apart. A block's quantization indices are coded in block
// order (x fastest), each from the magnitudes of its already-coded neighbours: the neighbourhood
// sum picks a context class (about log2 of the local magnitude) and from it a Golomb-Rice
// parameter k (LOCO-I style); the index's high part q >> k is coded in unary with adaptive
// binary models of that class, the top low bit with a model, the other low bits and the sign
// raw (equiprobable, several at once).

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "codec/entropy/bit_model.h"
#include "transforms/subband.h"

namespace pupwave {

// Indices below 2^kCoefMaxBits (the bit-plane coder's limit: a stream can switch coders freely).
inline constexpr int kCoefMaxBits = 30;
// Context classes: bit width of the weighted neighbour sum, capped.
inline constexpr int kCoefClasses = 48;
// The weighted sum counts 12 times the mean neighbour magnitude mu, and k = class / 2 - this
// (class / 2 ~ log2 of the sum) makes q >> k about 1..2 on average (measured: offsets 1 and 3
// cost 0.1-0.4% more bits on wmag91 and turbulence).
inline constexpr int kCoefKOffset = 2;
// Unary bins with their own model (later bins share the last), and the unary length after
// which the rest of the high part is sent raw (Elias-gamma style).
inline constexpr int kCoefUnaryModels = 4;
inline constexpr int kCoefEscape = 12;
// Raw bits the range coder takes at once (range >= 2^24 before, >= 2^8 after); longer runs (at
// most 31 bits: escapes, Rice parameters up to 21) go in two pieces.
inline constexpr int kCoefRawChunk = 16;
// Low bits (below the high part) coded with models, the rest raw: 0 costs 1-2.8% more bits, 1
// 0.3% more on turbulence at 1e-3 / 1e-4.
inline constexpr int kCoefModelledLow = 2;
// Sign contexts: each of 3 neighbours negative, zero or positive.
inline constexpr int kCoefSignContexts = 27;

// Adaptive models of one block (fresh per block: each block's codeword decodes alone).
struct CoefModels {
  std::array<std::array<BitModel, kCoefUnaryModels>, kCoefClasses> unary{};
  // Top kCoefModelledLow low bits as a binary tree (node 1..), one tree for high part 0, one for > 0.
  std::array<std::array<BitModel, 2 << kCoefModelledLow>, kCoefClasses> low{};
  // Sign, by the signs of the x-1, y-1, z-1 neighbours and whether the index is 1 or larger
  // (neighbour signs agree more with a large coefficient's): streams 2-5% smaller than with raw signs.
  std::array<BitModel, 2 * kCoefSignContexts> sign{};
  static constexpr int kSignContexts = kCoefSignContexts;
};

// Block indices with a zero border before x, y, z and after x, so every causal neighbour of a
// block coefficient is a plain load.
class CoefPlane {
 public:
  explicit CoefPlane(const Extent& size)
      : nx_(size[0] + 2), ny_(size[1] + 2), q_(nx_ * ny_ * (size[2] + 1), 0u), s_(q_.size(), 0) {}
  // Position of block coefficient (x, y, z).
  std::size_t at(std::size_t x, std::size_t y, std::size_t z) const {
    return (x + 1) + nx_ * ((y + 1) + ny_ * (z + 1));
  }
  // Context class of the coefficient at `p` from its coded neighbours: x-1 (twice), y-1 (twice),
  // z-1 (twice), and the diagonals (x-1, y-1), (x+1, y-1), (x, y-1, z-1) once; 9 weights.
  int context(std::size_t p) const {
    const std::uint32_t* q = q_.data();
    const std::size_t dy = nx_, dz = nx_ * ny_;
    const std::uint64_t s = 2 * (std::uint64_t(q[p - 1]) + q[p - dy] + q[p - dz]) +
                            std::uint64_t(q[p - 1 - dy]) + q[p + 1 - dy] + q[p - dy - dz] + q[p - 1 - dz] +
                            q[p + 1 - dz] + q[p + dy - dz];
    // Half-octave classes: the bit width and the bit below the leading one.
    const int w = int(std::bit_width(s));
    const int cls = s < 2 ? int(s) : 2 * w - 2 + int((s >> (w - 2)) & 1u);
    return std::min(cls, kCoefClasses - 1);
  }
  void set(std::size_t p, std::uint32_t v) { q_[p] = v; }
  void set_sign(std::size_t p, int s) { s_[p] = std::int8_t(s); }
  // Sign context: each of the x-1, y-1, z-1 neighbours negative, zero or positive.
  std::size_t sign_context(std::size_t p) const {
    const std::size_t dy = nx_, dz = nx_ * ny_;
    return std::size_t(9 * (s_[p - 1] + 1) + 3 * (s_[p - dy] + 1) + (s_[p - dz] + 1));
  }

 private:
  std::size_t nx_, ny_;
  std::vector<std::uint32_t> q_;
  std::vector<std::int8_t> s_;  // -1, 0, +1
};

// Golomb-Rice parameter of a context class.
inline int coef_rice_k(int ctx) { return std::max((ctx >> 1) - kCoefKOffset, 0); }

}  // namespace pupwave
