#pragma once
// The code length (sum of -log2 p under the adaptive models) of one detail band's quantization
// indices under the lc coder's model (codec/entropy/lc_blocks.cpp: zero / unary bit length / two
// modelled mantissa bits / raw bits, two-rate adaptive probabilities, activity contexts from the
// causal neighbours and the parent), with knobs the real coder does not have, for the
// nonembedded_rd estimate (bench/nonembedded_rd.cpp): the parent's weight, the parent's 3x3
// neighbourhood, and greedy RDOQ (each index chosen among its nearest reconstruction point, the
// one below and zero by distortion + lambda x the bits the models would spend on it now).
// The model and activity contexts are lc_blocks.h's own; the binarisation is re-counted here.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "codec/entropy/lc_blocks.h"

namespace pupwave::estimate {

inline constexpr int kLengths = 31;

// Bits lc_blocks' model would spend on `bit` now.
inline double cost(const LcModel& m, int bit) {
  const std::uint32_t p = bit ? kProbabilityOne - m.p0() : m.p0();
  return -std::log2(double(p) / double(kProbabilityOne));
}

struct Models {
  std::array<LcModel, kLcActivityContexts> zero{};
  std::array<std::array<LcModel, kLengths>, kLcActivityContexts> length{}, first{};
  std::array<std::array<std::array<LcModel, 2>, kLengths>, kLcActivityContexts> second{};
  std::array<LcModel, 81> sign{};
};

// Bits of magnitude `mag` in context ctx; Update: adapt the models as the coder would.
template <bool Update>
double magnitude_bits(Models& m, int ctx, std::uint32_t mag, int planes) {
  auto code = [](LcModel& model, int bit) {
    const double c = cost(model, bit);
    if constexpr (Update) model.update(bit);
    return c;
  };
  double bits = code(m.zero[std::size_t(ctx)], mag != 0);
  if (mag == 0) return bits;
  const int n = int(std::bit_width(mag));
  int len = 1;
  for (; len < planes; ++len) {
    bits += code(m.length[std::size_t(ctx)][std::size_t(len)], len < n);
    if (len >= n) break;
  }
  len = n;
  if (len >= 2) bits += code(m.first[std::size_t(ctx)][std::size_t(len)], int((mag >> (len - 2)) & 1u));
  if (len >= 3) {
    const std::uint32_t top = (2u | ((mag >> (len - 2)) & 1u)) & 1u;
    bits += code(m.second[std::size_t(ctx)][std::size_t(len)][top], int((mag >> (len - 3)) & 1u));
  }
  if (len >= 4) bits += double(len - 3);
  return bits;
}

struct BandOptions {
  int parent_weight = 2;     // lc's; 0: no parent
  int scale = 1;             // the neighbour weights are multiplied by this (finer parent weights)
  bool parent_ring = false;  // also the parent's 8 neighbours (weight 1 each)
  bool parent_sign = false;  // the sign context also takes the parent's sign
  double lambda = 0.0;       // RDOQ: index-unit squared error per bit; 0: off
  double delta = 0.4375;     // reconstruction offset (index units)
};

// Parent band of a detail band: the signed indices one level coarser, same orientation.
struct ParentBand {
  const std::int32_t* origin = nullptr;
  std::size_t stride = 0, width = 0, height = 0;
};

// Codes (estimates) the band's indices q (w x h, x fastest; with RDOQ rewritten to the chosen
// ones, from the coefficients in index units `u`) and returns the bits.
inline double band_bits(std::vector<std::int32_t>& q, const std::vector<float>& u, std::size_t w,
                        std::size_t h, const ParentBand& parent, const BandOptions& o) {
  if (o.lambda > 0.0)  // start from the nearest reconstruction points; RDOQ only lowers them
    for (std::size_t k = 0; k < q.size(); ++k) {
      const auto n = std::int32_t(std::max(0.0, std::floor(std::fabs(double(u[k])) - o.delta + 0.5)));
      q[k] = u[k] < 0 ? -n : n;
    }
  std::uint32_t largest = 0;
  for (std::int32_t v : q) largest = std::max<std::uint32_t>(largest, std::uint32_t(std::abs(v)));
  const int planes = int(std::bit_width(largest));
  if (planes == 0) return 0.0;
  const std::size_t pad = 2, pw = w + 2 * pad;
  std::vector<std::uint32_t> mag((h + pad) * pw, 0u);
  std::vector<std::int8_t> sgn((h + pad) * pw, 0);
  auto models = std::make_unique<Models>();
  Models& m = *models;
  double bits = 0.0;
  auto pget = [&](std::size_t x, std::size_t y) {
    return parent.origin[std::min(y, parent.height - 1) * parent.stride + std::min(x, parent.width - 1)];
  };
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const std::size_t i = (y + pad) * pw + x + pad;
      const std::uint32_t* a = mag.data() + i;
      std::uint32_t s = std::uint32_t(o.scale) *
                        (4 * (a[-1] + a[-pw]) + 2 * (a[-pw - 1] + a[-pw + 1]) + a[-2] + a[-2 * pw]);
      int psign = 1;
      if (parent.origin && o.parent_weight > 0) {
        const std::size_t px = x >> 1, py = y >> 1;
        const std::int32_t p = pget(px, py);
        s += std::uint32_t(o.parent_weight) * std::uint32_t(std::abs(p));
        psign = p == 0 ? 1 : (p < 0 ? 0 : 2);
        if (o.parent_ring)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
              if ((dx || dy) && std::ptrdiff_t(px) + dx >= 0 && std::ptrdiff_t(py) + dy >= 0)
                s += std::uint32_t(std::abs(pget(px + std::size_t(dx), py + std::size_t(dy))));
      }
      const int ctx = lc_activity_context(s);
      const std::size_t k = y * w + x;
      const int sc = 3 * (sgn[i - 1] + 1) + (sgn[i - pw] + 1) + (o.parent_sign ? 9 * psign : 0);
      std::uint32_t v = std::uint32_t(std::abs(q[k]));
      if (o.lambda > 0.0) {  // greedy RDOQ among the nearest point, the one below and zero
        const double x0 = std::fabs(double(u[k]));
        const auto nearest = std::uint32_t(std::abs(q[k]));
        const int neg = u[k] < 0;
        double best = 1e300;
        for (std::uint32_t c : {nearest, nearest > 0 ? nearest - 1 : 0u, 0u}) {
          const double r = c == 0 ? 0.0 : double(c) + o.delta;
          const double rate =
              magnitude_bits<false>(m, ctx, c, planes) + (c ? cost(m.sign[std::size_t(sc)], neg) : 0.0);
          const double j = (x0 - r) * (x0 - r) + o.lambda * rate;
          if (j < best) {
            best = j;
            v = c;
          }
        }
        q[k] = neg ? -std::int32_t(v) : std::int32_t(v);
      }
      bits += magnitude_bits<true>(m, ctx, v, planes);
      if (v != 0) {
        LcModel& sm = m.sign[std::size_t(sc)];
        const int neg = q[k] < 0;
        bits += cost(sm, neg);
        sm.update(neg);
      }
      mag[i] = v;
      sgn[i] = std::int8_t(v == 0 ? 0 : (q[k] < 0 ? -1 : 1));
    }
  return bits;
}

}  // namespace pupwave::estimate
