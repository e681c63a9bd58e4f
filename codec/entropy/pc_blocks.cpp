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
#include "codec/entropy/coef_index.h"
#include "codec/entropy/range_decoder.h"
#include "codec/entropy/range_encoder.h"
#include "codec/error.h"

namespace pupwave {

PcContext::PcContext(std::size_t w, std::size_t h, const LcParent& parent, const PcLuma& luma,
                     int parent_weight, int scale)
    : nx_(w + 2),
      a_((h + 1) * nx_, 0u),
      sg_((h + 1) * nx_, 0),
      parent_(parent),
      luma_(luma),
      in_weight_(parent.origin ? 6 * std::uint64_t(scale) : 3),
      parent_weight_(3 * std::uint64_t(parent_weight)) {
  if (!parent_.origin) return;
  // The parent of child c is c / 2 (clamped); its neighbour towards c is one further on c's side.
  const auto own_and_side = [](std::size_t c, std::size_t extent) {
    const std::size_t p = std::min(c >> 1, extent - 1);
    return std::pair{p, (c & 1u) ? std::min(p + 1, extent - 1) : (p > 0 ? p - 1 : 0)};
  };
  parent_rows_.resize(2 * h);
  for (std::size_t y = 0; y < h; ++y) {
    const auto [py, ny] = own_and_side(parent_.y0 + y, parent_.height);
    parent_rows_[2 * y] = parent_.origin + py * parent_.stride;
    parent_rows_[2 * y + 1] = parent_.origin + ny * parent_.stride;
  }
  parent_cols_.resize(2 * w);
  for (std::size_t x = 0; x < w; ++x) {
    const auto [px, nx] = own_and_side(parent_.x0 + x, parent_.width);
    parent_cols_[2 * x] = px;
    parent_cols_[2 * x + 1] = nx;
  }
}

std::int32_t pc_rdoq_index(PcModels& m, const PcCtx& ctx, float u, std::int32_t v, double lambda,
                           double delta) {
  if (v == 0) return 0;
  const bool negative = v < 0;
  const double x = std::fabs(double(u));
  const auto nearest = std::uint32_t(negative ? -std::int64_t(v) : v);
  double best = 0.0;
  std::uint32_t pick = nearest;
  for (std::uint32_t c : {nearest, nearest - 1, 0u}) {
    const double d = x - (c == 0 ? 0.0 : double(c) + delta);
    const double j = d * d + lambda * pc_index_bits<false>(m, ctx, c, negative);
    if (c == nearest || j < best) {
      best = j;
      pick = c;
    }
  }
  return negative ? -std::int32_t(pick) : std::int32_t(pick);
}

std::pair<std::vector<std::uint8_t>, std::uint32_t> pc_encode_indices(std::vector<std::int32_t>& q,
                                                                      std::size_t width, std::size_t height,
                                                                      PcContext ctx, const PcRdoq* rdoq,
                                                                      PcModels* given) {
  RangeEncoder enc;
  std::unique_ptr<PcModels> fresh;
  PcModels* models = given ? given : (fresh = std::make_unique<PcModels>()).get();
  const std::uint32_t largest =
      pc_visit(width, height, ctx, [&](std::size_t x, std::size_t y, const PcCtx& c) {
        std::int32_t& v = q[y * width + x];
        if (rdoq)
          v = pc_rdoq_index(*models, c, rdoq->coefficients[y * width + x], v, rdoq->lambda, rdoq->delta);
        put_pc_index(enc, *models, c, std::uint32_t(v < 0 ? -std::int64_t(v) : v), v < 0);
        return v;
      });
  return {enc.finish(), largest};
}

std::uint32_t pc_decode_indices(std::span<const std::uint8_t> codeword, std::uint64_t limit,
                                std::size_t width, std::size_t height, PcContext ctx, std::int32_t* out,
                                std::size_t stride, PcModels* given) {
  RangeDecoder dec(codeword);
  std::unique_ptr<PcModels> fresh;
  PcModels* models = given ? given : (fresh = std::make_unique<PcModels>()).get();
  return pc_visit(width, height, ctx, [&](std::size_t x, std::size_t y, const PcCtx& c) {
    bool negative = false;
    const std::uint32_t a = get_pc_index(dec, *models, c, limit, negative);
    return out[y * stride + x] = negative ? -std::int32_t(a) : std::int32_t(a);
  });
}

CoefCodeword pc_encode_block(std::vector<std::int32_t>& q, std::size_t width, std::size_t height,
                             const LcParent& parent, const PcRdoq* rdoq, const PcLuma& luma,
                             const PcModels* start, PcModels* end) {
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
  auto models = std::make_unique<PcModels>(start ? *start : PcModels{});
  if (end) *end = *models;  // no codeword: the models stay as they start
  if (all == 0) return out;
  auto [bytes, largest] =
      pc_encode_indices(q, width, height, PcContext(width, height, parent, luma), rdoq, models.get());
  out.bits = int(std::bit_width(largest));  // RDOQ may have lowered it: the decoder checks this one
  if (out.bits == 0) return out;            // RDOQ zeroed everything: no codeword
  if (end) *end = *models;
  out.bytes = std::move(bytes);
  if (out.bytes.empty()) out.bytes.push_back(0);  // a codeword is never empty (the index says so)
  return out;
}

void pc_decode_block(std::span<const std::uint8_t> codeword, int bits, std::size_t width, std::size_t height,
                     const LcParent& parent, std::int32_t* out, std::size_t stride, const PcLuma& luma,
                     const PcModels* start, PcModels* end) {
  require_stream(bits >= 1 && bits <= kCoefMaxBits && !codeword.empty(), "pc code-block: index bit width");
  const std::uint64_t limit = (std::uint64_t(1) << bits) - 1;
  auto models = std::make_unique<PcModels>(start ? *start : PcModels{});
  const std::uint32_t largest = pc_decode_indices(
      codeword, limit, width, height, PcContext(width, height, parent, luma), out, stride, models.get());
  if (end) *end = *models;
  require_stream(int(std::bit_width(largest)) == bits, "pc code-block: largest index differs from the index");
}

}  // namespace pupwave
