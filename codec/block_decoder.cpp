#include "codec/block_decoder.h"

#include <string>

#include "codec/block_contexts.h"
#include "codec/error.h"
#include "codec/range_decoder.h"

namespace pupwave {
namespace {

// Mirrors BitPlaneEncoder pass by pass, stopping after the requested number of passes.
class BitPlaneDecoder {
 public:
  BitPlaneDecoder(std::span<const std::uint8_t> codeword, const Extent& size, unsigned orientation)
      : state_(size, orientation), rc_(codeword) {
    const std::size_t n = size[0] * size[1] * size[2];
    out_.known.assign(n, 0);
    out_.low_plane.assign(n, 255);
  }

  DecodedBlock run(int planes, int passes) {
    int done = 0;
    for (int p = planes - 1; p >= 0 && done < passes; --p) {
      if (p != planes - 1) {
        significance_pass(p);
        if (++done == passes) break;
        refinement_pass(p);
        if (++done == passes) break;
      }
      cleanup_pass(p);
      ++done;
    }
    return std::move(out_);
  }

 private:
  std::size_t index(std::size_t x, std::size_t y, std::size_t z) const {
    const Extent& s = state_.size();
    return x + s[0] * (y + s[1] * z);
  }

  void decode_significance(std::size_t f, std::size_t i, int p, int ctx) {
    if (rc_.decode(state_.models[std::size_t(ctx)])) become_significant(f, i, p);
  }
  void become_significant(std::size_t f, std::size_t i, int p) {
    const auto [ctx, flip] = state_.sign_context(f);
    const bool negative = (rc_.decode(state_.models[std::size_t(ctx)]) ^ flip) != 0;
    state_.make_significant(f, negative);
    const std::int32_t bit = std::int32_t(1u << p);
    out_.known[i] = negative ? -bit : bit;
    out_.low_plane[i] = std::uint8_t(p);
  }

  void significance_pass(int p) {
    for_each_stripe_column(state_.size(),
                           [&](std::size_t x, std::size_t y0, std::size_t z, std::size_t rows) {
                             for (std::size_t y = y0; y < y0 + rows; ++y) {
                               const std::size_t f = state_.at(x, y, z);
                               if (state_.flags(f) & kSignificant) continue;
                               const int ctx = state_.significance_context(f);
                               if (ctx == 0) continue;
                               decode_significance(f, index(x, y, z), p, ctx);
                               state_.flags(f) |= kVisited;
                             }
                           });
  }

  void refinement_pass(int p) {
    for_each_stripe_column(
        state_.size(), [&](std::size_t x, std::size_t y0, std::size_t z, std::size_t rows) {
          for (std::size_t y = y0; y < y0 + rows; ++y) {
            const std::size_t f = state_.at(x, y, z);
            if ((state_.flags(f) & (kSignificant | kVisited)) != kSignificant) continue;
            const std::size_t i = index(x, y, z);
            const int bit = rc_.decode(state_.models[std::size_t(state_.refinement_context(f))]);
            state_.flags(f) |= kRefined;
            const std::int32_t add = bit ? std::int32_t(1u << p) : 0;
            out_.known[i] += out_.known[i] < 0 ? -add : add;
            out_.low_plane[i] = std::uint8_t(p);
          }
        });
  }

  void cleanup_pass(int p) {
    for_each_stripe_column(state_.size(),
                           [&](std::size_t x, std::size_t y0, std::size_t z, std::size_t rows) {
                             std::size_t y = y0;
                             if (rows == kStripe && run_eligible(x, y0, z)) {
                               if (!rc_.decode(state_.models[kRunContext])) return;
                               std::size_t first = std::size_t(rc_.decode_equiprobable()) << 1;
                               first |= std::size_t(rc_.decode_equiprobable());
                               become_significant(state_.at(x, y0 + first, z), index(x, y0 + first, z), p);
                               y = y0 + first + 1;
                             }
                             for (; y < y0 + rows; ++y) {
                               const std::size_t f = state_.at(x, y, z);
                               if (state_.flags(f) & (kSignificant | kVisited)) continue;
                               decode_significance(f, index(x, y, z), p, state_.significance_context(f));
                             }
                           });
    state_.clear_visited();
  }

  bool run_eligible(std::size_t x, std::size_t y0, std::size_t z) const {
    for (std::size_t r = 0; r < kStripe; ++r) {
      const std::size_t f = state_.at(x, y0 + r, z);
      if ((state_.flags(f) & (kSignificant | kVisited)) || !state_.isolated(f)) return false;
    }
    return true;
  }

  BlockState state_;
  RangeDecoder rc_;
  DecodedBlock out_;
};

}  // namespace

DecodedBlock decode_block(std::span<const std::uint8_t> codeword, int planes, int passes, const Extent& size,
                          unsigned orientation) {
  require_stream(planes >= 0 && planes <= kMaxBitPlanes,
                 "code-block bit-plane count " + std::to_string(planes));
  require_stream(passes >= 0 && passes <= passes_for_planes(planes),
                 "code-block pass count " + std::to_string(passes));
  return BitPlaneDecoder(codeword, size, orientation).run(planes, passes);
}

}  // namespace pupwave
