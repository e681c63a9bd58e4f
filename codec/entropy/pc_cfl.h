#pragma once
// Chroma from luma in the wavelet domain (AV1's CfL, per detail block) for the pc coder
// (docs/bitstream.md, "Parent-context coefficient coder"): a Cb detail coefficient is predicted
// as a x L, a Cr one as a x L + b x Cb, where L and Cb are the decoded (dequantized) co-located
// coefficients of the same band and a, b are per-block weights code / 16 in [-2, 2] chosen by the
// encoder (least squares) and coded at the head of the block's codeword (pc_blocks.h, PcCfl). The
// block's indices then quantize the residual. The ICT leaves the chroma bands of photographs
// correlated with luma and with each other band by band, with a sign and size that vary by image.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "codec/entropy/pc_blocks.h"
#include "codec/entropy/pc_groups.h"

namespace pupwave {

inline constexpr int kPcCflDenominator = 16;
inline constexpr int kPcCflMaxCode = 2 * kPcCflDenominator;

// Whether block b (of an image with `components` components) is predicted: the Cb and Cr detail
// blocks (the coarse band's are not: its values are offsets, not co-varying detail).
inline bool pc_cfl_applies(std::size_t component, unsigned orientation, std::size_t components) {
  return pc_has_luma(component, components) && orientation != 0;
}
inline bool pc_cfl_applies(const CodeBlock& b, std::size_t components) {
  return pc_cfl_applies(b.component, b.orientation, components);
}

// The number of weights block b codes: 1 for Cb (luma's), 2 for Cr (luma's and Cb's).
inline int pc_cfl_count(const CodeBlock& b) { return b.component == 2 ? 2 : 1; }

// The prediction of a coefficient from its decoded luma `l` and Cb `cb` (Cr only). Encoder and
// decoder both use this one expression, so their floats agree.
inline float pc_cfl_predict(const PcCfl& k, float l, float cb) {
  float p = float(k.code[0]) * (1.0f / kPcCflDenominator) * l;
  if (k.count == 2) p += float(k.code[1]) * (1.0f / kPcCflDenominator) * cb;
  return p;
}

// A weight rounded to a code in [-32, 32].
inline int pc_cfl_code(double weight) {
  if (!std::isfinite(weight)) return 0;
  return int(
      std::clamp(std::round(weight * kPcCflDenominator), double(-kPcCflMaxCode), double(kPcCflMaxCode)));
}

// Least-squares sums of a block: x1 = L, x2 = Cb, y = the coefficient.
struct PcCflSums {
  double x1x1 = 0, x1x2 = 0, x2x2 = 0, x1y = 0, x2y = 0;
  void add(double x1, double x2, double y) {
    x1x1 += x1 * x1, x1x2 += x1 * x2, x2x2 += x2 * x2, x1y += x1 * y, x2y += x2 * y;
  }
};

// The least-squares weights' codes for `count` regressors (1: L; 2: L and Cb); 0 where the
// regressors carry nothing (all zero, or collinear).
inline PcCfl pc_cfl_fit(const PcCflSums& s, int count) {
  PcCfl k;
  k.count = count;
  if (count == 1) {
    if (s.x1x1 > 0.0) k.code[0] = pc_cfl_code(s.x1y / s.x1x1);
    return k;
  }
  const double det = s.x1x1 * s.x2x2 - s.x1x2 * s.x1x2;
  if (det > 1e-9 * s.x1x1 * s.x2x2 && det > 0.0) {
    k.code[0] = pc_cfl_code((s.x1y * s.x2x2 - s.x2y * s.x1x2) / det);
    k.code[1] = pc_cfl_code((s.x1x1 * s.x2y - s.x1x2 * s.x1y) / det);
  } else if (s.x1x1 > 0.0) {
    k.code[0] = pc_cfl_code(s.x1y / s.x1x1);
  } else if (s.x2x2 > 0.0) {
    k.code[1] = pc_cfl_code(s.x2y / s.x2x2);
  }
  return k;
}

// Whether a prediction is all zero.
inline bool pc_cfl_none(const PcCfl& k) { return k.code[0] == 0 && (k.count < 2 || k.code[1] == 0); }

// The samples pc_cfl_proxy_cost reads of a block at most (about): a decision between two sums
// over a band needs no more, and a large band is read at an odd stride (never in step with its rows).
inline constexpr std::size_t kPcCflProxySamples = 8192;

// The encoder's cheap estimate of what coding values x (index units: coefficient / step) costs
// in RDOQ's measure (squared index-unit error + lambda x bits), without coding them: the error
// of rounding to the reconstruction points (0 and |q| + delta), and as bits a quarter of the
// zero-order entropy of the magnitude classes (bit length of |q|) with their low bits and signs,
// plus 2 bits per non-zero nearest index. The weights were fitted on the chroma blocks of the
// first search pass of the training photographs at 0.125-2 bpp, as the ones that best agree with
// coding both ways: the contexts code zeros far
// below their zero-order cost, so the count of non-zeros carries most of the rate. A block of
// more than 2 x kPcCflProxySamples values is estimated from every stride-th one (a sum in scale).
inline double pc_cfl_proxy_cost(std::span<const float> x, double delta, double lambda) {
  std::array<double, 34> classes{};
  double error = 0.0, low_bits = 0.0, nonzero = 0.0, n = 0.0;
  const std::size_t stride = (x.size() / kPcCflProxySamples) | 1;
  for (std::size_t i = 0; i < x.size(); i += stride) {
    const float f = std::abs(x[i]);
    n += 1.0;
    if (f < 0.5f) {  // the common case: index 0, class 0 (counted from n below)
      error += double(f) * double(f);
      continue;
    }
    const double a = double(f);
    const double q = std::min(std::floor(a - delta + 0.5), 2147483647.0);
    const double r = q > 0.0 ? q + delta : 0.0;
    error += (a - r) * (a - r);
    const int c = std::bit_width(std::uint32_t(q));  // 0 for zero
    low_bits += double(c);                           // c - 1 low bits and the sign
    classes[std::size_t(c)] += 1.0;
    nonzero += 1.0;  // a >= 0.5: a non-zero nearest index
  }
  classes[0] += n - nonzero;  // the values under half a step (the others counted their class)
  double entropy = 0.0;
  for (const double m : classes)
    if (m > 0.0) entropy -= m * std::log2(m / n);
  return error + lambda * (0.25 * (entropy + low_bits) + 2.0 * nonzero);
}

// Whether a chroma block is coded with its prediction: when its residual ur (index units) is
// estimated cheaper than its values u (pc_cfl_proxy_cost), so the encoder codes it once.
inline bool pc_cfl_pays(std::span<const float> u, std::span<const float> ur, double delta, double lambda) {
  return pc_cfl_proxy_cost(ur, delta, lambda) < pc_cfl_proxy_cost(u, delta, lambda);
}

}  // namespace pupwave
