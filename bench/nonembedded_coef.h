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
#include <vector>

#include "codec/entropy/coef_contexts.h"

namespace pupwave::estimate {

template <bool Update>
double model_bits(BitModel& m, int bit) {
  const std::uint32_t p = bit ? kProbabilityOne - m.p0 : m.p0;
  if constexpr (Update) m.update(bit);
  return -std::log2(double(p) / double(kProbabilityOne));
}

// coef_encoder.cpp's put_index, counting bits (Update: adapting the models as it would).
template <bool Update>
double coef_index_bits(CoefModels& m, int ctx, std::size_t sign_ctx, std::uint32_t q, bool negative) {
  const int k = coef_rice_k(ctx);
  const std::uint32_t h = q >> k;
  auto& unary = m.unary[std::size_t(ctx)];
  double bits = 0.0;
  const std::uint32_t ones = std::min<std::uint32_t>(h, kCoefEscape);
  for (std::uint32_t j = 0; j < ones; ++j)
    bits += model_bits<Update>(unary[std::min<std::size_t>(j, kCoefUnaryModels - 1)], 1);
  if (h < kCoefEscape)
    bits += model_bits<Update>(unary[std::min<std::size_t>(h, kCoefUnaryModels - 1)], 0);
  else
    bits += 5 + std::bit_width(h - kCoefEscape);
  const int modelled = std::min(k, kCoefModelledLow);
  auto& low = m.low[std::size_t(ctx)];
  std::size_t node = 1;
  const std::size_t tree = h > 0 ? std::size_t(1) << kCoefModelledLow : 0;
  for (int b = k - 1; b >= k - modelled; --b) {
    const int bit = int((q >> b) & 1u);
    bits += model_bits<Update>(low[tree + node], bit);
    node = 2 * node + std::size_t(bit);
  }
  bits += k - modelled;
  if (q != 0)
    bits += model_bits<Update>(m.sign[sign_ctx + (q > 1 ? kCoefSignContexts : 0)], negative ? 1 : 0);
  return bits;
}

// Bits of the band's signed indices q (w x h); parent: the coarser band's signed indices
// (origin null: none), coefficient (x, y) under parent (x / 2, y / 2) clamped.
// lambda > 0: greedy RDOQ from the coefficients in index units `u` as in nonembedded_model.h
// (q rewritten to the chosen indices), reconstruction offset delta.
inline double coef_band_bits(std::vector<std::int32_t>& q, std::size_t w, std::size_t h,
                             const std::int32_t* parent, std::size_t pstride, std::size_t pwidth,
                             std::size_t pheight, int parent_weight, int scale, const std::vector<float>& u,
                             double lambda, double delta) {
  if (lambda > 0.0)
    for (std::size_t k = 0; k < q.size(); ++k) {
      const auto n = std::int32_t(std::max(0.0, std::floor(std::fabs(double(u[k])) - delta + 0.5)));
      q[k] = u[k] < 0 ? -n : n;
    }
  if (std::all_of(q.begin(), q.end(), [](std::int32_t v) { return v == 0; })) return 0.0;  // no codeword
  auto m = std::make_unique<CoefModels>();
  const std::size_t nx = w + 2;
  std::vector<std::uint32_t> a((h + 1) * nx, 0u);
  std::vector<int> sg((h + 1) * nx, 0);
  double bits = 0.0;
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const std::size_t p = (y + 1) * nx + x + 1;
      std::uint64_t s = 2 * (std::uint64_t(a[p - 1]) + a[p - nx]) + a[p - 1 - nx] + a[p + 1 - nx];
      if (parent) s *= 2 * std::uint64_t(scale);
      int ps = 0;
      if (parent) {
        auto at = [&](std::ptrdiff_t px, std::ptrdiff_t py) {
          px = std::clamp<std::ptrdiff_t>(px, 0, std::ptrdiff_t(pwidth) - 1);
          py = std::clamp<std::ptrdiff_t>(py, 0, std::ptrdiff_t(pheight) - 1);
          return parent[std::size_t(py) * pstride + std::size_t(px)];
        };
        const auto px = std::ptrdiff_t(x >> 1), py = std::ptrdiff_t(y >> 1);
        const std::int32_t c = at(px, py);
        s += std::uint64_t(parent_weight) * std::uint64_t(std::abs(c));
        ps = c == 0 ? 0 : (c < 0 ? -1 : 1);
      }
      const int wdt = int(std::bit_width(s));
      const int cls = std::min(s < 2 ? int(s) : 2 * wdt - 2 + int((s >> (wdt - 2)) & 1u), kCoefClasses - 1);
      const std::size_t sc = std::size_t(9 * (sg[p - 1] + 1) + 3 * (sg[p - nx] + 1) + (ps + 1));
      std::int32_t& v = q[y * w + x];
      if (lambda > 0.0 && v != 0) {  // the nearest point, the one below, zero
        const double x0 = std::fabs(double(u[y * w + x]));
        const auto nearest = std::uint32_t(std::abs(v));
        const bool neg = v < 0;
        double best = 1e300;
        std::uint32_t pick = nearest;
        for (std::uint32_t c : {nearest, nearest - 1, 0u}) {
          const double r = c == 0 ? 0.0 : double(c) + delta;
          const double j = (x0 - r) * (x0 - r) + lambda * coef_index_bits<false>(*m, cls, sc, c, neg);
          if (j < best) {
            best = j;
            pick = c;
          }
        }
        v = neg ? -std::int32_t(pick) : std::int32_t(pick);
      }
      bits += coef_index_bits<true>(*m, cls, sc, std::uint32_t(std::abs(v)), v < 0);
      a[p] = std::uint32_t(std::abs(v));
      sg[p] = v == 0 ? 0 : (v < 0 ? -1 : 1);
    }
  return bits;
}

}  // namespace pupwave::estimate
