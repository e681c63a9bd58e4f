#include "codec/entropy/block_encoder.h"

#include <cmath>
#include <stdexcept>

#include "codec/entropy/block_contexts.h"

namespace pupwave {
namespace {

// Runs the coding passes over one block and records the truncation points.
class BitPlaneEncoder {
 public:
  BitPlaneEncoder(std::span<const float> magnitude, std::span<const std::uint8_t> negative,
                  const Extent& size, unsigned orientation, double delta)
      : m_(magnitude),
        negative_(negative),
        state_(size, orientation),
        size_(size),
        flag_row_(size[0] + 2),
        delta_(delta),
        q_(magnitude.size()) {
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
    auto committed = rc_.committed();
    out.committed.assign(committed.begin(), committed.end());
    return out;
  }

 private:
  // Reconstruction (index units) of magnitude q known down to bit-plane p.
  double reconstruction(std::uint32_t q, int p) const {
    const std::uint32_t known = (q >> p) << p;
    return double(known) + delta_ * double(1u << p);
  }
  void add_gain(double m, double before, double after) {
    gain_ += (m - before) * (m - before) - (m - after) * (m - after);
  }

  void finish_pass(EncodedBlock& out) {
    out.passes.push_back(rc_.truncation_point());
    out.distortion_drop.push_back(gain_);
    gain_ = 0.0;
  }

  // Codes bit-plane p of a coefficient not yet significant (at row y of slice z).
  void code_significance(std::size_t p_flag, std::size_t i, int p, int ctx, std::size_t y, std::size_t z) {
    const int bit = int((q_[i] >> p) & 1u);
    rc_.encode(bit, state_.models[std::size_t(ctx)]);
    if (bit) become_significant(p_flag, i, p, y, z);
  }
  void become_significant(std::size_t p_flag, std::size_t i, int p, std::size_t y, std::size_t z) {
    const auto [ctx, flip] = state_.sign_context(p_flag);
    rc_.encode(int(negative_[i] != 0) ^ flip, state_.models[std::size_t(ctx)]);
    state_.make_significant(p_flag, negative_[i] != 0);
    state_.mark_active(y, z);
    add_gain(m_[i], 0.0, reconstruction(q_[i], p));
  }

  void significance_pass(int p) {
    const std::size_t fs = flag_row_, is = size_[0];
    for_each_stripe(size_, [&](const Stripe& s) {
      if (!state_.stripe_active(s.index)) return;  // every context 0: nothing to code
      for (std::size_t x = 0; x < is; ++x)
        for (std::size_t r = 0; r < s.rows; ++r) {
          const std::size_t f = s.f0 + x + r * fs;
          if (state_.flags(f) & kSignificant) continue;
          const int ctx = state_.significance_context(f);
          if (ctx == 0) continue;
          code_significance(f, s.i0 + x + r * is, p, ctx, s.y0 + r, s.z);
          state_.flags(f) |= kVisited;
        }
    });
  }

  void refinement_pass(int p) {
    const std::size_t fs = flag_row_, is = size_[0];
    for_each_stripe(size_, [&](const Stripe& s) {
      if (!state_.stripe_active(s.index)) return;  // nothing significant
      for (std::size_t x = 0; x < is; ++x)
        for (std::size_t r = 0; r < s.rows; ++r) {
          const std::size_t f = s.f0 + x + r * fs;
          if ((state_.flags(f) & (kSignificant | kVisited)) != kSignificant) continue;
          const std::size_t i = s.i0 + x + r * is;
          rc_.encode(int((q_[i] >> p) & 1u), state_.models[std::size_t(state_.refinement_context(f))]);
          state_.flags(f) |= kRefined;
          add_gain(m_[i], reconstruction(q_[i], p + 1), reconstruction(q_[i], p));
        }
    });
  }

  void cleanup_pass(int p) {
    const std::size_t fs = flag_row_, is = size_[0];
    for_each_stripe(size_, [&](const Stripe& s) {
      // An inactive full stripe has every column run-eligible until something in it becomes
      // significant, so run_eligible need not be asked until then.
      bool quiet = s.rows == kStripe && !state_.stripe_active(s.index);
      for (std::size_t x = 0; x < is; ++x) {
        const std::size_t f0 = s.f0 + x, i0 = s.i0 + x;
        std::size_t r = 0;
        if (s.rows == kStripe && (quiet || state_.run_eligible(f0))) {
          const std::uint32_t column = q_[i0] | q_[i0 + is] | q_[i0 + 2 * is] | q_[i0 + 3 * is];
          const bool any = (column >> p) & 1u;
          rc_.encode(any, state_.models[kRunContext]);
          if (!any) continue;
          std::size_t first = 0;  // first coefficient of the column with bit p set
          while (!((q_[i0 + first * is] >> p) & 1u)) ++first;
          rc_.encode_equiprobable(int(first >> 1));
          rc_.encode_equiprobable(int(first & 1));
          become_significant(f0 + first * fs, i0 + first * is, p, s.y0 + first, s.z);
          quiet = false;
          r = first + 1;
        }
        for (; r < s.rows; ++r) {
          const std::size_t f = f0 + r * fs;
          if (state_.flags(f) & (kSignificant | kVisited)) continue;
          code_significance(f, i0 + r * is, p, state_.significance_context(f), s.y0 + r, s.z);
        }
      }
    });
    state_.clear_visited();
  }

  std::span<const float> m_;
  std::span<const std::uint8_t> negative_;
  BlockState state_;
  Extent size_;           // block extent (a copy: flag writes would force reloads of state_'s)
  std::size_t flag_row_;  // flag positions between vertically adjacent coefficients
  double delta_;
  std::vector<std::uint32_t> q_;
  RangeEncoder rc_;
  double gain_ = 0.0;
};

}  // namespace

std::vector<std::uint8_t> EncodedBlock::codeword(int n) const {
  if (n <= 0) return {};
  return RangeEncoder::codeword(committed, passes[std::size_t(n - 1)]);
}

EncodedBlock encode_block(std::span<const float> magnitude, std::span<const std::uint8_t> negative,
                          const Extent& size, unsigned orientation, double delta) {
  if (magnitude.size() != size[0] * size[1] * size[2] || negative.size() != magnitude.size())
    throw std::invalid_argument("encode_block: coefficient count does not match the block size");
  return BitPlaneEncoder(magnitude, negative, size, orientation, delta).run();
}

}  // namespace pupwave
