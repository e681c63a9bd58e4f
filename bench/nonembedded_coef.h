#pragma once
// The code length of one detail band under the volume coder's model (codec/entropy/
// coef_contexts.h, coef_encoder.cpp: Rice classes from the neighbour sum, unary high part with
// models, modelled top low bits, raw rest, sign by neighbour signs) treating the band as a
// 1-deep volume, with the parent coefficient one level coarser put where the z-1 neighbour
// would be (its sign in the sign context; in the sum, with the neighbour terms doubled,
// `parent_weight` x the parent: the volume coder's z-1 weights, 2 + 4 x 1, over-weigh it), or
// not (parent null: the volume coder exactly). For the nonembedded_rd estimate (bench/nonembedded_rd.cpp).

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "codec/entropy/coef_contexts.h"
#include "codec/entropy/coef_index.h"
#include "codec/entropy/pc_blocks.h"

namespace pupwave::estimate {

// Bits of the band's signed indices q (w x h) in `ctx` (the pc coder's binarisation and models,
// pc_index.h, with pc_blocks' contexts; this estimate gives no block a luma parent). lambda > 0: greedy RDOQ
// from the coefficients in index units `u` as in nonembedded_model.h (q rewritten to the chosen indices,
// pc_rdoq_index), reconstruction offset delta.
inline double coef_band_bits(std::vector<std::int32_t>& q, std::size_t w, std::size_t h, PcContext ctx,
                             const std::vector<float>& u, double lambda, double delta) {
  if (lambda > 0.0)
    for (std::size_t k = 0; k < q.size(); ++k) {
      const auto n = std::int32_t(std::max(0.0, std::floor(std::fabs(double(u[k])) - delta + 0.5)));
      q[k] = u[k] < 0 ? -n : n;
    }
  if (std::all_of(q.begin(), q.end(), [](std::int32_t v) { return v == 0; })) return 0.0;  // no codeword
  auto m = std::make_unique<PcModels>();
  double bits = 0.0;
  pc_visit(w, h, ctx, [&](std::size_t x, std::size_t y, const PcCtx& c) {
    std::int32_t& v = q[y * w + x];
    if (lambda > 0.0) v = pc_rdoq_index(*m, c, u[y * w + x], v, lambda, delta);
    bits += pc_index_bits<true>(*m, c, std::uint32_t(std::abs(v)), v < 0);
    return v;
  });
  return bits;
}

// The real codeword of the band's indices q in `ctx` (pc_blocks' coder with these contexts): the
// round-trip check that the estimate is a decodable code.
inline std::vector<std::uint8_t> coef_band_encode(const std::vector<std::int32_t>& q, std::size_t w,
                                                  std::size_t h, const PcContext& ctx) {
  std::vector<std::int32_t> copy = q;
  return pc_encode_indices(copy, w, h, ctx, nullptr).first;
}

// Its decoder.
inline std::vector<std::int32_t> coef_band_decode(std::span<const std::uint8_t> word, std::size_t w,
                                                  std::size_t h, const PcContext& ctx) {
  std::vector<std::int32_t> q(w * h, 0);
  pc_decode_indices(word, std::uint64_t(1) << 30, w, h, ctx, q.data(), w);
  return q;
}

}  // namespace pupwave::estimate
