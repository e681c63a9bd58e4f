#include "codec/entropy/pc_blocks.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <tuple>
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
    : parent_(parent),
      luma_(luma),
      in_weight_(parent.origin ? 6 * std::uint64_t(scale) : 3),
      parent_weight_(3 * std::uint64_t(parent_weight)) {
  if (!parent_.origin) return;
  // The parent of child c is c / 2 (clamped); its neighbour towards c is one further on c's side.
  const auto own_and_side = [](std::size_t c, std::size_t extent) {
    const std::size_t p = std::min(c >> 1, extent - 1);
    return std::pair{p, (c & 1u) ? std::min(p + 1, extent - 1) : (p > 0 ? p - 1 : 0)};
  };
  if (w == 0 || h == 0) return;
  parent_rows_.resize(2 * h);
  for (std::size_t y = 0; y < h; ++y)
    std::tie(parent_rows_[2 * y], parent_rows_[2 * y + 1]) = own_and_side(parent_.y0 + y, parent_.height);
  parent_cols_.resize(2 * w);
  for (std::size_t x = 0; x < w; ++x)
    std::tie(parent_cols_[2 * x], parent_cols_[2 * x + 1]) = own_and_side(parent_.x0 + x, parent_.width);
  // The window of parent rows and columns read, copied as magnitudes and signs.
  const auto [row0, row1] = std::minmax_element(parent_rows_.begin(), parent_rows_.end());
  const auto [col0, col1] = std::minmax_element(parent_cols_.begin(), parent_cols_.end());
  const std::size_t y0 = *row0, x0 = *col0, pw = *col1 - x0 + 1, ph = *row1 - y0 + 1;
  pmag_.resize(pw * ph);
  psign_.resize(pw * ph);
  for (std::size_t r = 0; r < ph; ++r) {
    const std::int32_t* from = parent_.origin + (y0 + r) * parent_.stride + x0;
    for (std::size_t c = 0; c < pw; ++c) {
      pmag_[r * pw + c] = std::uint32_t(magnitude(from[c]));
      psign_[r * pw + c] = std::int8_t(sign_of(from[c]));
    }
  }
  for (std::size_t& r : parent_rows_) r = (r - y0) * pw;
  for (std::size_t& c : parent_cols_) c -= x0;
}

std::int32_t pc_rdoq_index(PcModels& m, const PcCtx& ctx, float u, std::int32_t v, double lambda,
                           double delta, double neighbour_bits) {
  if (v == 0) return 0;
  const bool negative = v < 0;
  const double x = std::fabs(double(u));
  const auto nearest = std::uint32_t(negative ? -std::int64_t(v) : v);
  const auto error = [&](std::uint32_t c) {
    const double d = x - (c == 0 ? 0.0 : double(c) + delta);
    return d * d;
  };
  const auto extra = [&](std::uint32_t c) { return c == 0 ? 0.0 : neighbour_bits; };
  double best = error(nearest) + lambda * (pc_index_bits<false>(m, ctx, nearest, negative) + extra(nearest));
  const double bound = best;  // a candidate whose cost without its own bits reaches this cannot win
  std::uint32_t pick = nearest;
  for (std::uint32_t c : {nearest - 1, 0u}) {
    const double e = error(c);
    if (e + lambda * std::min(0.0, extra(c)) >= bound) continue;  // skipped unpriced: same outcome
    const double j = e + lambda * (pc_index_bits<false>(m, ctx, c, negative) + extra(c));
    if (j < best) {
      best = j;
      pick = c;
    }
    if (c == 0) break;  // nearest 1: its n - 1 was 0
  }
  return negative ? -std::int32_t(pick) : std::int32_t(pick);
}

namespace {

// The CfL codes: each zigzagged (0, -1, 1, -2, ...) as an order-0 Exp-Golomb code of equiprobable
// bits (a zero weight costs one bit; the codes sit near 0 for Cb and near -16 for Cr).
constexpr int kCflMaxCode = 32;
constexpr int kCflMaxPrefix = 6;  // zigzag(+-32) + 1 = 65 < 2^7

void put_cfl(RangeEncoder& enc, const PcCfl& cfl) {
  for (int i = 0; i < cfl.count; ++i) {
    const int c = cfl.code[i];
    const std::uint32_t z = std::uint32_t(c > 0 ? 2 * c - 1 : -2 * c) + 1;
    const int n = int(std::bit_width(z)) - 1;
    for (int k = 0; k < n; ++k) enc.encode_equiprobable(0);
    enc.encode_equiprobable(1);
    for (int k = n - 1; k >= 0; --k) enc.encode_equiprobable(int((z >> k) & 1u));
  }
}

void get_cfl(RangeDecoder& dec, PcCfl& cfl) {
  for (int i = 0; i < cfl.count; ++i) {
    int n = 0;
    while (dec.decode_equiprobable() == 0)
      require_stream(++n <= kCflMaxPrefix, "pc code-block: chroma-from-luma code too long");
    std::uint32_t z = 1;
    for (int k = 0; k < n; ++k) z = (z << 1) | std::uint32_t(dec.decode_equiprobable());
    const int zz = int(z - 1);
    const int c = zz & 1 ? (zz + 1) / 2 : -(zz / 2);
    require_stream(c >= -kCflMaxCode && c <= kCflMaxCode,
                   "pc code-block: chroma-from-luma weight out of range");
    cfl.code[i] = c;
  }
}

}  // namespace

double pc_neighbour_bits(const std::vector<std::int32_t>& q, std::size_t width, std::size_t height,
                         std::size_t x, std::size_t y, int cls, const PcRdoq& rdoq) {
  // Zeros among the later neighbours E, S (weight 2: they count twice in the activity), SW and
  // SE (1); beyond the block counts as zero (no neighbour there pays).
  const std::size_t i = y * width + x;
  const bool east = x + 1 < width, west = x > 0;
  int zeros = 2 * (!east || q[i + 1] == 0);
  if (y + 1 < height)
    zeros += 2 * (q[i + width] == 0) + (!west || q[i + width - 1] == 0) + (!east || q[i + width + 1] == 0);
  else
    zeros += 4;
  // (zeros - non-zeros) / 6: +1 when all six weights are on zeros, -1 when none is.
  const double balance = double(zeros - 3) / 3.0;
  return rdoq.neighbour_bits * balance * rdoq.neighbour_fade / (rdoq.neighbour_fade + double(cls));
}

std::pair<std::vector<std::uint8_t>, std::uint32_t> pc_encode_indices(std::vector<std::int32_t>& q,
                                                                      std::size_t width, std::size_t height,
                                                                      PcContext ctx, const PcRdoq* rdoq,
                                                                      const PcCfl* cfl, PcModels* given) {
  RangeEncoder enc;
  if (cfl) put_cfl(enc, *cfl);
  std::unique_ptr<PcModels> fresh;
  PcModels* models = given ? given : (fresh = std::make_unique<PcModels>()).get();
  const std::uint32_t largest =
      pc_visit(width, height, ctx, [&](std::size_t x, std::size_t y, const PcCtx& c) {
        std::int32_t& v = q[y * width + x];
        if (rdoq && v != 0)  // a zero stays zero: no call for the most common index
          v = pc_rdoq_index(*models, c, rdoq->coefficients[y * width + x], v, rdoq->lambda, rdoq->delta,
                            pc_neighbour_bits(q, width, height, x, y, c.cls, *rdoq));
        put_pc_index(enc, *models, c, std::uint32_t(v < 0 ? -std::int64_t(v) : v), v < 0);
        return v;
      });
  return {enc.finish(), largest};
}

std::uint32_t pc_decode_indices(std::span<const std::uint8_t> codeword, std::uint64_t limit,
                                std::size_t width, std::size_t height, PcContext ctx, std::int32_t* out,
                                std::size_t stride, PcCfl* cfl, PcModels* given) {
  RangeDecoder dec(codeword);
  if (cfl) get_cfl(dec, *cfl);
  std::unique_ptr<PcModels> fresh;
  PcModels* models = given ? given : (fresh = std::make_unique<PcModels>()).get();
  return pc_visit(width, height, ctx, [&](std::size_t x, std::size_t y, const PcCtx& c) {
    bool negative = false;
    const std::uint32_t a = get_pc_index(dec, *models, c, limit, negative);
    return out[y * stride + x] = negative ? -std::int32_t(a) : std::int32_t(a);
  });
}

CoefCodeword pc_encode_block(std::vector<std::int32_t>& q, std::size_t width, std::size_t height,
                             const LcParent& parent, const PcRdoq* rdoq, const PcLuma& luma, const PcCfl* cfl,
                             const PcModels* start, PcModels* end) {
  if (cfl)
    for (int i = 0; i < cfl->count; ++i)
      if (std::abs(cfl->code[i]) > kCflMaxCode)
        throw std::invalid_argument("pc_encode_block: chroma-from-luma code beyond [-32, 32]");
  if (q.size() != width * height)
    throw std::invalid_argument("pc_encode_block: index count differs from the size");
  std::uint64_t all = 0;  // the magnitudes or'ed: zero for a block of zeros
  if (rdoq) {
    if (rdoq->coefficients.size() != q.size())
      throw std::invalid_argument("pc_encode_block: coefficient count differs from the size");
    // The nearest reconstruction points floor(|u| - delta + 0.5), 0 below 0: truncation of a
    // non-negative value clamped to the range's end, whose largest index (an integer maximum, so
    // that the loop vectorizes) tells after the loop whether one left the range.
    const double delta = rdoq->delta, limit = double(1u << kCoefMaxBits);
    std::int32_t largest = 0;
    for (std::size_t k = 0; k < q.size(); ++k) {
      const float u = rdoq->coefficients[k];
      const double v = (double(std::fabs(u)) - delta) + 0.5;
      const double y = v > 0.0 ? v : 0.0;  // NaN too
      const auto n = std::int32_t(y < limit ? y : limit);
      largest = n > largest ? n : largest;
      q[k] = u < 0 ? -n : n;
    }
    if (largest >= (1 << kCoefMaxBits)) throw IndexRangeError("index too large for the pc coder");
    all = std::uint64_t(largest);
  } else {
    for (std::int32_t v : q) all |= std::uint64_t(v < 0 ? -std::int64_t(v) : v);
  }
  if (all >= (std::uint64_t(1) << kCoefMaxBits)) throw IndexRangeError("index too large for the pc coder");
  CoefCodeword out;
  auto models = std::make_unique<PcModels>(start ? *start : PcModels{});
  if (end) *end = *models;  // no codeword: the models stay as they start
  if (all == 0) return out;
  auto [bytes, largest] =
      pc_encode_indices(q, width, height, PcContext(width, height, parent, luma), rdoq, cfl, models.get());
  out.bits = int(std::bit_width(largest));  // RDOQ may have lowered it: the decoder checks this one
  if (out.bits == 0) return out;            // RDOQ zeroed everything: no codeword
  if (end) *end = *models;
  out.bytes = std::move(bytes);
  if (out.bytes.empty()) out.bytes.push_back(0);  // a codeword is never empty (the index says so)
  return out;
}

void pc_decode_block(std::span<const std::uint8_t> codeword, int bits, std::size_t width, std::size_t height,
                     const LcParent& parent, std::int32_t* out, std::size_t stride, const PcLuma& luma,
                     PcCfl* cfl, const PcModels* start, PcModels* end) {
  require_stream(bits >= 1 && bits <= kCoefMaxBits && !codeword.empty(), "pc code-block: index bit width");
  const std::uint64_t limit = (std::uint64_t(1) << bits) - 1;
  auto models = std::make_unique<PcModels>(start ? *start : PcModels{});
  const std::uint32_t largest = pc_decode_indices(
      codeword, limit, width, height, PcContext(width, height, parent, luma), out, stride, cfl, models.get());
  if (end) *end = *models;
  require_stream(int(std::bit_width(largest)) == bits, "pc code-block: largest index differs from the index");
}

}  // namespace pupwave
