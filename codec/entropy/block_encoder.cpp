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

  // Codes bit-plane p of a coefficient not yet significant; returns the coded bit.
  int code_significance(std::size_t p_flag, std::size_t i, int p, int ctx) {
    const int bit = int((q_[i] >> p) & 1u);
    rc_.encode(bit, state_.models[std::size_t(ctx)]);
    if (bit) become_significant(p_flag, i, p);
    return bit;
  }
  void become_significant(std::size_t p_flag, std::size_t i, int p) {
    const auto [ctx, flip] = state_.sign_context(p_flag);
    rc_.encode(int(negative_[i] != 0) ^ flip, state_.models[std::size_t(ctx)]);
    state_.make_significant(p_flag, negative_[i] != 0);
    add_gain(m_[i], 0.0, reconstruction(q_[i], p));
  }

  void significance_pass(int p) {
    const std::size_t fs = flag_row_, is = size_[0];
    for_each_stripe_column(size_, [&](std::size_t f0, std::size_t i0, std::size_t rows) {
      for (std::size_t r = 0; r < rows; ++r) {
        const std::size_t f = f0 + r * fs;
        if (state_.flags(f) & kSignificant) continue;
        const int ctx = state_.significance_context(f);
        if (ctx == 0) continue;
        code_significance(f, i0 + r * is, p, ctx);
        state_.flags(f) |= kVisited;
      }
    });
  }

  void refinement_pass(int p) {
    const std::size_t fs = flag_row_, is = size_[0];
    for_each_stripe_column(size_, [&](std::size_t f0, std::size_t i0, std::size_t rows) {
      for (std::size_t r = 0; r < rows; ++r) {
        const std::size_t f = f0 + r * fs;
        if ((state_.flags(f) & (kSignificant | kVisited)) != kSignificant) continue;
        const std::size_t i = i0 + r * is;
        rc_.encode(int((q_[i] >> p) & 1u), state_.models[std::size_t(state_.refinement_context(f))]);
        state_.flags(f) |= kRefined;
        add_gain(m_[i], reconstruction(q_[i], p + 1), reconstruction(q_[i], p));
      }
    });
  }

  void cleanup_pass(int p) {
    const std::size_t fs = flag_row_, is = size_[0];
    for_each_stripe_column(size_, [&](std::size_t f0, std::size_t i0, std::size_t rows) {
      std::size_t r = 0;
      if (rows == kStripe && state_.run_eligible(f0)) {
        std::size_t first = kStripe;  // first coefficient of the column with bit p set
        for (std::size_t k = 0; k < kStripe && first == kStripe; ++k)
          if ((q_[i0 + k * is] >> p) & 1u) first = k;
        rc_.encode(first != kStripe, state_.models[kRunContext]);
        if (first == kStripe) return;
        rc_.encode_equiprobable(int(first >> 1));
        rc_.encode_equiprobable(int(first & 1));
        become_significant(f0 + first * fs, i0 + first * is, p);
        r = first + 1;
      }
      for (; r < rows; ++r) {
        const std::size_t f = f0 + r * fs;
        if (state_.flags(f) & (kSignificant | kVisited)) continue;
        code_significance(f, i0 + r * is, p, state_.significance_context(f));
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
