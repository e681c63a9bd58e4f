#include "codec/block_contexts.h"

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

using SigTable = std::array<std::array<std::array<std::array<std::uint8_t, 5>, 3>, 3>, 3>;

constexpr SigTable make_sig_table() {
  SigTable t{};
  for (int h = 0; h < 3; ++h)
    for (int v = 0; v < 3; ++v)
      for (int d = 0; d < 5; ++d) {
        t[0][h][v][d] = std::uint8_t(context_hv(h, v, d));
        t[1][h][v][d] = std::uint8_t(context_hv(v, h, d));  // high-pass in x: vertical edges
        t[2][h][v][d] = std::uint8_t(context_diagonal(h, v, d));
      }
  return t;
}

constexpr SigTable kSigTable = make_sig_table();

}  // namespace

BlockState::BlockState(const Extent& size, unsigned orientation) : size_(size) {
  const bool high_x = orientation & 1u;
  const bool high_y = orientation & 2u;
  table_ = high_x && high_y ? 2 : (high_x ? 1 : 0);
  volume_ = size[2] > 1;
  stride_y_ = size[0] + 2;
  stride_z_ = stride_y_ * (size[1] + 2);
  flags_.assign(stride_z_ * (size[2] + 2), 0);
  // Most coefficients of a block stay insignificant with no significant neighbour.
  models[0] = BitModel(std::uint16_t(kProbabilityOne * 15 / 16));
  models[kRunContext] = BitModel(std::uint16_t(kProbabilityOne * 7 / 8));
}

int BlockState::significance_context(std::size_t p) const {
  const int h = sig(p - 1) + sig(p + 1);
  const int v = sig(p - stride_y_) + sig(p + stride_y_);
  int d = sig(p - stride_y_ - 1) + sig(p - stride_y_ + 1) + sig(p + stride_y_ - 1) + sig(p + stride_y_ + 1);
  if (volume_) d = std::min(4, d + sig(p - stride_z_) + sig(p + stride_z_));
  return kSigTable[std::size_t(table_)][std::size_t(h)][std::size_t(v)][std::size_t(d)];
}

std::pair<int, int> BlockState::sign_context(std::size_t p) const {
  const int h = std::clamp(sign_of(p - 1) + sign_of(p + 1), -1, 1);
  int v = sign_of(p - stride_y_) + sign_of(p + stride_y_);
  if (volume_) v += sign_of(p - stride_z_) + sign_of(p + stride_z_);
  v = std::clamp(v, -1, 1);
  // JPEG 2000 Table D.3: contexts are symmetric under negating both contributions.
  const int flip = (h < 0 || (h == 0 && v < 0)) ? 1 : 0;
  const int hh = flip ? -h : h;
  const int vv = flip ? -v : v;
  const int ctx = hh == 0 ? (vv == 0 ? 0 : 1) : 3 + vv;  // (0,0) (0,1) (1,-1) (1,0) (1,1)
  return {kSignContext0 + ctx, flip};
}

bool BlockState::isolated(std::size_t p) const {
  const std::size_t sy = stride_y_;
  bool any = sig(p - 1) || sig(p + 1) || sig(p - sy) || sig(p + sy) || sig(p - sy - 1) || sig(p - sy + 1) ||
             sig(p + sy - 1) || sig(p + sy + 1);
  if (volume_) any = any || sig(p - stride_z_) || sig(p + stride_z_);
  return !any;
}

int BlockState::refinement_context(std::size_t p) const {
  if (flags_[p] & kRefined) return kRefineContext0 + 2;
  return kRefineContext0 + (isolated(p) ? 0 : 1);
}

void BlockState::clear_visited() {
  for (auto& f : flags_) f = std::uint8_t(f & ~kVisited);
}

}  // namespace pupwave
