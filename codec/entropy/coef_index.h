#pragma once
// One quantization index under the coefficient coder's binarisation (coef_contexts.h): unary high
// part with models (escape: Elias-gamma raw), modelled top low bits, raw rest, sign by context.
// Shared by the volume coefficient coder (coef_encoder.cpp, coef_decoder.cpp) and the
// parent-context coder (pc_blocks.cpp). Inline throughout: a call taking the coder's address
// would keep its state in memory instead of registers.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "codec/entropy/coef_contexts.h"
#include "codec/entropy/range_decoder.h"
#include "codec/entropy/range_encoder.h"

namespace pupwave {

// `n` (0..32) raw bits of `v`, the high chunk first (the coder takes at most 16 at once).
inline void put_coef_raw(RangeEncoder& enc, std::uint64_t v, int n) {
  if (n > kCoefRawChunk) {
    enc.encode_raw(std::uint32_t(v >> kCoefRawChunk), n - kCoefRawChunk);
    enc.encode_raw(std::uint32_t(v), kCoefRawChunk);
  } else if (n > 0) {
    enc.encode_raw(std::uint32_t(v), n);
  }
}

inline std::uint64_t get_coef_raw(RangeDecoder& dec, int n) {
  if (n > kCoefRawChunk) {
    const std::uint64_t high = dec.decode_raw(n - kCoefRawChunk);
    return (high << kCoefRawChunk) | dec.decode_raw(kCoefRawChunk);
  }
  return n > 0 ? dec.decode_raw(n) : 0;
}

// code_coef_index's k low bits of q: the top ones with models (a binary tree per high part h
// zero / non-zero), the rest raw. Apart, so that the classes without low bits (the quiet ones,
// where most indices are coded) skip it whole.
template <class Sink, class Low>
inline void code_coef_low_bits(Sink& sink, Low& low, int k, std::uint32_t h, std::uint32_t q) {
  const int modelled = std::min(k, kCoefModelledLow);
  std::size_t node = 1;
  const std::size_t tree = h > 0 ? std::size_t(1) << kCoefModelledLow : 0;
  for (int b = k - 1; b >= k - modelled; --b) {
    const int bit = int((q >> b) & 1u);
    sink.bit(bit, low[tree + node]);
    node = 2 * node + std::size_t(bit);
  }
  const int rest_bits = k - modelled;
  sink.rest(q & ((1u << rest_bits) - 1u), rest_bits);
}

// A sign context given as its index (the volume coder's); pc_index.h overloads it for a context
// whose sign index is only worked out when a non-zero index needs it.
inline std::size_t coef_sign_index(std::size_t sign_ctx) { return sign_ctx; }

// The decisions of index q (sign `negative`, ignored for 0) in activity class `ctx` and sign
// context `sign_ctx` (coef_sign_index), handed to `sink`: bit(b, model) for a modelled bit, escape(e) for the
// Elias-gamma raw tail of a long high part, rest(v, n) for the n raw low bits. One binarisation
// for the coder (CoefIndexWriter) and the rate estimates (CoefIndexCounter).
// Models: CoefModels, or the pc coder's PcModels (pc_index.h), whose bits adapt their own way.
template <class Sink, class Models, class SignCtx>
inline void code_coef_index(Sink& sink, Models& m, int ctx, const SignCtx& sign_ctx, std::uint32_t q,
                            bool negative) {
  const int k = coef_rice_k(ctx);
  const std::uint32_t h = q >> k;
  auto& unary = m.unary[std::size_t(ctx)];
  const std::uint32_t ones = std::min<std::uint32_t>(h, kCoefEscape);
  for (std::uint32_t j = 0; j < ones; ++j) sink.bit(1, unary[std::min<std::size_t>(j, kCoefUnaryModels - 1)]);
  if (h < kCoefEscape)
    sink.bit(0, unary[std::min<std::size_t>(h, kCoefUnaryModels - 1)]);
  else
    sink.escape(h - kCoefEscape);
  if (k > 0) code_coef_low_bits(sink, m.low[std::size_t(ctx)], k, h, q);
  if (q != 0)
    sink.bit(negative ? 1 : 0, m.sign[coef_sign_index(sign_ctx) + (q > 1 ? Models::kSignContexts : 0)]);
}

// The range coder as code_coef_index's sink.
struct CoefIndexWriter {
  RangeEncoder& enc;
  void bit(int b, BitModel& model) { enc.encode(b, model); }
  void escape(std::uint32_t e) {
    const int n = int(std::bit_width(e));
    enc.encode_raw(std::uint32_t(n), 5);
    put_coef_raw(enc, e, n);
  }
  void rest(std::uint32_t v, int n) { put_coef_raw(enc, v, n); }
};

// Codes index q with the range coder.
inline void put_coef_index(RangeEncoder& enc, CoefModels& m, int ctx, std::size_t sign_ctx, std::uint32_t q,
                           bool negative) {
  CoefIndexWriter writer{enc};
  code_coef_index(writer, m, ctx, sign_ctx, q, negative);
}

// One modelled bit decoded (pc_index.h overloads it for its models).
inline int decode_model_bit(RangeDecoder& dec, BitModel& model) { return dec.decode(model); }

// Inverse of put_coef_index: the magnitude, clamped to `limit` (corrupt input only), and its sign.
template <class Models, class SignCtx>
inline std::uint32_t get_coef_index(RangeDecoder& dec, Models& m, int ctx, const SignCtx& sign_ctx,
                                    std::uint64_t limit, bool& negative) {
  const int k = coef_rice_k(ctx);
  auto& unary = m.unary[std::size_t(ctx)];
  std::uint64_t h = 0;
  while (h < kCoefEscape && decode_model_bit(dec, unary[std::min<std::size_t>(h, kCoefUnaryModels - 1)]) != 0)
    ++h;
  if (h == kCoefEscape) {
    const int n = int(dec.decode_raw(5));  // at most 31 bits: bounded
    h += get_coef_raw(dec, n);
  }
  const int modelled = std::min(k, kCoefModelledLow);
  auto& low = m.low[std::size_t(ctx)];
  std::size_t node = 1;
  const std::size_t tree = h > 0 ? std::size_t(1) << kCoefModelledLow : 0;
  for (int b = 0; b < modelled; ++b) node = 2 * node + std::size_t(decode_model_bit(dec, low[tree + node]));
  const std::uint64_t top = (node - (std::size_t(1) << modelled)) | (h << modelled);  // q >> rest_bits
  const int rest_bits = k - modelled;
  const std::uint64_t value = (top << rest_bits) | get_coef_raw(dec, rest_bits);
  negative =
      value != 0 &&
      decode_model_bit(dec, m.sign[coef_sign_index(sign_ctx) + (value > 1 ? Models::kSignContexts : 0)]) != 0;
  return std::uint32_t(std::min(value, limit));
}

// Bits model m would spend on `bit` now; Update: adapting it as the coder would.
template <bool Update>
double coef_model_bits(BitModel& m, int bit) {
  const std::uint32_t p = bit ? kProbabilityOne - m.p0 : m.p0;
  if constexpr (Update) m.update(bit);
  return -std::log2(double(p) / double(kProbabilityOne));
}

// Counts the bits code_coef_index's decisions would take (raw bits whole); Update: adapting the
// models as the coder would.
template <bool Update>
struct CoefIndexCounter {
  double bits = 0.0;
  void bit(int b, BitModel& model) { bits += coef_model_bits<Update>(model, b); }
  void escape(std::uint32_t e) { bits += 5.0 + double(std::bit_width(e)); }
  void rest(std::uint32_t, int n) { bits += double(n); }
};

// put_coef_index's code length in bits, for rate estimates and RDOQ.
template <bool Update>
double coef_index_bits(CoefModels& m, int ctx, std::size_t sign_ctx, std::uint32_t q, bool negative) {
  CoefIndexCounter<Update> counter;
  code_coef_index(counter, m, ctx, sign_ctx, q, negative);
  return counter.bits;
}

}  // namespace pupwave
