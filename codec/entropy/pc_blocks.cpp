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

namespace {

std::uint64_t magnitude(std::int32_t v) { return std::uint64_t(v < 0 ? -std::int64_t(v) : v); }
int sign_of(std::int32_t v) { return v == 0 ? 0 : (v < 0 ? -1 : 1); }

}  // namespace

PcCtx PcContext::at(std::size_t x, std::size_t y) const {
  const std::size_t p = (y + 1) * nx_ + x + 1;
  const std::uint64_t in = 2 * (std::uint64_t(a_[p - 1]) + a_[p - nx_]) + a_[p - 1 - nx_] + a_[p + 1 - nx_];
  std::uint64_t s3 = 3 * in;  // three times the activity (the parent's neighbours count a third)
  int ps = 0, ls = 0;
  if (parent_.origin) {
    s3 *= 2 * std::uint64_t(scale_);
    const std::size_t cx = parent_.x0 + x, cy = parent_.y0 + y;
    const std::size_t px = std::min(cx >> 1, parent_.width - 1), py = std::min(cy >> 1, parent_.height - 1);
    // The parent's neighbour on the child's side in each direction (clamped to the band).
    const std::size_t nx = (cx & 1u) ? std::min(px + 1, parent_.width - 1) : (px > 0 ? px - 1 : 0);
    const std::size_t ny = (cy & 1u) ? std::min(py + 1, parent_.height - 1) : (py > 0 ? py - 1 : 0);
    const std::int32_t* row = parent_.origin + py * parent_.stride;
    const std::int32_t* side = parent_.origin + ny * parent_.stride;
    const std::int32_t c = row[px];
    s3 += 3 * std::uint64_t(weight_) * magnitude(c) + magnitude(row[nx]) + magnitude(side[px]) + magnitude(side[nx]);
    ps = sign_of(c);
  }
  if (luma_.origin) {
    const std::int32_t l = luma_.origin[y * luma_.stride + x];
    s3 += 3 * magnitude(l);
    ls = sign_of(l);
  }
  const std::uint64_t s = (2 * s3 + 3) / 6;  // s3 / 3 rounded
  const int w = int(std::bit_width(s));
  const int cls = std::min(s < 2 ? int(s) : 2 * w - 2 + int((s >> (w - 2)) & 1u), kCoefClasses - 1);
  return {cls, std::size_t(27 * (ls + 1) + 9 * (sg_[p - 1] + 1) + 3 * (sg_[p - nx_] + 1) + (ps + 1))};
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
                                                                      PcContext ctx, const PcRdoq* rdoq) {
  RangeEncoder enc;
  auto models = std::make_unique<PcModels>();
  const std::uint32_t largest = pc_visit(width, height, ctx, [&](std::size_t x, std::size_t y, const PcCtx& c) {
        std::int32_t& v = q[y * width + x];
        if (rdoq) v = pc_rdoq_index(*models, c, rdoq->coefficients[y * width + x], v, rdoq->lambda, rdoq->delta);
        put_pc_index(enc, *models, c, std::uint32_t(v < 0 ? -std::int64_t(v) : v), v < 0);
        return v;
      });
  return {enc.finish(), largest};
}

std::uint32_t pc_decode_indices(std::span<const std::uint8_t> codeword, std::uint64_t limit,
                                std::size_t width, std::size_t height, PcContext ctx, std::int32_t* out,
                                std::size_t stride) {
  RangeDecoder dec(codeword);
  auto models = std::make_unique<PcModels>();
  return pc_visit(width, height, ctx, [&](std::size_t x, std::size_t y, const PcCtx& c) {
    bool negative = false;
    const std::uint32_t a = get_pc_index(dec, *models, c, limit, negative);
    return out[y * stride + x] = negative ? -std::int32_t(a) : std::int32_t(a);
  });
}

CoefCodeword pc_encode_block(std::vector<std::int32_t>& q, std::size_t width, std::size_t height,
                             const LcParent& parent, const PcRdoq* rdoq, const PcLuma& luma) {
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
  auto [bytes, largest] = pc_encode_indices(q, width, height, PcContext(width, height, parent, luma), rdoq);
  out.bits = int(std::bit_width(largest));  // RDOQ may have lowered it: the decoder checks this one
  if (out.bits == 0) return out;            // RDOQ zeroed everything: no codeword
  out.bytes = std::move(bytes);
  if (out.bytes.empty()) out.bytes.push_back(0);  // a codeword is never empty (the index says so)
  return out;
}

void pc_decode_block(std::span<const std::uint8_t> codeword, int bits, std::size_t width, std::size_t height,
                     const LcParent& parent, std::int32_t* out, std::size_t stride, const PcLuma& luma) {
  require_stream(bits >= 1 && bits <= kCoefMaxBits && !codeword.empty(), "pc code-block: index bit width");
  const std::uint64_t limit = (std::uint64_t(1) << bits) - 1;
  const std::uint32_t largest =
      pc_decode_indices(codeword, limit, width, height, PcContext(width, height, parent, luma), out, stride);
  require_stream(int(std::bit_width(largest)) == bits, "pc code-block: largest index differs from the index");
}

}  // namespace pupwave
