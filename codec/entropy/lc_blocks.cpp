#include "codec/entropy/lc_blocks.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdlib>
#include <memory>

#include "codec/entropy/block_contexts.h"
#include "codec/entropy/block_encoder.h"
#include "codec/entropy/range_decoder.h"
#include "codec/entropy/range_encoder.h"
#include "codec/error.h"

namespace pupwave {
namespace {

// Bit lengths 1 .. kMaxBitPlanes index the length and mantissa models.
constexpr int kLengths = kMaxBitPlanes + 1;
// Magnitudes are capped here in the context planes, so the weighted sums fit 32 bits.
constexpr std::uint32_t kMagnitudeCap = std::uint32_t(1) << 24;
// Decoded values beyond this are corrupt (the encoder's never are).
constexpr std::int64_t kValueLimit = std::int64_t(1) << 30;
// Padding of the context planes: two columns each side, two rows above.
constexpr std::size_t kPad = 2;

using Model = LcModel;  // lc_blocks.h: shared with the bench estimate

struct Models {
  std::array<Model, kLcActivityContexts> zero{};
  std::array<std::array<Model, kLengths>, kLcActivityContexts> length{};  // "bit length > n"
  std::array<std::array<Model, kLengths>, kLcActivityContexts> first{};   // bit below the leading one
  std::array<std::array<std::array<Model, 2>, kLengths>, kLcActivityContexts>
      second{};                  // the next, by the first
  std::array<Model, 27> sign{};  // by the signs of W and N (and of the guide's residual)
};

struct EncoderIo {
  static constexpr bool kEncoding = true;
  static constexpr bool kDry = false;
  RangeEncoder coder;
  int bit(int b, Model& m) {
    coder.encode_probability(b, m.p0());
    m.update(b);
    return b;
  }
  std::uint32_t raw(std::uint32_t v, int n) {
    for (int left = n; left > 0;) {
      const int k = std::min(left, 16);
      left -= k;
      coder.encode_raw(v >> left, k);
    }
    return v;
  }
};

struct DecoderIo {
  static constexpr bool kEncoding = false;
  static constexpr bool kDry = false;
  RangeDecoder coder;
  int bit(int, Model& m) {
    const int b = coder.decode_probability(m.p0());
    m.update(b);
    return b;
  }
  std::uint32_t raw(std::uint32_t, int n) {
    std::uint32_t v = 0;
    for (int left = n; left > 0;) {
      const int k = std::min(left, 16);
      left -= k;
      v = (v << k) | coder.decode_raw(k);
    }
    return v;
  }
};

// One magnitude (the encoder's `mag`, or decoded) in activity context ctx; lengths never
// exceed `planes`, so the decision at planes is implied.
template <class Io>
std::uint32_t code_magnitude(Io& io, Models& m, int ctx, std::uint32_t mag, int planes) {
  if (!io.bit(mag != 0, m.zero[std::size_t(ctx)])) return 0;
  const int n = Io::kEncoding ? int(std::bit_width(mag)) : 0;
  int len = 1;
  auto& length = m.length[std::size_t(ctx)];
  while (len < planes && io.bit(len < n, length[std::size_t(len)])) ++len;
  std::uint32_t v = 1;
  if (len >= 2)
    v = 2 * v +
        std::uint32_t(io.bit(int((mag >> (len - 2)) & 1u), m.first[std::size_t(ctx)][std::size_t(len)]));
  if (len >= 3)
    v = 2 * v + std::uint32_t(io.bit(int((mag >> (len - 3)) & 1u),
                                     m.second[std::size_t(ctx)][std::size_t(len)][v & 1u]));
  if (len >= 4) v = (v << (len - 3)) | io.raw(mag & ((1u << (len - 3)) - 1u), len - 3);
  return v;
}

inline int sign_of(std::int8_t s) { return s + 1; }  // -1, 0, 1 -> 0, 1, 2

// What a block's coder keeps of the samples already coded: magnitudes and signs on a grid padded
// by kPad on the left, right and top (so neighbours need no edge tests), and fresh models.
struct CausalState {
  std::size_t pw;
  std::ptrdiff_t sp;  // pw, signed: a[-pw] with a size_t pw is pointer overflow
  std::vector<std::uint32_t> mag;
  std::vector<std::int8_t> sgn;
  std::unique_ptr<Models> models = std::make_unique<Models>();
  CausalState(std::size_t w, std::size_t h)
      : pw(w + 2 * kPad), sp(std::ptrdiff_t(pw)), mag((h + kPad) * pw, 0u), sgn((h + kPad) * pw, 0) {}
};

// Codes the symbols of a block (the encoder's `symbols`, or decoded into them; row y at
// symbols + y * stride) and returns the largest magnitude.
template <class Io>
std::uint32_t code_symbols(Io& io, std::int32_t* symbols, std::size_t stride, std::size_t w, std::size_t h,
                           const LcParent& parent, int planes) {
  CausalState state(w, h);
  auto& [pw, sp, mag, sgn, models] = state;
  Models& m = *models;
  std::uint32_t largest = 0;
  for (std::size_t y = 0; y < h; ++y) {
    const std::int32_t* prow = nullptr;
    if (parent.origin)
      prow = parent.origin + std::min((parent.y0 + y) >> 1, parent.height - 1) * parent.stride;
    std::int32_t* row = symbols + y * stride;
    for (std::size_t x = 0; x < w; ++x) {
      const std::size_t i = (y + kPad) * pw + x + kPad;
      const std::uint32_t* a = mag.data() + i;
      std::uint32_t s = 4 * (a[-1] + a[-sp]) + 2 * (a[-sp - 1] + a[-sp + 1]) + a[-2] + a[-2 * sp];
      if (prow) {
        const std::int32_t p = prow[std::min((parent.x0 + x) >> 1, parent.width - 1)];
        s += 2 * std::min(std::uint32_t(p < 0 ? -std::int64_t(p) : p), kMagnitudeCap);
      }
      const int ctx = lc_activity_context(s);
      const std::int32_t value = Io::kEncoding ? row[x] : 0;
      const auto magnitude = std::uint32_t(value < 0 ? -std::int64_t(value) : value);
      const std::uint32_t v = code_magnitude(io, m, ctx, magnitude, planes);
      int negative = 0;
      if (v != 0) {
        const int sc = 3 * sign_of(sgn[i - 1]) + sign_of(sgn[i - pw]);
        negative = io.bit(value < 0, m.sign[std::size_t(sc)]);
      }
      if constexpr (!Io::kEncoding) row[x] = negative ? -std::int32_t(v) : std::int32_t(v);
      largest = std::max(largest, v);
      mag[i] = std::min(v, kMagnitudeCap);
      sgn[i] = std::int8_t(v == 0 ? 0 : (negative ? -1 : 1));
    }
  }
  return largest;
}

// Predictors of the coarse band: weighted with light corrections, MED, their 3:1 mix, weighted
// with strong corrections (JPEG XL's default strengths; light ones suit most photographs).
constexpr int kPredictors = 4;
// Fixed-point fraction of the predictions (1/8 sample units).
constexpr int kFrac = 3;
// Prediction errors are capped here in the error rows (so weighted sums fit 64 bits).
constexpr std::int64_t kErrorCap = std::int64_t(1) << 26;

// The median edge detector of LOCO-I.
inline std::int64_t med(std::int64_t w, std::int64_t n, std::int64_t nw) {
  if (nw >= std::max(w, n)) return std::min(w, n);
  if (nw <= std::min(w, n)) return std::max(w, n);
  return w + n - nw;
}

// The self-correcting weighted predictor (the idea of JPEG XL's modular mode): four simple
// sub-predictors, each weighted by the inverse of its recent absolute error at the causal
// neighbours, three of them corrected by the signed errors the final prediction made there.
class WeightedPredictor {
 public:
  static constexpr int kSubs = 4;
  WeightedPredictor(std::size_t w, int mode) : w_(w), pred_(mode) {
    for (auto& r : sub_) r.assign(2 * (w + 2), 0);
    true_.assign(2 * (w + 2), 0);
  }

  // Neighbour samples of (x, y), edges replaced by the nearest causal sample.
  struct Neighbours {
    std::int64_t w, n, nw, ne, nn, ww;
  };

  // Prediction at column x of row y (1/8 units).
  std::int64_t predict(const Neighbours& s, std::size_t x, std::size_t y) {
    if (pred_ == 1) return med(s.w, s.n, s.nw) << kFrac;  // MED needs no error rows
    const std::int64_t* up = true_.data() + ((y + 1) & 1) * (w_ + 2);
    const std::int64_t* cur = true_.data() + (y & 1) * (w_ + 2);
    const std::int64_t te_w = cur[x], te_n = up[x + 1], te_nw = up[x], te_ne = up[x + 2];
    sub_value_[0] = (s.w + s.ne - s.n) << kFrac;
    const bool strong = pred_ == 3;
    sub_value_[1] = (s.n << kFrac) - ((te_w + te_n + te_ne) * (strong ? 16 : 4) >> 5);
    sub_value_[2] = (s.w << kFrac) - ((te_w + te_n + te_nw) * (strong ? 10 : 2) >> 5);
    sub_value_[3] = (s.n << kFrac) - ((te_nw + te_n + te_ne) * (strong ? 7 : 1) >> 5);
    std::int64_t total = 0, weights = 0;
    for (int i = 0; i < kSubs; ++i) {
      const std::int64_t* su = sub_[std::size_t(i)].data() + ((y + 1) & 1) * (w_ + 2);
      const std::int64_t* sc = sub_[std::size_t(i)].data() + (y & 1) * (w_ + 2);
      const std::int64_t e = su[x + 1] + sc[x] + su[x] + su[x + 2];
      const auto wt = std::int64_t((std::uint32_t(1) << 24) / std::uint32_t(e + 16) + 1);  // e < 2^28
      total += wt * sub_value_[std::size_t(i)];
      weights += wt;
    }
    std::int64_t p = total >= 0 ? (total + weights / 2) / weights : -((-total + weights / 2) / weights);
    if (pred_ == 2) p = (3 * p + (med(s.w, s.n, s.nw) << kFrac)) / 4;
    {  // no extrapolation beyond the neighbours (clamping gained 0.3-0.5%)
      const std::int64_t lo = std::min({s.w, s.n, s.ne}) << kFrac, hi = std::max({s.w, s.n, s.ne}) << kFrac;
      p = std::clamp(p, lo, hi);
    }
    prediction_ = p;
    return p;
  }

  // Records the true sample at (x, y) after predict().
  void update(std::int64_t actual, std::size_t x, std::size_t y) {
    if (pred_ == 1) return;
    const std::int64_t a = actual << kFrac;
    for (int i = 0; i < kSubs; ++i)
      sub_[std::size_t(i)][(y & 1) * (w_ + 2) + x + 1] =
          std::min(std::abs(sub_value_[std::size_t(i)] - a), kErrorCap);
    true_[(y & 1) * (w_ + 2) + x + 1] = std::clamp(prediction_ - a, -kErrorCap, kErrorCap);
  }

 private:
  std::size_t w_;
  int pred_;                                          // 0 weighted, 1 MED, 2 mixed
  std::array<std::vector<std::int64_t>, kSubs> sub_;  // |sub-prediction error|, two rows padded by one
  std::vector<std::int64_t> true_;                    // final prediction - actual, the same layout
  std::array<std::int64_t, kSubs> sub_value_{};
  std::int64_t prediction_ = 0;
};

inline WeightedPredictor::Neighbours neighbours(const std::int32_t* v, std::size_t stride, std::size_t w,
                                                std::size_t x, std::size_t y) {
  const std::int32_t* row = v + y * stride;
  const std::int32_t* up = y > 0 ? row - stride : nullptr;
  WeightedPredictor::Neighbours s{};
  s.w = x > 0 ? row[x - 1] : (up ? up[x] : 0);
  s.n = up ? up[x] : s.w;
  s.nw = up && x > 0 ? up[x - 1] : s.n;
  s.ne = up && x + 1 < w ? up[x + 1] : s.n;
  s.nn = y > 1 ? (up - stride)[x] : s.n;
  s.ww = x > 1 ? row[x - 2] : s.w;
  return s;
}

// Codes a coarse band (the encoder's `values`, or decoded into them) as residuals of the
// weighted predictor; returns the largest residual magnitude. The encoder's first call uses a
// NullIo to find `planes`.
template <class Io>
std::uint32_t code_predicted(Io& io, std::int32_t* v, std::size_t stride, std::size_t w, std::size_t h,
                             int planes, int mode, const LcParent& guide) {
  CausalState state(w, h);
  auto& [pw, sp, mag, sgn, models] = state;
  Models& m = *models;
  WeightedPredictor wp(w, mode);

  std::uint32_t largest = 0;
  for (std::size_t y = 0; y < h; ++y) {
    std::int32_t* row = v + y * stride;
    for (std::size_t x = 0; x < w; ++x) {
      if constexpr (Io::kDry) {  // residuals only: no contexts
        const std::int64_t p8 = wp.predict(neighbours(v, stride, w, x, y), x, y);
        const std::int64_t r = std::int64_t(row[x]) - ((p8 + (1 << (kFrac - 1))) >> kFrac);
        const auto magnitude = std::uint32_t(std::min<std::int64_t>(r < 0 ? -r : r, 0xFFFFFFFFll));
        wp.update(row[x], x, y);
        largest = std::max(largest, magnitude);
        io.note(magnitude);
        continue;
      }
      const std::size_t i = (y + kPad) * pw + x + kPad;
      const std::uint32_t* a = mag.data() + i;
      // A wider neighbourhood than the detail bands' (the samples' residuals are less sparse).
      std::uint32_t s = 5 * (a[-1] + a[-sp]) + 3 * (a[-sp - 1] + a[-sp + 1]) +
                        2 * (a[-2] + a[-2 * sp] + a[-sp + 2]) + a[-sp - 2] + a[-2 * sp + 1] + a[-2 * sp - 1] +
                        a[-2 * sp + 2] + a[-2 * sp - 2];
      const std::int64_t p8 = wp.predict(neighbours(v, stride, w, x, y), x, y);
      int gsign = 1;
      if (guide.guide) {  // the first component's MED residual at this very sample
        const auto g = neighbours(guide.guide, guide.guide_stride, w, x, y);
        const std::int64_t e = guide.guide[y * guide.guide_stride + x] - med(g.w, g.n, g.nw);
        s += std::uint32_t(2 * std::min<std::int64_t>(e < 0 ? -e : e, kMagnitudeCap));
        gsign = e == 0 ? 1 : (e < 0 ? 0 : 2);
      }
      if (guide.guide2) {  // the previous component's MED residual (V after U: strongly alike)
        const auto g = neighbours(guide.guide2, guide.guide_stride, w, x, y);
        const std::int64_t e = guide.guide2[y * guide.guide_stride + x] - med(g.w, g.n, g.nw);
        s += std::uint32_t(16 * std::min<std::int64_t>(e < 0 ? -e : e, kMagnitudeCap));
      }
      const std::int64_t pred = (p8 + (1 << (kFrac - 1))) >> kFrac;
      const int ctx = lc_activity_context(s);
      const std::int64_t r = Io::kEncoding ? std::int64_t(row[x]) - pred : 0;
      const auto magnitude = std::uint32_t(std::min<std::int64_t>(r < 0 ? -r : r, 0xFFFFFFFFll));
      const std::uint32_t u = code_magnitude(io, m, ctx, magnitude, planes);
      int negative = 0;
      if (u != 0) {
        const int sc = 9 * gsign + 3 * sign_of(sgn[i - 1]) + sign_of(sgn[i - pw]);
        negative = io.bit(r < 0, m.sign[std::size_t(sc)]);
      }
      if constexpr (!Io::kEncoding) {
        const std::int64_t value = pred + (negative ? -std::int64_t(u) : std::int64_t(u));
        require_stream(value >= -kValueLimit && value <= kValueLimit,
                       "lc code-block: coarse value out of range");
        row[x] = std::int32_t(value);
      }
      wp.update(row[x], x, y);

      largest = std::max(largest, u);
      mag[i] = std::min(u, kMagnitudeCap);
      sgn[i] = std::int8_t(u == 0 ? 0 : (negative ? -1 : 1));
    }
  }
  return largest;
}

// Codes nothing: the encoder's dry run of code_predicted, which finds the largest residual.
struct NullIo {
  static constexpr bool kEncoding = true;
  static constexpr bool kDry = true;
  std::uint64_t cost = 0;  // sum of the residuals' bit lengths: the predictors' figure of merit
  void note(std::uint32_t magnitude) { cost += std::uint64_t(std::bit_width(magnitude)); }
  int bit(int b, Model&) { return b; }
  std::uint32_t raw(std::uint32_t v, int) { return v; }
};

}  // namespace

LcCodeword lc_encode_block(std::span<const std::int32_t> values, std::size_t width, std::size_t height,
                           bool low_pass, const LcParent& parent) {
  std::vector<std::int32_t> copy(values.begin(), values.end());
  LcCodeword best;
  if (!low_pass) {
    std::uint64_t largest = 0;
    for (std::int32_t x : values)
      largest = std::max<std::uint64_t>(largest, std::uint64_t(x < 0 ? -std::int64_t(x) : x));
    if (largest >= (std::uint64_t(1) << kMaxBitPlanes))
      throw IndexRangeError("coefficient too large for the lc coder");
    best.planes = int(std::bit_width(largest));
    if (best.planes == 0) return best;
    EncoderIo io;
    code_symbols(io, copy.data(), width, width, height, parent, best.planes);
    best.bytes = io.coder.finish();
  } else {
    for (std::int32_t x : values)
      if (x >= kValueLimit || x <= -kValueLimit)
        throw IndexRangeError("coefficient too large for the lc coder");
    // The predictor whose residuals have the fewest bits in all is used (its number leads the
    // codeword): within 0.2% of coding with each and keeping the smallest, at a third of the time.
    int mode = 0;
    std::uint32_t largest = 0;
    std::uint64_t least = 0;
    for (int m = 0; m < kPredictors; ++m) {
      NullIo dry;
      const std::uint32_t l =
          code_predicted(dry, copy.data(), width, width, height, kMaxBitPlanes, m, parent);
      if (m == 0 || dry.cost < least) {
        mode = m;
        largest = l;
        least = dry.cost;
      }
    }
    if (largest >= (std::uint32_t(1) << kMaxBitPlanes))
      throw IndexRangeError("residual too large for the lc coder");
    best.planes = int(std::bit_width(largest));
    if (best.planes == 0) return best;  // all zero (a nonzero sample has a nonzero residual first)
    EncoderIo io;
    io.coder.encode_raw(std::uint32_t(mode), 2);
    code_predicted(io, copy.data(), width, width, height, best.planes, mode, parent);
    best.bytes = io.coder.finish();
  }
  if (best.bytes.empty()) best.bytes.push_back(0);  // a codeword is never empty (the index says so)
  return best;
}

void lc_decode_block(std::span<const std::uint8_t> codeword, std::size_t width, std::size_t height,
                     bool low_pass, const LcParent& parent, int planes, std::int32_t* out,
                     std::size_t stride) {
  require_stream(planes >= 1 && planes <= kMaxBitPlanes && !codeword.empty(), "lc code-block: bit planes");
  DecoderIo io{RangeDecoder(codeword)};
  std::uint32_t largest = 0;
  if (low_pass) {
    const int mode = int(io.coder.decode_raw(2));
    require_stream(mode < kPredictors, "lc code-block: predictor");
    largest = code_predicted(io, out, stride, width, height, planes, mode, parent);
  } else {
    largest = code_symbols(io, out, stride, width, height, parent, planes);
  }
  require_stream(int(std::bit_width(largest)) == planes,
                 "lc code-block: largest magnitude differs from the index");
}

}  // namespace pupwave
