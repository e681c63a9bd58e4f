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
#include "codec/entropy/range_decoder.h"
#include "codec/entropy/range_encoder.h"

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

// The contexts of one band as the codeword goes: the in-band causal magnitudes and signs, and
// the parent band (the coarser band's signed indices, coefficient (x, y) under (x / 2, y / 2)
// clamped; null: none).
class BandContext {
 public:
  BandContext(std::size_t w, std::size_t h, const std::int32_t* parent, std::size_t pstride,
              std::size_t pwidth, std::size_t pheight, int parent_weight, int scale)
      : nx_(w + 2),
        a_((h + 1) * nx_, 0u),
        sg_((h + 1) * nx_, 0),
        parent_(parent),
        pstride_(pstride),
        pwidth_(pwidth),
        pheight_(pheight),
        weight_(parent_weight),
        scale_(scale) {}

  // Activity class and sign context of coefficient (x, y).
  std::pair<int, std::size_t> at(std::size_t x, std::size_t y) const {
    const std::size_t p = (y + 1) * nx_ + x + 1;
    std::uint64_t s = 2 * (std::uint64_t(a_[p - 1]) + a_[p - nx_]) + a_[p - 1 - nx_] + a_[p + 1 - nx_];
    int ps = 0;
    if (parent_) {
      s *= 2 * std::uint64_t(scale_);
      const std::int32_t c =
          parent_[std::min(y >> 1, pheight_ - 1) * pstride_ + std::min(x >> 1, pwidth_ - 1)];
      s += std::uint64_t(weight_) * std::uint64_t(std::abs(c));
      ps = c == 0 ? 0 : (c < 0 ? -1 : 1);
    }
    const int wdt = int(std::bit_width(s));
    const int cls = std::min(s < 2 ? int(s) : 2 * wdt - 2 + int((s >> (wdt - 2)) & 1u), kCoefClasses - 1);
    return {cls, std::size_t(9 * (sg_[p - 1] + 1) + 3 * (sg_[p - nx_] + 1) + (ps + 1))};
  }
  void set(std::size_t x, std::size_t y, std::int32_t v) {
    const std::size_t p = (y + 1) * nx_ + x + 1;
    a_[p] = std::uint32_t(std::abs(v));
    sg_[p] = v == 0 ? 0 : (v < 0 ? -1 : 1);
  }

 private:
  std::size_t nx_;
  std::vector<std::uint32_t> a_;
  std::vector<int> sg_;
  const std::int32_t* parent_;
  std::size_t pstride_, pwidth_, pheight_;
  int weight_, scale_;
};

// Bits of the band's signed indices q (w x h) in `ctx`. lambda > 0: greedy RDOQ from the
// coefficients in index units `u` as in nonembedded_model.h (q rewritten to the chosen
// indices), reconstruction offset delta.
inline double coef_band_bits(std::vector<std::int32_t>& q, std::size_t w, std::size_t h, BandContext ctx,
                             const std::vector<float>& u, double lambda, double delta) {
  if (lambda > 0.0)
    for (std::size_t k = 0; k < q.size(); ++k) {
      const auto n = std::int32_t(std::max(0.0, std::floor(std::fabs(double(u[k])) - delta + 0.5)));
      q[k] = u[k] < 0 ? -n : n;
    }
  if (std::all_of(q.begin(), q.end(), [](std::int32_t v) { return v == 0; })) return 0.0;  // no codeword
  auto m = std::make_unique<CoefModels>();
  double bits = 0.0;
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const auto [cls, sc] = ctx.at(x, y);
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
      ctx.set(x, y, v);
    }
  return bits;
}

// The real codeword of the band's indices q in `ctx` (coef_encoder.cpp's put_index with these
// contexts): the round-trip check that the estimate is a decodable code.
inline std::vector<std::uint8_t> coef_band_encode(const std::vector<std::int32_t>& q, std::size_t w,
                                                  std::size_t h, BandContext ctx) {
  RangeEncoder enc;
  auto m = std::make_unique<CoefModels>();
  auto raw = [&](std::uint64_t v, int n) {
    if (n > kCoefRawChunk) {
      enc.encode_raw(std::uint32_t(v >> kCoefRawChunk), n - kCoefRawChunk);
      enc.encode_raw(std::uint32_t(v), kCoefRawChunk);
    } else if (n > 0) {
      enc.encode_raw(std::uint32_t(v), n);
    }
  };
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const auto [cls, sc] = ctx.at(x, y);
      const std::int32_t v = q[y * w + x];
      const auto qa = std::uint32_t(std::abs(v));
      const int k = coef_rice_k(cls);
      const std::uint32_t hi = qa >> k;
      auto& unary = m->unary[std::size_t(cls)];
      for (std::uint32_t j = 0; j < std::min<std::uint32_t>(hi, kCoefEscape); ++j)
        enc.encode(1, unary[std::min<std::size_t>(j, kCoefUnaryModels - 1)]);
      if (hi < kCoefEscape) {
        enc.encode(0, unary[std::min<std::size_t>(hi, kCoefUnaryModels - 1)]);
      } else {
        const std::uint32_t e = hi - kCoefEscape;
        enc.encode_raw(std::uint32_t(std::bit_width(e)), 5);
        raw(e, int(std::bit_width(e)));
      }
      const int modelled = std::min(k, kCoefModelledLow);
      auto& low = m->low[std::size_t(cls)];
      std::size_t node = 1;
      const std::size_t tree = hi > 0 ? std::size_t(1) << kCoefModelledLow : 0;
      for (int b = k - 1; b >= k - modelled; --b) {
        const int bit = int((qa >> b) & 1u);
        enc.encode(bit, low[tree + node]);
        node = 2 * node + std::size_t(bit);
      }
      raw(qa & ((1u << (k - modelled)) - 1u), k - modelled);
      if (qa != 0) enc.encode(v < 0 ? 1 : 0, m->sign[sc + (qa > 1 ? kCoefSignContexts : 0)]);
      ctx.set(x, y, v);
    }
  return enc.finish();
}

// Its decoder (coef_decoder.cpp's get_index with these contexts).
inline std::vector<std::int32_t> coef_band_decode(std::span<const std::uint8_t> word, std::size_t w,
                                                  std::size_t h, BandContext ctx) {
  RangeDecoder dec(word);
  auto m = std::make_unique<CoefModels>();
  auto raw = [&](int n) -> std::uint64_t {
    if (n > kCoefRawChunk) {
      const std::uint64_t high = dec.decode_raw(n - kCoefRawChunk);
      return (high << kCoefRawChunk) | dec.decode_raw(kCoefRawChunk);
    }
    return n > 0 ? dec.decode_raw(n) : 0;
  };
  std::vector<std::int32_t> q(w * h, 0);
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const auto [cls, sc] = ctx.at(x, y);
      const int k = coef_rice_k(cls);
      auto& unary = m->unary[std::size_t(cls)];
      std::uint64_t hi = 0;
      while (hi < kCoefEscape && dec.decode(unary[std::min<std::size_t>(hi, kCoefUnaryModels - 1)]) != 0)
        ++hi;
      if (hi == kCoefEscape) hi += raw(int(dec.decode_raw(5)));
      const int modelled = std::min(k, kCoefModelledLow);
      auto& low = m->low[std::size_t(cls)];
      std::size_t node = 1;
      const std::size_t tree = hi > 0 ? std::size_t(1) << kCoefModelledLow : 0;
      for (int b = 0; b < modelled; ++b) node = 2 * node + std::size_t(dec.decode(low[tree + node]));
      const std::uint64_t top = (node - (std::size_t(1) << modelled)) | (hi << modelled);
      const std::uint64_t value = (top << (k - modelled)) | raw(k - modelled);
      const bool negative = value != 0 && dec.decode(m->sign[sc + (value > 1 ? kCoefSignContexts : 0)]) != 0;
      const auto v = std::int32_t(std::min<std::uint64_t>(value, 1u << 30));
      q[y * w + x] = negative ? -v : v;
      ctx.set(x, y, q[y * w + x]);
    }
  return q;
}

}  // namespace pupwave::estimate
