#include "codec/entropy/coef_encoder.h"

#include <bit>
#include <stdexcept>

#include "codec/entropy/block_encoder.h"
#include "codec/entropy/coef_contexts.h"
#include "codec/entropy/range_encoder.h"

namespace pupwave {
namespace {

// `n` (0..32) raw bits of `v`, the high chunk first (the coder takes at most 16 at once).
inline void put_raw(RangeEncoder& enc, std::uint64_t v, int n) {
  if (n > kCoefRawChunk) {
    enc.encode_raw(std::uint32_t(v >> kCoefRawChunk), n - kCoefRawChunk);
    enc.encode_raw(std::uint32_t(v), kCoefRawChunk);
  } else if (n > 0) {
    enc.encode_raw(std::uint32_t(v), n);
  }
}

// One index: unary high part (escape: Elias-gamma raw), modelled top low bit, raw rest and sign.
void put_index(RangeEncoder& enc, CoefModels& m, int ctx, std::size_t sign_ctx, std::uint32_t q,
               bool negative) {
  const int k = coef_rice_k(ctx);
  const std::uint32_t h = q >> k;
  auto& unary = m.unary[std::size_t(ctx)];
  const std::uint32_t ones = std::min<std::uint32_t>(h, kCoefEscape);
  for (std::uint32_t j = 0; j < ones; ++j)
    enc.encode(1, unary[std::min<std::size_t>(j, kCoefUnaryModels - 1)]);
  if (h < kCoefEscape) {
    enc.encode(0, unary[std::min<std::size_t>(h, kCoefUnaryModels - 1)]);
  } else {
    const std::uint32_t e = h - kCoefEscape;
    const int n = int(std::bit_width(e));
    enc.encode_raw(std::uint32_t(n), 5);
    put_raw(enc, e, n);
  }
  // The top low bits with models (a binary tree per high part zero / non-zero), the rest raw.
  const int modelled = std::min(k, kCoefModelledLow);
  auto& low = m.low[std::size_t(ctx)];
  std::size_t node = 1;
  const std::size_t tree = h > 0 ? std::size_t(1) << kCoefModelledLow : 0;
  for (int b = k - 1; b >= k - modelled; --b) {
    const int bit = int((q >> b) & 1u);
    enc.encode(bit, low[tree + node]);
    node = 2 * node + std::size_t(bit);
  }
  const int rest_bits = k - modelled;
  const std::uint32_t rest = q & ((1u << rest_bits) - 1u);
  put_raw(enc, rest, rest_bits);
  if (q != 0) enc.encode(negative ? 1 : 0, m.sign[sign_ctx + (q > 1 ? kCoefSignContexts : 0)]);
}

}  // namespace

CoefCodeword encode_coefficients(std::span<const std::uint32_t> index, std::span<const std::uint8_t> negative,
                                 const Extent& size) {
  if (index.size() != size[0] * size[1] * size[2] || negative.size() != index.size())
    throw std::invalid_argument("encode_coefficients: coefficient count does not match the block size");
  std::uint32_t all = 0;
  for (std::uint32_t q : index) all |= q;
  CoefCodeword out;
  out.bits = int(std::bit_width(all));
  if (out.bits > kCoefMaxBits)
    throw IndexRangeError("quantization index too large for the coefficient coder");
  if (out.bits == 0) return out;
  RangeEncoder enc;
  CoefModels models;
  CoefPlane plane(size);
  std::size_t i = 0;
  for (std::size_t z = 0; z < size[2]; ++z)
    for (std::size_t y = 0; y < size[1]; ++y) {
      std::size_t p = plane.at(0, y, z);
      for (std::size_t x = 0; x < size[0]; ++x, ++i, ++p) {
        const std::uint32_t q = index[i];
        const bool neg = negative[i] != 0;
        put_index(enc, models, plane.context(p), plane.sign_context(p), q, neg);
        plane.set(p, q);
        plane.set_sign(p, q == 0 ? 0 : neg ? -1 : 1);
      }
    }
  out.bytes = enc.finish();
  return out;
}

}  // namespace pupwave
