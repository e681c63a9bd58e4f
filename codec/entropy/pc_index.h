#pragma once
// The parent-context coder's binarisation of one quantization index (entropy coder 4): the
// volume coefficient coder's (coef_index.h: Rice class, unary high part with kCoefUnaryModels
// models a class, escape, kCoefModelledLow modelled top low bits, raw rest, sign by context)
// with pc's own models (pc_bit.h) and sign contexts, so that the volume coder's streams stay
// as they are.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "codec/entropy/coef_contexts.h"
#include "codec/entropy/coef_index.h"
#include "codec/entropy/pc_bit.h"
#include "codec/entropy/range_decoder.h"
#include "codec/entropy/range_encoder.h"

namespace pupwave {

// Sign contexts: the signs of W, N, the parent and the luma parent (Cb for Cr) (each negative,
// zero or positive; zero where there is none).
inline constexpr int kPcSignContexts = 81;

// A coefficient's contexts: activity class (coef_rice_k's class) and sign context (sign()). The
// sign context is kept in parts and worked out only for a non-zero index, so that the zero ones,
// most of them, never load the parent's and the luma parent's signs.
struct PcCtx {
  int cls = 0;
  int sign_w = 0, sign_n = 0;           // the signs of W and N
  const std::int8_t* parent = nullptr;  // the parent's sign; null: none (0)
  const std::int32_t* luma = nullptr;   // the luma parent's index (Cb's for Cr); null: none
  // 27 (sign of the luma parent + 1) + 9 (W's + 1) + 3 (N's + 1) + (the parent's + 1), in [0, 81).
  std::size_t sign() const {
    const int ps = parent ? *parent : 0;
    const int ls = luma ? int(*luma > 0) - int(*luma < 0) : 0;
    return std::size_t(27 * (ls + 1) + 9 * (sign_w + 1) + 3 * (sign_n + 1) + ps + 1);
  }
};
inline std::size_t coef_sign_index(const PcCtx& c) { return c.sign(); }

// Adaptive models of one pc block (started per block, from its band class's trained states in the
// coder, pc_priors.h: each block's codeword decodes alone).
struct PcModels {
  std::array<std::array<PcBit, kCoefUnaryModels>, kCoefClasses> unary{};
  std::array<std::array<PcBit, 2 << kCoefModelledLow>, kCoefClasses> low{};  // as CoefModels::low
  std::array<PcBit, 2 * kPcSignContexts> sign{};                             // x2: index 1 / larger
  static constexpr int kSignContexts = kPcSignContexts;

  // Class 0's unary models adapt faster (pc_bit.h).
  static constexpr int kSilentShift = 5;
  static_assert(kSilentShift >= PcBit::kMinShift && BitModel::kMaxShift >= PcBit::kMinShift);
  PcModels() {
    for (PcBit& b : unary[0]) b.max_shift = kSilentShift;
  }
};

// code_coef_index with pc's models: the decisions of q handed to `sink`.
template <class Sink>
inline void code_pc_index(Sink& sink, PcModels& m, const PcCtx& c, std::uint32_t q, bool negative) {
  code_coef_index(sink, m, c.cls, c, q, negative);
}

// The range coder as code_pc_index's sink.
struct PcIndexWriter {
  RangeEncoder& enc;
  void bit(int b, PcBit& model) {
    enc.encode_probability(b, model.p0);
    model.update(b);
  }
  void escape(std::uint32_t e) {
    const int n = int(std::bit_width(e));
    enc.encode_raw(std::uint32_t(n), 5);
    put_coef_raw(enc, e, n);
  }
  void rest(std::uint32_t v, int n) { put_coef_raw(enc, v, n); }
};

inline void put_pc_index(RangeEncoder& enc, PcModels& m, const PcCtx& c, std::uint32_t q, bool negative) {
  PcIndexWriter writer{enc};
  code_pc_index(writer, m, c, q, negative);
}

// get_coef_index's bit decoder for pc's models.
inline int decode_model_bit(RangeDecoder& dec, PcBit& model) {
  const int b = dec.decode_probability(model.p0);
  model.update(b);
  return b;
}

// Inverse of put_pc_index: the magnitude, clamped to `limit` (corrupt input only), and its sign.
inline std::uint32_t get_pc_index(RangeDecoder& dec, PcModels& m, const PcCtx& c, std::uint64_t limit,
                                  bool& negative) {
  return get_coef_index(dec, m, c.cls, c, limit, negative);
}

// -log2(p / 2^15) for every 15-bit probability p: the counter's cost of a decision, looked up
// rather than computed because RDOQ prices three candidates per index (log2 would be a tenth of a
// pc encode). Float holds the cost to 2^-24 relative, far below any difference RDOQ decides on.
inline const std::array<float, kProbabilityOne + 1> kPcBitCost = [] {
  std::array<float, kProbabilityOne + 1> cost{};
  cost[0] = 64.0f;  // never looked up: models keep p inside [kMinP, 2^15 - kMinP]
  for (std::uint32_t p = 1; p <= kProbabilityOne; ++p)
    cost[p] = float(-std::log2(double(p) / double(kProbabilityOne)));
  return cost;
}();

// Counts the bits code_pc_index's decisions would take (raw bits whole); Update: adapting the
// models as the coder would.
template <bool Update>
struct PcIndexCounter {
  double bits = 0.0;
  void bit(int b, PcBit& model) {
    bits += double(kPcBitCost[b ? kProbabilityOne - model.p0 : model.p0]);
    if constexpr (Update) model.update(b);
  }
  void escape(std::uint32_t e) { bits += 5.0 + double(std::bit_width(e)); }
  void rest(std::uint32_t, int n) { bits += double(n); }
};

// put_pc_index's code length in bits, for RDOQ and the bench estimate.
template <bool Update>
double pc_index_bits(PcModels& m, const PcCtx& c, std::uint32_t q, bool negative) {
  PcIndexCounter<Update> counter;
  code_pc_index(counter, m, c, q, negative);
  return counter.bits;
}

}  // namespace pupwave
