#include "codec/entropy/block_encoder.h"

#include <bit>
#include <cmath>
#include <stdexcept>

#include "codec/entropy/block_contexts.h"
#include "codec/entropy/block_tally.h"

namespace pupwave {
namespace {

// Runs the coding passes over one block and, when Track, records the truncation points and the
// distortion each pass removes (a whole-codeword encode needs neither: it skips their cost).
template <bool Track>
class BitPlaneEncoder {
 public:
  BitPlaneEncoder(std::span<const float> magnitude, std::span<const std::uint8_t> negative,
                  const Extent& size, unsigned orientation, double delta, ContextTally* tally)
      : m_(magnitude),
        negative_(negative),
        state_(size, orientation),
        size_(size),
        flag_row_(size[0] + 2),
        delta_(delta),
        q_(magnitude.size()),
        tally_(tally),
        prior_class_(prior_class_of(orientation)) {
    for (std::size_t i = 0; i < q_.size(); ++i) {
      if (!(m_[i] < float(1u << kMaxBitPlanes)))
        throw IndexRangeError("quantization index too large for the block coder");
      q_[i] = std::uint32_t(m_[i]);
    }
  }

  EncodedBlock run() {
    EncodedBlock out;
    std::uint32_t all = 0;
    for (auto q : q_) all |= q;
    while (all >> out.planes) ++out.planes;
    if constexpr (Track)
      for (std::size_t i = 0; i < q_.size(); ++i) out.initial_distortion += double(m_[i]) * double(m_[i]);
    for (int p = out.planes - 1; p >= 0; --p) {
      if (p != out.planes - 1) {
        significance_pass(p);
        finish_pass(out);
        refinement_pass(p);
        finish_pass(out);
      }
      cleanup_pass(p);
      finish_pass(out);
    }
    if (tally_ != nullptr) tally_->add(prior_class_, starts_);
    if constexpr (!Track) {
      out.committed = rc_.finish();
      return out;
    }
    auto committed = rc_.committed();
    out.committed.assign(committed.begin(), committed.end());
    return out;
  }

  // Passes coded so far (untracked encodes count them only).
  int passes_coded() const { return passes_coded_; }

 private:
  // Reconstruction (index units) of magnitude q known down to bit-plane p.
  double reconstruction(std::uint32_t q, int p) const {
    const std::uint32_t known = (q >> p) << p;
    return double(known) + delta_ * double(1u << p);
  }
  void add_gain(double m, double before, double after) {
    if constexpr (!Track) return;
    gain_ += (m - before) * (m - before) - (m - after) * (m - after);
  }

  // Codes `bit` in context ctx (kept for prior training when the caller passed a tally).
  void code(RangeEncoder& rc, int bit, int ctx) {
    if (tally_ != nullptr) starts_.record(ctx, bit);
    rc.encode(bit, state_.models[std::size_t(ctx)]);
  }

  void finish_pass(EncodedBlock& out) {
    ++passes_coded_;
    if constexpr (!Track) return;
    out.passes.push_back(rc_.truncation_point());
    out.distortion_drop.push_back(gain_);
    gain_ = 0.0;
  }

  // Codes bit-plane p of row r of column x of stripe s, not yet significant; true if 1.
  bool code_significance(RangeEncoder& rc, const Stripe& s, std::size_t x, unsigned r, int p) {
    const std::size_t f = s.f0 + x + r * flag_row_, i = s.i0 + x + r * size_[0];
    const int bit = int((q_[i] >> p) & 1u);
    code(rc, bit, state_.full_significance_context(f, state_.column(s.c0 + x), r));
    if (bit) become_significant(rc, s, x, r, p);
    return bit != 0;
  }
  void become_significant(RangeEncoder& rc, const Stripe& s, std::size_t x, unsigned r, int p) {
    const std::size_t f = s.f0 + x + r * flag_row_, i = s.i0 + x + r * size_[0];
    const auto [ctx, flip] = state_.sign_context(f);
    code(rc, int(negative_[i] != 0) ^ flip, ctx);
    state_.make_significant(f, x, s.y0 + r, s.z, negative_[i] != 0);
    add_gain(m_[i], 0.0, reconstruction(q_[i], p));
  }

  // As in the decoder: insignificant rows with a significant neighbour, not yet visited.
  static std::uint32_t propagation_rows(std::uint32_t w, std::uint32_t rows) {
    return (w >> kColumnNeighbour) & ~(w >> kColumnSignificant) & ~(w >> kColumnVisited) & rows;
  }

  void significance_pass(int p) {
    RangeEncoder rc = std::move(rc_);  // a local the compiler can keep in registers
    for_each_stripe(state_, [&](const Stripe& s) {
      if (!state_.stripe_active(s.index)) return;  // every context 0: nothing to code
      for (std::size_t x = 0; x < size_[0]; ++x) {
        std::uint32_t& w = state_.column(s.c0 + x);
        for (std::uint32_t todo = propagation_rows(w, s.rows); todo != 0;) {
          const unsigned r = unsigned(std::countr_zero(todo));
          code_significance(rc, s, x, r, p);
          w |= 1u << (kColumnVisited + r);
          todo = propagation_rows(w, s.rows) & ~((2u << r) - 1u);
        }
      }
    });
    rc_ = std::move(rc);
  }

  void refinement_pass(int p) {
    RangeEncoder rc = std::move(rc_);
    for_each_stripe(state_, [&](const Stripe& s) {
      if (!state_.stripe_active(s.index)) return;  // nothing significant
      for (std::size_t x = 0; x < size_[0]; ++x) {
        std::uint32_t& w = state_.column(s.c0 + x);
        const std::uint32_t todo = (w >> kColumnSignificant) & ~(w >> kColumnVisited) & s.rows;
        for (std::uint32_t t = todo; t != 0; t &= t - 1) {
          const unsigned r = unsigned(std::countr_zero(t));
          const std::size_t i = s.i0 + x + r * size_[0];
          code(rc, int((q_[i] >> p) & 1u), BlockState::refinement_context(w, r));
          add_gain(m_[i], reconstruction(q_[i], p + 1), reconstruction(q_[i], p));
        }
        w |= todo << kColumnRefined;
      }
    });
    rc_ = std::move(rc);
  }

  void cleanup_pass(int p) {
    const std::size_t is = size_[0];
    RangeEncoder rc = std::move(rc_);
    for_each_stripe(state_, [&](const Stripe& s) {
      const bool full = s.rows == kRows;
      for (std::size_t x = 0; x < size_[0]; ++x) {
        std::uint32_t& w = state_.column(s.c0 + x);
        std::uint32_t todo = ~((w >> kColumnSignificant) | (w >> kColumnVisited)) & s.rows;
        if (full &&
            (w & (kRows << kColumnSignificant | kRows << kColumnVisited | kRows << kColumnNeighbour)) == 0) {
          const std::size_t i0 = s.i0 + x;
          const std::uint32_t column = q_[i0] | q_[i0 + is] | q_[i0 + 2 * is] | q_[i0 + 3 * is];
          const bool any = (column >> p) & 1u;
          code(rc, int(any), BlockState::run_context(w));
          if (!any) continue;
          unsigned first = 0;  // first coefficient of the column with bit p set
          while (!((q_[i0 + first * is] >> p) & 1u)) ++first;
          rc.encode_equiprobable(int(first >> 1));
          rc.encode_equiprobable(int(first & 1));
          become_significant(rc, s, x, first, p);
          todo &= ~((2u << first) - 1u);
        }
        for (; todo != 0; todo &= todo - 1) code_significance(rc, s, x, unsigned(std::countr_zero(todo)), p);
        w &= ~(kRows << kColumnVisited);  // this plane's visits end with its cleanup
      }
    });
    rc_ = std::move(rc);
  }

  std::span<const float> m_;
  std::span<const std::uint8_t> negative_;
  BlockState state_;
  Extent size_;           // block extent (a copy: state writes would force reloads of state_'s)
  std::size_t flag_row_;  // padded positions between vertically adjacent coefficients
  double delta_;
  std::vector<std::uint32_t> q_;
  RangeEncoder rc_;
  double gain_ = 0.0;
  int passes_coded_ = 0;
  ContextTally* tally_;      // null unless prior training counts bits
  std::size_t prior_class_;  // band class of the block (ctx_priors.h)
  BlockStarts starts_;       // the bits kept for tally_
};

}  // namespace

std::vector<std::uint8_t> EncodedBlock::codeword(int n) const {
  if (n <= 0) return {};
  return RangeEncoder::codeword(committed, passes[std::size_t(n - 1)]);
}

EncodedBlock encode_block(std::span<const float> magnitude, std::span<const std::uint8_t> negative,
                          const Extent& size, unsigned orientation, double delta, ContextTally* tally) {
  if (magnitude.size() != size[0] * size[1] * size[2] || negative.size() != magnitude.size())
    throw std::invalid_argument("encode_block: coefficient count does not match the block size");
  return BitPlaneEncoder<true>(magnitude, negative, size, orientation, delta, tally).run();
}

WholeBlock encode_block_whole(std::span<const float> magnitude, std::span<const std::uint8_t> negative,
                              const Extent& size, unsigned orientation, double delta, ContextTally* tally) {
  if (magnitude.size() != size[0] * size[1] * size[2] || negative.size() != magnitude.size())
    throw std::invalid_argument("encode_block: coefficient count does not match the block size");
  BitPlaneEncoder<false> encoder(magnitude, negative, size, orientation, delta, tally);
  EncodedBlock coded = encoder.run();
  return WholeBlock{coded.planes, encoder.passes_coded(), std::move(coded.committed)};
}

}  // namespace pupwave
