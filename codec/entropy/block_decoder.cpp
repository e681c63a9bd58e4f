#include "codec/entropy/block_decoder.h"

#include <algorithm>
#include <bit>
#include <string>

#include "codec/entropy/block_contexts.h"
#include "codec/entropy/range_decoder.h"
#include "codec/error.h"

namespace pupwave {
namespace {

// Mirrors BitPlaneEncoder pass by pass, stopping after the requested number of passes.
// Each pass works on local copies of the range decoder and of the array pointers, which the
// compiler keeps in registers: as members they would be reloaded and stored around every
// write to the coefficient state, which may alias them.
class BitPlaneDecoder {
 public:
  BitPlaneDecoder(std::span<const std::uint8_t> codeword, const Extent& size, unsigned orientation)
      : state_(size, orientation), size_(size), rc_(codeword) {
    const std::size_t n = size[0] * size[1] * size[2];
    out_.known.assign(n, 0);
    out_.low_plane.assign(n, 255);
  }

  DecodedBlock run(int planes, int passes) {
    int done = 0;
    int lowest_refined = planes;  // lowest bit-plane whose refinement pass was decoded
    for (int p = planes - 1; p >= 0 && done < passes; --p) {
      if (p != planes - 1) {
        significance_pass(p);
        if (++done == passes) break;
        refinement_pass(p);
        lowest_refined = p;
        if (++done == passes) break;
      }
      cleanup_pass(p);
      ++done;
    }
    // low_plane holds the plane where each coefficient became significant; one significant
    // before a decoded refinement pass was refined in every later one, lastly lowest_refined.
    // min(low, lowest_refined) with 255 kept: 255 + 1 wraps to 0 (a form that vectorizes).
    const auto cap = std::uint8_t(lowest_refined + 1);
    if (lowest_refined < planes)
      for (auto& low : out_.low_plane) low = std::uint8_t(std::min(std::uint8_t(low + 1), cap) - 1);
    return std::move(out_);
  }

 private:
  // The pass-local view of the decoder.
  struct Pass {
    RangeDecoder rc;
    BlockState& state;
    std::int32_t* known;
    std::uint8_t* low_plane;
    std::size_t width;   // block indices between vertically adjacent coefficients
    std::size_t stride;  // padded positions between vertically adjacent coefficients
    int p;

    // Decodes the sign of row r of column x of stripe s, which has just become significant.
    // Always inlined, as are make_significant and decode_significance: with the far bits GCC does
    // not inline them on its own, and the calls would be a tenth of the decode time.
    [[gnu::always_inline]] void become_significant(const Stripe& s, std::size_t x, unsigned r) {
      const std::size_t f = s.f0 + x + r * stride;
      const auto [ctx, flip] = state.sign_context(f);
      const bool negative = (rc.decode(state.models[std::size_t(ctx)]) ^ flip) != 0;
      state.make_significant(f, x, s.y0 + r, s.z, negative);
      const std::size_t i = s.i0 + x + r * width;
      const std::int32_t bit = std::int32_t(1u << p);
      known[i] = negative ? -bit : bit;
      low_plane[i] = std::uint8_t(p);
    }
    // Decodes the significance bit of row r of column x of stripe s.
    [[gnu::always_inline]] void decode_significance(const Stripe& s, std::size_t x, unsigned r) {
      const std::size_t f = s.f0 + x + r * stride;
      const int ctx = state.full_significance_context(f, state.column(s.c0 + x), r);
      if (rc.decode(state.models[std::size_t(ctx)])) become_significant(s, x, r);
    }
  };
  Pass begin(int p) {
    return Pass{rc_, state_, out_.known.data(), out_.low_plane.data(), size_[0], size_[0] + 2, p};
  }

  // Rows of column word w still to code in the significance pass: insignificant, with a
  // significant neighbour (a non-zero context), not yet visited.
  static std::uint32_t propagation_rows(std::uint32_t w, std::uint32_t rows) {
    return (w >> kColumnNeighbour) & ~(w >> kColumnSignificant) & ~(w >> kColumnVisited) & rows;
  }

  void significance_pass(int p) {
    Pass pass = begin(p);
    for_each_stripe(state_, [&](const Stripe& s) {
      if (!state_.stripe_active(s.index)) return;  // every context 0: nothing coded
      std::uint32_t* columns = &state_.column(s.c0);
      for (std::size_t x = 0; x < pass.width; ++x) {
        // A row becoming significant gives the rows below it a neighbour: re-read the word.
        for (std::uint32_t todo = propagation_rows(columns[x], s.rows); todo != 0;) {
          const unsigned r = unsigned(std::countr_zero(todo));
          pass.decode_significance(s, x, r);
          columns[x] |= 1u << (kColumnVisited + r);
          todo = propagation_rows(columns[x], s.rows) & ~((2u << r) - 1u);
        }
      }
    });
    rc_ = pass.rc;
  }

  void refinement_pass(int p) {
    Pass pass = begin(p);
    const std::int32_t bit_value = std::int32_t(1u << p);
    BitModel* models = state_.models.data();
    for_each_stripe(state_, [&](const Stripe& s) {
      if (!state_.stripe_active(s.index)) return;  // nothing significant
      std::uint32_t* columns = &state_.column(s.c0);
      std::int32_t* known = pass.known + s.i0;
      for (std::size_t x = 0; x < pass.width; ++x) {
        const std::uint32_t w = columns[x];
        const std::uint32_t todo = (w >> kColumnSignificant) & ~(w >> kColumnVisited) & s.rows;
        if (todo == 0) continue;
        for (std::uint32_t t = todo; t != 0; t &= t - 1) {
          const unsigned r = unsigned(std::countr_zero(t));
          const int bit = pass.rc.decode(models[BlockState::refinement_context(w, r)]);
          // known += sign(known) * bit * 2^p without branches (the sign is a coin toss).
          std::int32_t& k = known[x + r * pass.width];
          const std::int32_t add = bit_value & -std::int32_t(bit);
          const std::int32_t sign = k >> 31;
          k += (add ^ sign) - sign;
        }
        columns[x] = w | todo << kColumnRefined;
      }
    });
    rc_ = pass.rc;
  }

  void cleanup_pass(int p) {
    Pass pass = begin(p);
    for_each_stripe(state_, [&](const Stripe& s) {
      const bool full = s.rows == kRows;
      std::uint32_t* columns = &state_.column(s.c0);
      for (std::size_t x = 0; x < pass.width; ++x) {
        const std::uint32_t w = columns[x];
        std::uint32_t todo = ~((w >> kColumnSignificant) | (w >> kColumnVisited)) & s.rows;
        // Run mode: a full column with nothing significant, visited or near significance.
        constexpr std::uint32_t kBusy =
            kRows << kColumnSignificant | kRows << kColumnVisited | kRows << kColumnNeighbour;
        if (full && (w & kBusy) == 0) {
          if (!pass.rc.decode(state_.models[std::size_t(BlockState::run_context(w))])) continue;
          unsigned first = unsigned(pass.rc.decode_equiprobable()) << 1;
          first |= unsigned(pass.rc.decode_equiprobable());
          pass.become_significant(s, x, first);
          todo &= ~((2u << first) - 1u);
        }
        for (; todo != 0; todo &= todo - 1) pass.decode_significance(s, x, unsigned(std::countr_zero(todo)));
        columns[x] &= ~(kRows << kColumnVisited);  // this plane's visits end with its cleanup
      }
    });
    rc_ = pass.rc;
  }

  BlockState state_;
  Extent size_;  // block extent (a copy: state writes would force reloads of state_'s)
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
