#include "codec/entropy/block_contexts.h"

#include <algorithm>

#include "codec/entropy/block_tally.h"
#include "codec/entropy/ctx_priors.h"

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

// Context for every neighbour count byte (see BlockState::neighbours_), per orientation
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

}  // namespace

// Context * 2 + XOR bit for every sign word (h + 2) + 5 (v + 4).
const std::array<std::uint8_t, 45> BlockState::kSignTable = [] {
  std::array<std::uint8_t, 45> t{};
  for (int h = -2; h <= 2; ++h)
    for (int v = -4; v <= 4; ++v) {
      const auto [ctx, flip] = sign_context_of(std::clamp(h, -1, 1), std::clamp(v, -1, 1));
      t[std::size_t((h + 2) * kSignCodeH + (v + 4) * kSignCodeV)] = std::uint8_t(ctx * 2 + flip);
    }
  return t;
}();

static_assert(std::tuple_size_v<decltype(kContextPriors)::value_type> == kBlockContexts);

BlockState::BlockState(const Extent& size, unsigned orientation) : size_(size) {
  const bool high_x = orientation & 1u;
  const bool high_y = orientation & 2u;
  const int table = high_x && high_y ? 2 : (high_x ? 1 : 0);
  volume_ = size[2] > 1;
  stride_y_ = size[0] + 2;
  stride_z_ = stride_y_ * (size[1] + 2);
  neighbours_.assign(stride_z_ * (size[2] + 2), std::uint16_t(kSignCodeZero * kSignUnit));
  sig_table_ = kSigTable[std::size_t(table)].data();
  stripes_ = (size[1] + kStripe - 1) / kStripe;
  column_row_ = size[0] + 4;
  column_slice_ = column_row_ * (stripes_ + 2);
  columns_.assign(column_slice_ * (size[2] + 2), 0);
  active_.assign(stripes_ * size[2], 0);
  const std::size_t prior_class = prior_class_of(orientation);
  for (std::size_t k = 0; k < models.size(); ++k)
    models[k] = prior_model(kContextPriors[prior_class][k], kContextPriorCounts[prior_class][k]);
}

}  // namespace pupwave
