#include "codec/entropy/pc_blocks.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <utility>

#include "codec/entropy/block_encoder.h"
#include "codec/entropy/coef_contexts.h"
#include "codec/entropy/range_decoder.h"
#include "codec/entropy/range_encoder.h"
#include "codec/error.h"

namespace pupwave {
namespace {

// The block's contexts as the codeword goes: causal magnitudes and signs (padded by one column
// each side and one row above) and the parent band.
class PcContext {
 public:
  PcContext(std::size_t w, std::size_t h, const LcParent& parent)
      : nx_(w + 2), a_((h + 1) * nx_, 0u), sg_((h + 1) * nx_, 0), parent_(parent) {}

  // Activity class and sign context of coefficient (x, y): the in-band sum 2 (W + N) + NW + NE
  // (the volume coder's), with a parent doubled and plus the parent's magnitude (weight 1:
  // heavier weights measured worse); the sign context by the signs of W, N and the parent.
  std::pair<int, std::size_t> at(std::size_t x, std::size_t y) const {
    const std::size_t p = (y + 1) * nx_ + x + 1;
    std::uint64_t s = 2 * (std::uint64_t(a_[p - 1]) + a_[p - nx_]) + a_[p - 1 - nx_] + a_[p + 1 - nx_];
    int ps = 0;
    if (parent_.origin) {
      s *= 2;
      const std::size_t py = std::min((parent_.y0 + y) >> 1, parent_.height - 1);
      const std::size_t px = std::min((parent_.x0 + x) >> 1, parent_.width - 1);
      const std::int32_t c = parent_.origin[py * parent_.stride + px];
      s += std::uint64_t(c < 0 ? -std::int64_t(c) : c);
      ps = c == 0 ? 0 : (c < 0 ? -1 : 1);
    }
    const int w = int(std::bit_width(s));
    const int cls = std::min(s < 2 ? int(s) : 2 * w - 2 + int((s >> (w - 2)) & 1u), kCoefClasses - 1);
    return {cls, std::size_t(9 * (sg_[p - 1] + 1) + 3 * (sg_[p - nx_] + 1) + (ps + 1))};
  }
  void set(std::size_t x, std::size_t y, std::int32_t v) {
    const std::size_t p = (y + 1) * nx_ + x + 1;
    a_[p] = std::uint32_t(v < 0 ? -std::int64_t(v) : v);
    sg_[p] = std::int8_t(v == 0 ? 0 : (v < 0 ? -1 : 1));
  }

 private:
  std::size_t nx_;
  std::vector<std::uint32_t> a_;
  std::vector<std::int8_t> sg_;
  LcParent parent_;
};

// Bits the models would spend on index q now (no adaptation): the RDOQ's rate.
double cost(const BitModel& m, int bit) {
  const std::uint32_t p = bit ? kProbabilityOne - m.p0 : m.p0;
  return -std::log2(double(p) / double(kProbabilityOne));
}

double index_bits(const CoefModels& m, int ctx, std::size_t sign_ctx, std::uint32_t q, bool negative) {
  const int k = coef_rice_k(ctx);
  const std::uint32_t h = q >> k;
  const auto& unary = m.unary[std::size_t(ctx)];
  double bits = 0.0;
  for (std::uint32_t j = 0; j < std::min<std::uint32_t>(h, kCoefEscape); ++j)
    bits += cost(unary[std::min<std::size_t>(j, kCoefUnaryModels - 1)], 1);
  if (h < kCoefEscape)
    bits += cost(unary[std::min<std::size_t>(h, kCoefUnaryModels - 1)], 0);
  else
    bits += 5.0 + double(std::bit_width(h - kCoefEscape));
  const int modelled = std::min(k, kCoefModelledLow);
  const auto& low = m.low[std::size_t(ctx)];
  std::size_t node = 1;
  const std::size_t tree = h > 0 ? std::size_t(1) << kCoefModelledLow : 0;
  for (int b = k - 1; b >= k - modelled; --b) {
    const int bit = int((q >> b) & 1u);
    bits += cost(low[tree + node], bit);
    node = 2 * node + std::size_t(bit);
  }
  bits += double(k - modelled);
  if (q != 0) bits += cost(m.sign[sign_ctx + (q > 1 ? kCoefSignContexts : 0)], negative ? 1 : 0);
  return bits;
}

// `n` (0..32) raw bits of `v`, the high chunk first (the coder takes at most 16 at once).
void put_raw(RangeEncoder& enc, std::uint64_t v, int n) {
  if (n > kCoefRawChunk) {
    enc.encode_raw(std::uint32_t(v >> kCoefRawChunk), n - kCoefRawChunk);
    enc.encode_raw(std::uint32_t(v), kCoefRawChunk);
  } else if (n > 0) {
    enc.encode_raw(std::uint32_t(v), n);
  }
}

std::uint64_t get_raw(RangeDecoder& dec, int n) {
  if (n > kCoefRawChunk) {
    const std::uint64_t high = dec.decode_raw(n - kCoefRawChunk);
    return (high << kCoefRawChunk) | dec.decode_raw(kCoefRawChunk);
  }
  return n > 0 ? dec.decode_raw(n) : 0;
}

// coef_encoder.cpp's put_index.
void put_index(RangeEncoder& enc, CoefModels& m, int ctx, std::size_t sign_ctx, std::uint32_t q,
               bool negative) {
  const int k = coef_rice_k(ctx);
  const std::uint32_t h = q >> k;
  auto& unary = m.unary[std::size_t(ctx)];
  for (std::uint32_t j = 0; j < std::min<std::uint32_t>(h, kCoefEscape); ++j)
    enc.encode(1, unary[std::min<std::size_t>(j, kCoefUnaryModels - 1)]);
  if (h < kCoefEscape) {
    enc.encode(0, unary[std::min<std::size_t>(h, kCoefUnaryModels - 1)]);
  } else {
    const std::uint32_t e = h - kCoefEscape;
    enc.encode_raw(std::uint32_t(std::bit_width(e)), 5);
    put_raw(enc, e, int(std::bit_width(e)));
  }
  const int modelled = std::min(k, kCoefModelledLow);
  auto& low = m.low[std::size_t(ctx)];
  std::size_t node = 1;
  const std::size_t tree = h > 0 ? std::size_t(1) << kCoefModelledLow : 0;
  for (int b = k - 1; b >= k - modelled; --b) {
    const int bit = int((q >> b) & 1u);
    enc.encode(bit, low[tree + node]);
    node = 2 * node + std::size_t(bit);
  }
  put_raw(enc, q & ((1u << (k - modelled)) - 1u), k - modelled);
  if (q != 0) enc.encode(negative ? 1 : 0, m.sign[sign_ctx + (q > 1 ? kCoefSignContexts : 0)]);
}

// coef_decoder.cpp's get_index; the magnitude is clamped to `limit` (corrupt input only).
std::uint32_t get_index(RangeDecoder& dec, CoefModels& m, int ctx, std::size_t sign_ctx, std::uint64_t limit,
                        bool& negative) {
  const int k = coef_rice_k(ctx);
  auto& unary = m.unary[std::size_t(ctx)];
  std::uint64_t h = 0;
  while (h < kCoefEscape && dec.decode(unary[std::min<std::size_t>(h, kCoefUnaryModels - 1)]) != 0) ++h;
  if (h == kCoefEscape) h += get_raw(dec, int(dec.decode_raw(5)));  // at most 31 bits
  const int modelled = std::min(k, kCoefModelledLow);
  auto& low = m.low[std::size_t(ctx)];
  std::size_t node = 1;
  const std::size_t tree = h > 0 ? std::size_t(1) << kCoefModelledLow : 0;
  for (int b = 0; b < modelled; ++b) node = 2 * node + std::size_t(dec.decode(low[tree + node]));
  const std::uint64_t top = (node - (std::size_t(1) << modelled)) | (h << modelled);
  const std::uint64_t value = (top << (k - modelled)) | get_raw(dec, k - modelled);
  negative = value != 0 && dec.decode(m.sign[sign_ctx + (value > 1 ? kCoefSignContexts : 0)]) != 0;
  return std::uint32_t(std::min(value, limit));
}

// The RDOQ choice for coefficient magnitude x (index units) whose nearest point is `nearest`.
std::uint32_t rdoq_choice(const CoefModels& m, int ctx, std::size_t sc, double x, std::uint32_t nearest,
                          bool neg, const PcRdoq& r) {
  double best = 0.0;
  std::uint32_t pick = nearest;
  for (std::uint32_t c : {nearest, nearest - 1, 0u}) {
    const double d = x - (c == 0 ? 0.0 : double(c) + r.delta);
    const double j = d * d + r.lambda * index_bits(m, ctx, sc, c, neg);
    if (c == nearest || j < best) {
      best = j;
      pick = c;
    }
  }
  return pick;
}

}  // namespace

CoefCodeword pc_encode_block(std::vector<std::int32_t>& q, std::size_t width, std::size_t height,
                             const LcParent& parent, const PcRdoq* rdoq) {
  if (q.size() != width * height)
    throw std::invalid_argument("pc_encode_block: index count differs from the size");
  if (rdoq) {
    if (rdoq->coefficients.size() != q.size())
      throw std::invalid_argument("pc_encode_block: coefficient count differs from the size");
    for (std::size_t k = 0; k < q.size(); ++k) {  // the nearest reconstruction points
      const double x = std::fabs(double(rdoq->coefficients[k]));
      const double n = std::max(0.0, std::floor(x - rdoq->delta + 0.5));
      if (n >= double(1u << kCoefMaxBits)) throw IndexRangeError("index too large for the pc coder");
      q[k] = rdoq->coefficients[k] < 0 ? -std::int32_t(n) : std::int32_t(n);
    }
  }
  std::uint64_t all = 0;
  for (std::int32_t v : q) all |= std::uint64_t(v < 0 ? -std::int64_t(v) : v);
  if (all >= (std::uint64_t(1) << kCoefMaxBits)) throw IndexRangeError("index too large for the pc coder");
  CoefCodeword out;
  if (all == 0) return out;
  RangeEncoder enc;
  auto models = std::make_unique<CoefModels>();
  PcContext ctx(width, height, parent);
  std::uint32_t largest = 0;
  for (std::size_t y = 0; y < height; ++y)
    for (std::size_t x = 0; x < width; ++x) {
      const auto [cls, sc] = ctx.at(x, y);
      std::int32_t& v = q[y * width + x];
      const bool neg = v < 0;
      auto a = std::uint32_t(neg ? -std::int64_t(v) : v);
      if (rdoq && a != 0) {
        a = rdoq_choice(*models, cls, sc, std::fabs(double(rdoq->coefficients[y * width + x])), a, neg,
                        *rdoq);
        v = neg ? -std::int32_t(a) : std::int32_t(a);
      }
      put_index(enc, *models, cls, sc, a, neg);
      ctx.set(x, y, v);
      largest = std::max(largest, a);
    }
  out.bits = int(std::bit_width(largest));  // RDOQ may have lowered it: the decoder checks this one
  if (out.bits == 0) return out;            // RDOQ zeroed everything: no codeword
  out.bytes = enc.finish();
  if (out.bytes.empty()) out.bytes.push_back(0);  // a codeword is never empty (the index says so)
  return out;
}

void pc_decode_block(std::span<const std::uint8_t> codeword, int bits, std::size_t width, std::size_t height,
                     const LcParent& parent, std::int32_t* out, std::size_t stride) {
  require_stream(bits >= 1 && bits <= kCoefMaxBits && !codeword.empty(), "pc code-block: index bit width");
  const std::uint64_t limit = (std::uint64_t(1) << bits) - 1;
  RangeDecoder dec(codeword);
  auto models = std::make_unique<CoefModels>();
  PcContext ctx(width, height, parent);
  std::uint32_t largest = 0;
  for (std::size_t y = 0; y < height; ++y)
    for (std::size_t x = 0; x < width; ++x) {
      const auto [cls, sc] = ctx.at(x, y);
      bool negative = false;
      const std::uint32_t a = get_index(dec, *models, cls, sc, limit, negative);
      const std::int32_t v = negative ? -std::int32_t(a) : std::int32_t(a);
      out[y * stride + x] = v;
      ctx.set(x, y, v);
      largest = std::max(largest, a);
    }
  require_stream(int(std::bit_width(largest)) == bits, "pc code-block: largest index differs from the index");
}

}  // namespace pupwave
