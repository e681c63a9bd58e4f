#include "codec/entropy/block_contexts.h"

#include <algorithm>

namespace pupwave {
namespace {

// Significance context from counts of significant horizontal (h <= 2), vertical (v <= 2)
// and diagonal (d <= 4) neighbours, for the band where horizontal neighbours matter most
// (JPEG 2000 Table D.1, LL/LH column).
constexpr int context_hv(int h, int v, int d) {
  if (h == 2) return 8;
  if (h == 1) return v >= 1 ? 7 : (d >= 1 ? 6 : 5);
  if (v == 2) return 4;
  if (v == 1) return 3;
  return d >= 2 ? 2 : d;
}

// The same for bands high-pass in both axes, where diagonal neighbours matter most.
constexpr int context_diagonal(int h, int v, int d) {
  const int hv = h + v;
  if (d >= 3) return 8;
  if (d == 2) return hv >= 1 ? 7 : 6;
  if (d == 1) return hv >= 2 ? 5 : (hv == 1 ? 4 : 3);
  return hv >= 2 ? 2 : hv;
}

// Context for every packed neighbour word (see BlockState::neighbours_), per orientation
// table; diagonal counts above 4 (3-D blocks) saturate at 4.
using SigTable = std::array<std::array<std::uint8_t, 256>, 3>;

constexpr SigTable make_sig_table() {
  SigTable t{};
  for (int word = 0; word < 256; ++word) {
    const int h = std::min(word & 3, 2);
    const int v = std::min((word >> 2) & 3, 2);
    const int d = std::min(word >> 4, 4);
    t[0][std::size_t(word)] = std::uint8_t(context_hv(h, v, d));
    t[1][std::size_t(word)] = std::uint8_t(context_hv(v, h, d));  // high-pass in x: vertical edges
    t[2][std::size_t(word)] = std::uint8_t(context_diagonal(h, v, d));
  }
  return t;
}

constexpr SigTable kSigTable = make_sig_table();

// Sign context (0..4) and XOR bit from the clamped horizontal and vertical contributions
// (JPEG 2000 Table D.3: contexts are symmetric under negating both contributions).
constexpr std::pair<int, int> sign_context_of(int h, int v) {
  const int flip = (h < 0 || (h == 0 && v < 0)) ? 1 : 0;
  const int hh = flip ? -h : h;
  const int vv = flip ? -v : v;
  return {hh == 0 ? (vv == 0 ? 0 : 1) : 3 + vv, flip};  // (0,0) (0,1) (1,-1) (1,0) (1,1)
}

// +1 / -1 / 0 of a 2-bit sign state (bit 0: significant, bit 1: negative).
constexpr int sign_of_state(std::size_t s) { return (s & 1) ? ((s & 2) ? -1 : 1) : 0; }

// Context * 2 + XOR bit for every combination of the four direct neighbours' sign states
// (left, right, up, down; 2 bits each, as BlockState::sign_state gives them).
constexpr std::array<std::uint8_t, 256> make_sign_table() {
  std::array<std::uint8_t, 256> t{};
  for (std::size_t key = 0; key < 256; ++key) {
    const int h = std::clamp(sign_of_state(key & 3) + sign_of_state((key >> 2) & 3), -1, 1);
    const int v = std::clamp(sign_of_state((key >> 4) & 3) + sign_of_state((key >> 6) & 3), -1, 1);
    const auto [ctx, flip] = sign_context_of(h, v);
    t[key] = std::uint8_t(ctx * 2 + flip);
  }
  return t;
}

constexpr std::array<std::uint8_t, 256> kSignTable = make_sign_table();

}  // namespace

BlockState::BlockState(const Extent& size, unsigned orientation) : size_(size) {
  const bool high_x = orientation & 1u;
  const bool high_y = orientation & 2u;
  table_ = high_x && high_y ? 2 : (high_x ? 1 : 0);
  volume_ = size[2] > 1;
  stride_y_ = size[0] + 2;
  stride_z_ = stride_y_ * (size[1] + 2);
  flags_.assign(stride_z_ * (size[2] + 2), 0);
  neighbours_.assign(flags_.size(), 0);
  sig_table_ = kSigTable[std::size_t(table_)].data();
  stripes_ = (size[1] + kStripe - 1) / kStripe;
  active_.assign(stripes_ * size[2], 0);
  // Most coefficients of a block stay insignificant with no significant neighbour.
  models[0] = BitModel(std::uint16_t(kProbabilityOne * 15 / 16));
  models[kRunContext] = BitModel(std::uint16_t(kProbabilityOne * 7 / 8));
}

std::pair<int, int> BlockState::sign_context(std::size_t p) const {
  if (!volume_) {  // 2-D: one look-up on the four direct neighbours' sign states
    const std::size_t key = sign_state(p - 1) | sign_state(p + 1) << 2 | sign_state(p - stride_y_) << 4 |
                            sign_state(p + stride_y_) << 6;
    const std::uint8_t e = kSignTable[key];
    return {kSignContext0 + (e >> 1), e & 1};
  }
  const int h = std::clamp(sign_of(p - 1) + sign_of(p + 1), -1, 1);
  const int v =
      sign_of(p - stride_y_) + sign_of(p + stride_y_) + sign_of(p - stride_z_) + sign_of(p + stride_z_);
  const auto [ctx, flip] = sign_context_of(h, std::clamp(v, -1, 1));
  return {kSignContext0 + ctx, flip};
}

void BlockState::clear_visited() {
  for (auto& f : flags_) f = std::uint8_t(f & ~kVisited);
}

}  // namespace pupwave
