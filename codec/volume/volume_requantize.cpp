// requantize_brick (volume_brick.h): the max-error encoder's evaluation of a candidate step.
#include <bit>
#include <cmath>

#include "codec/entropy/block_contexts.h"
#include "codec/entropy/block_encoder.h"
#include "codec/error.h"
#include "codec/volume/volume_brick.h"
#include "transforms/separable.h"

namespace pupwave {

namespace {

// log2 of x >= 1 within 0.005: exponent plus a quadratic in the mantissa (the model needs no more).
float approximate_log2(float x) {
  const auto bits = std::bit_cast<std::uint32_t>(x);
  const float f = std::bit_cast<float>((bits & 0x7fffffu) | 0x3f800000u) - 1.0f;
  return float(int(bits >> 23) - 127) + f * (1.3466f - 0.3466f * f);
}

double binary_entropy_bits(double k, double n) {
  if (k <= 0.0 || k >= n) return 0.0;
  const double p = k / n;
  return -n * (p * std::log2(p) + (1.0 - p) * std::log2(1.0 - p));
}

// One row of a code-block: the reconstruction into out and log2(index) into lg (exactly 0 for an
// insignificant index, log2(1)); returns how many indices are significant and ORs into too_large
// whether one is out of the block coder's range. No float sum here, so that the loop vectorises;
// the same float and double operations as quantize() and reconstruct(), so the values are identical.
std::size_t requantize_row(const float* coef, float* out, float* lg, std::size_t n, float inv, float step,
                           double delta, float rounding, std::uint32_t& too_large) {
  std::uint32_t count = 0, large = 0;
  for (std::size_t x = 0; x < n; ++x) {
    const float v = coef[x];
    // |v| * inv + rounding, as code_one; a NaN or -0 gives index 0 either way (rounding < 1).
    const float m = std::fabs(v) * inv + rounding;
    const std::uint32_t in_range = m < float(1u << kMaxBitPlanes) ? 1u : 0u;  // 0 for NaN too
    large |= in_range ^ 1u;
    const std::int32_t q =
        std::int32_t(std::bit_cast<float>(std::bit_cast<std::uint32_t>(m) & (0u - in_range)));
    const std::uint32_t sig = q != 0 ? 1u : 0u;  // m >= 1
    count += sig;
    lg[x] = approximate_log2(float(q > 1 ? q : 1));  // log2(1) is exactly 0 (std::max stops vectorising)
    // reconstruct() of a fully decoded coefficient: index + delta in double, then float, with
    // v's sign (v < 0 whenever the index is significant and its sign bit is set); insignificant:
    // the decoder's reconstruct() gives +0.
    const float r = float(double(q) + delta);
    const std::uint32_t sign = std::bit_cast<std::uint32_t>(v) & 0x80000000u;
    const float signed_r = std::bit_cast<float>(std::bit_cast<std::uint32_t>(r) ^ sign) * step;
    out[x] = std::bit_cast<float>(std::bit_cast<std::uint32_t>(signed_r) & (0u - sig));
  }
  too_large |= large;
  return count;
}

}  // namespace

void requantize_brick(const BrickCoding& c, std::span<const float> coef, const Extent& size, double base_step,
                      std::vector<float>& out, IndexStats* stats) {
  const std::vector<float> steps = brick_steps(c, size, base_step);
  out.resize(coef.size());
  std::vector<float> lg(size[0]);
  for (const CodeBlock& b : brick_blocks(c, size)) {
    const float step = steps[b.band];
    const float inv = 1.0f / step;  // as quantize() computes the index
    std::size_t significant = 0;
    float log2_sum = 0.0f;
    std::uint32_t too_large = 0;
    for (std::size_t z = 0; z < b.size[2]; ++z)
      for (std::size_t y = 0; y < b.size[1]; ++y) {
        const std::size_t row = b.offset[0] + size[0] * ((b.offset[1] + y) + size[1] * (b.offset[2] + z));
        significant += requantize_row(coef.data() + row, out.data() + row, lg.data(), b.size[0], inv, step,
                                      c.delta, c.rounding, too_large);
        // In scan order, as the stream's rate model was fitted: a float sum depends on its order.
        for (std::size_t x = 0; x < b.size[0]; ++x) log2_sum += lg[x];
      }
    if (too_large != 0) throw IndexRangeError("quantization index too large for the block coder");
    if (stats == nullptr) continue;
    stats->significant += double(significant);
    stats->log2_sum += double(log2_sum);
    stats->map_bits += binary_entropy_bits(double(significant), double(b.count()));
  }
  inverse(*c.transform, out.data(), size, c.levels, 0);
}

}  // namespace pupwave
