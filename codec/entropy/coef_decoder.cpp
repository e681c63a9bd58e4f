#include "codec/entropy/coef_decoder.h"

#include <bit>

#include "codec/entropy/coef_contexts.h"
#include "codec/entropy/range_decoder.h"
#include "codec/error.h"

namespace pupwave {
namespace {

// `n` (0..32) raw bits, the high chunk first. Inline throughout: a call taking the decoder's
// address would keep its state in memory instead of registers.
inline std::uint64_t get_raw(RangeDecoder& dec, int n) {
  if (n > kCoefRawChunk) {
    const std::uint64_t high = dec.decode_raw(n - kCoefRawChunk);
    return (high << kCoefRawChunk) | dec.decode_raw(kCoefRawChunk);
  }
  return n > 0 ? dec.decode_raw(n) : 0;
}

// Inverse of put_index (coef_encoder.cpp); the index is clamped below 2^bits (corrupt input only).
std::int32_t get_index(RangeDecoder& dec, CoefModels& m, int ctx, std::size_t sign_ctx, std::uint64_t limit,
                       std::uint32_t& q) {
  const int k = coef_rice_k(ctx);
  auto& unary = m.unary[std::size_t(ctx)];
  std::uint64_t h = 0;
  while (h < kCoefEscape && dec.decode(unary[std::min<std::size_t>(h, kCoefUnaryModels - 1)]) != 0) ++h;
  if (h == kCoefEscape) {
    const int n = int(dec.decode_raw(5));  // at most 31 bits: bounded
    h += get_raw(dec, n);
  }
  const int modelled = std::min(k, kCoefModelledLow);
  auto& low = m.low[std::size_t(ctx)];
  std::size_t node = 1;
  const std::size_t tree = h > 0 ? std::size_t(1) << kCoefModelledLow : 0;
  for (int b = 0; b < modelled; ++b) node = 2 * node + std::size_t(dec.decode(low[tree + node]));
  const std::uint64_t top = (node - (std::size_t(1) << modelled)) | (h << modelled);  // q >> rest_bits
  const int rest_bits = k - modelled;
  const std::uint64_t rest = get_raw(dec, rest_bits);
  const std::uint64_t value = (top << rest_bits) | rest;
  const bool negative = value != 0 && dec.decode(m.sign[sign_ctx + (value > 1 ? kCoefSignContexts : 0)]) != 0;
  q = std::uint32_t(std::min(value, limit));
  return negative ? -std::int32_t(q) : std::int32_t(q);
}

}  // namespace

void decode_coefficients(std::span<const std::uint8_t> codeword, int bits, const Extent& size,
                         std::span<std::int32_t> out) {
  require_stream(bits >= 1 && bits <= kCoefMaxBits, "coefficient coder: index bit width out of range");
  require_stream(out.size() == size[0] * size[1] * size[2], "coefficient coder: block size");
  const std::uint64_t limit = (std::uint64_t(1) << bits) - 1;
  RangeDecoder dec(codeword);
  CoefModels models;
  CoefPlane plane(size);
  std::size_t i = 0;
  for (std::size_t z = 0; z < size[2]; ++z)
    for (std::size_t y = 0; y < size[1]; ++y) {
      std::size_t p = plane.at(0, y, z);
      for (std::size_t x = 0; x < size[0]; ++x, ++i, ++p) {
        std::uint32_t q = 0;
        const std::int32_t v = get_index(dec, models, plane.context(p), plane.sign_context(p), limit, q);
        out[i] = v;
        plane.set(p, q);
        plane.set_sign(p, v == 0 ? 0 : v < 0 ? -1 : 1);
      }
    }
}

}  // namespace pupwave
