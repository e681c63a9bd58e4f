#include "codec/entropy/block_decoder.h"

#include <string>

#include "codec/entropy/block_contexts.h"
#include "codec/entropy/range_decoder.h"
#include "codec/error.h"

namespace pupwave {
namespace {

// Mirrors BitPlaneEncoder pass by pass, stopping after the requested number of passes.
class BitPlaneDecoder {
 public:
  BitPlaneDecoder(std::span<const std::uint8_t> codeword, const Extent& size, unsigned orientation)
      : state_(size, orientation), size_(size), flag_row_(size[0] + 2), rc_(codeword) {
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
  void decode_significance(std::size_t f, std::size_t i, int p, int ctx, std::size_t y, std::size_t z) {
    if (rc_.decode(state_.models[std::size_t(ctx)])) become_significant(f, i, p, y, z);
  }
  void become_significant(std::size_t f, std::size_t i, int p, std::size_t y, std::size_t z) {
    const auto [ctx, flip] = state_.sign_context(f);
    const bool negative = (rc_.decode(state_.models[std::size_t(ctx)]) ^ flip) != 0;
    state_.make_significant(f, negative);
    state_.mark_active(y, z);
    const std::int32_t bit = std::int32_t(1u << p);
    out_.known[i] = negative ? -bit : bit;
    out_.low_plane[i] = std::uint8_t(p);
  }

  void significance_pass(int p) {
    const std::size_t fs = flag_row_, is = size_[0];
    for_each_stripe(size_, [&](const Stripe& s) {
      if (!state_.stripe_active(s.index)) return;  // every context 0: nothing coded
      for (std::size_t x = 0; x < is; ++x)
        for (std::size_t r = 0; r < s.rows; ++r) {
          const std::size_t f = s.f0 + x + r * fs;
          if (state_.flags(f) & kSignificant) continue;
          const int ctx = state_.significance_context(f);
          if (ctx == 0) continue;
          decode_significance(f, s.i0 + x + r * is, p, ctx, s.y0 + r, s.z);
          state_.flags(f) |= kVisited;
        }
    });
  }

  void refinement_pass(int p) {
    const std::size_t fs = flag_row_, is = size_[0];
    const std::int32_t bit_value = std::int32_t(1u << p);
    for_each_stripe(size_, [&](const Stripe& s) {
      if (!state_.stripe_active(s.index)) return;  // nothing significant
      for (std::size_t x = 0; x < is; ++x)
        for (std::size_t r = 0; r < s.rows; ++r) {
          const std::size_t f = s.f0 + x + r * fs;
          if ((state_.flags(f) & (kSignificant | kVisited)) != kSignificant) continue;
          const std::size_t i = s.i0 + x + r * is;
          const int bit = rc_.decode(state_.models[std::size_t(state_.refinement_context(f))]);
          state_.flags(f) |= kRefined;
          const std::int32_t add = bit ? bit_value : 0;
          out_.known[i] += out_.known[i] < 0 ? -add : add;
          out_.low_plane[i] = std::uint8_t(p);
        }
    });
  }

  void cleanup_pass(int p) {
    const std::size_t fs = flag_row_, is = size_[0];
    for_each_stripe(size_, [&](const Stripe& s) {
      bool quiet = s.rows == kStripe && !state_.stripe_active(s.index);  // as in the encoder
      for (std::size_t x = 0; x < is; ++x) {
        const std::size_t f0 = s.f0 + x, i0 = s.i0 + x;
        std::size_t r = 0;
        if (s.rows == kStripe && (quiet || state_.run_eligible(f0))) {
          if (!rc_.decode(state_.models[kRunContext])) continue;
          std::size_t first = std::size_t(rc_.decode_equiprobable()) << 1;
          first |= std::size_t(rc_.decode_equiprobable());
          become_significant(f0 + first * fs, i0 + first * is, p, s.y0 + first, s.z);
          quiet = false;
          r = first + 1;
        }
        for (; r < s.rows; ++r) {
          const std::size_t f = f0 + r * fs;
          if (state_.flags(f) & (kSignificant | kVisited)) continue;
          decode_significance(f, i0 + r * is, p, state_.significance_context(f), s.y0 + r, s.z);
        }
      }
    });
    state_.clear_visited();
  }

  BlockState state_;
  Extent size_;           // block extent (a copy: flag writes would force reloads of state_'s)
  std::size_t flag_row_;  // flag positions between vertically adjacent coefficients
  RangeDecoder rc_;
  DecodedBlock out_;
};

}  // namespace

DecodedBlock decode_block(std::span<const std::uint8_t> codeword, int planes, int passes, const Extent& size,
                          unsigned orientation) {
  require_stream(planes >= 0 && planes <= kMaxBitPlanes,
                 [&] { return "code-block bit-plane count " + std::to_string(planes); });
  require_stream(passes >= 0 && passes <= passes_for_planes(planes),
                 [&] { return "code-block pass count " + std::to_string(passes); });
  return BitPlaneDecoder(codeword, size, orientation).run(planes, passes);
}

}  // namespace pupwave
