#include "codec/volume/volume_brick.h"

#include <bit>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "codec/entropy/block_contexts.h"
#include "codec/entropy/block_decoder.h"
#include "codec/entropy/coef_contexts.h"
#include "codec/entropy/coef_decoder.h"
#include "codec/entropy/coef_encoder.h"
#include "codec/error.h"
#include "codec/image/image_components.h"
#include "codec/rate/quantizer.h"
#include "transforms/norms.h"
#include "transforms/separable.h"

namespace pupwave {

std::vector<BrickBox> brick_boxes(const Extent& dims, std::size_t brick) {
  if (brick == 0) throw std::invalid_argument("brick edge must be positive");
  Extent n{};
  for (int a = 0; a < 3; ++a) n[a] = (dims[a] + brick - 1) / brick;
  std::vector<BrickBox> boxes;
  boxes.reserve(n[0] * n[1] * n[2]);
  for (std::size_t z = 0; z < n[2]; ++z)
    for (std::size_t y = 0; y < n[1]; ++y)
      for (std::size_t x = 0; x < n[0]; ++x) {
        BrickBox b;
        const Extent at{x, y, z};
        for (int a = 0; a < 3; ++a) {
          b.offset[a] = at[a] * brick;
          b.size[a] = std::min(brick, dims[a] - b.offset[a]);
        }
        boxes.push_back(b);
      }
  return boxes;
}

std::vector<CodeBlock> brick_blocks(const BrickCoding& c, const Extent& size) {
  return partition_blocks(subbands(size, c.levels), c.levels, 1, {c.block, c.block, c.block});
}

std::vector<float> brick_steps(const BrickCoding& c, const Extent& size, double base_step) {
  const auto bands = subbands(size, c.levels);
  if (c.reversible) return std::vector<float>(bands.size(), 1.0f);
  const std::vector<double> norms = synthesis_norms(*c.transform, size, c.levels);
  const std::vector<double> unit{1.0};
  return subband_steps(base_step, norms, unit);
}

namespace {

// A block through the coefficient coder, as an EncodedBlock of one pass (none when all zero) so
// that the brick and stream code treats both coders alike.
EncodedBlock code_indices(std::span<const float> magnitude, std::span<const std::uint8_t> negative,
                          const Extent& size) {
  std::vector<std::uint32_t> index(magnitude.size());
  for (std::size_t i = 0; i < magnitude.size(); ++i) {
    const float m = magnitude[i];
    if (!(m < float(1u << kCoefMaxBits))) throw IndexRangeError("quantization index too large for the coder");
    index[i] = std::uint32_t(std::int32_t(m));  // as requantize_brick and the bit-plane coder truncate
  }
  CoefCodeword w = encode_coefficients(index, negative, size);
  EncodedBlock out;
  out.planes = w.bits;
  if (w.bits > 0) {
    out.passes.push_back(TruncationPoint{w.bytes.size(), {}});
    out.distortion_drop.push_back(0.0);
  }
  out.committed = std::move(w.bytes);
  return out;
}

// Index-unit magnitudes and signs of one block of transformed coefficients.
template <class T>
EncodedBlock code_one(const BrickCoding& c, std::span<const T> coef, const Extent& size, const CodeBlock& b,
                      float step) {
  std::vector<T> values(b.count());
  copy_block_out(coef.data(), size, b, values.data());
  std::vector<float> magnitude(b.count());
  std::vector<std::uint8_t> negative(b.count());
  quantize<T>(values, step, magnitude, negative);
  // The same float addition as requantize_row, so the encoder's prediction stays bit exact.
  if (c.rounding != 0.0f)
    for (float& m : magnitude) m += c.rounding;
  if (c.coef) return code_indices(magnitude, negative, b.size);
  return encode_block(magnitude, negative, b.size, b.orientation, c.delta);
}

}  // namespace

template <class S>
CodedBrick code_brick(const BrickCoding& c, std::span<const S> samples, const Extent& size, double base_step,
                      BrickWork& work) {
  if (!c.reversible) {
    analyze_brick(c, samples, size, work.real);
    return code_coefficients(c, work.real, size, base_step);
  }
  CodedBrick out;
  out.blocks = brick_blocks(c, size);
  out.coded.reserve(out.blocks.size());
  std::vector<std::int32_t>& coef = work.integer;
  coef.resize(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) coef[i] = std::int32_t(samples[i]);  // integers (checked)
  forward(*c.transform, coef.data(), size, c.levels);
  for (std::int32_t v : coef)
    if (v >= (1 << 24) || v <= -(1 << 24)) throw EncodeError("reversible coefficient out of range");
  for (const CodeBlock& b : out.blocks)
    out.coded.push_back(code_one(c, std::span<const std::int32_t>(coef), size, b, 1.0f));
  return out;
}

template <class S>
void analyze_brick(const BrickCoding& c, std::span<const S> samples, const Extent& size,
                   std::vector<float>& coef) {
  coef.resize(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) coef[i] = float(samples[i]);
  forward(*c.transform, coef.data(), size, c.levels);
}

template CodedBrick code_brick(const BrickCoding&, std::span<const std::uint8_t>, const Extent&, double,
                               BrickWork&);
template CodedBrick code_brick(const BrickCoding&, std::span<const std::uint16_t>, const Extent&, double,
                               BrickWork&);
template CodedBrick code_brick(const BrickCoding&, std::span<const float>, const Extent&, double, BrickWork&);
template CodedBrick code_brick(const BrickCoding&, std::span<const double>, const Extent&, double,
                               BrickWork&);
template void analyze_brick(const BrickCoding&, std::span<const std::uint8_t>, const Extent&,
                            std::vector<float>&);
template void analyze_brick(const BrickCoding&, std::span<const std::uint16_t>, const Extent&,
                            std::vector<float>&);
template void analyze_brick(const BrickCoding&, std::span<const float>, const Extent&, std::vector<float>&);
template void analyze_brick(const BrickCoding&, std::span<const double>, const Extent&, std::vector<float>&);

CodedBrick code_coefficients(const BrickCoding& c, std::span<const float> coef, const Extent& size,
                             double base_step) {
  CodedBrick out;
  out.blocks = brick_blocks(c, size);
  const std::vector<float> steps = brick_steps(c, size, base_step);
  out.coded.reserve(out.blocks.size());
  for (const CodeBlock& b : out.blocks) out.coded.push_back(code_one(c, coef, size, b, steps[b.band]));
  return out;
}

namespace {

// Dequantized signed indices of a block, into its place in the brick: reconstruct()'s arithmetic
// for a fully decoded coefficient (index + delta in double, then float, times the step), so
// requantize_brick's values hold for this coder too.
template <class T>
void place_indices(std::span<const std::int32_t> indices, const BrickCoding& c, const Extent& size,
                   const CodeBlock& b, float step, std::vector<T>& coef) {
  std::size_t k = 0;
  for (std::size_t z = 0; z < b.size[2]; ++z)
    for (std::size_t y = 0; y < b.size[1]; ++y) {
      T* row = coef.data() + b.offset[0] + size[0] * ((b.offset[1] + y) + size[1] * (b.offset[2] + z));
      for (std::size_t x = 0; x < b.size[0]; ++x, ++k) {
        const std::int32_t q = indices[k];
        if constexpr (std::is_floating_point_v<T>) {
          const float r = float(double(q < 0 ? -std::int64_t(q) : q) + c.delta);
          row[x] = q == 0 ? 0.0f : (q < 0 ? -r : r) * step;
        } else {
          row[x] = T(q);
        }
      }
    }
}

// Dequantized coefficients of every block the level needs, in the brick's in-place layout, into
// `coef` (resized; its storage reused).
template <class T>
void dequantize_brick(const BrickCoding& c, const Extent& size, std::span<const float> steps,
                      std::span<const BlockEntry> entries,
                      std::span<const std::span<const std::uint8_t>> codewords, int level,
                      std::vector<T>& coef) {
  const auto blocks = brick_blocks(c, size);
  require_stream(entries.size() == blocks.size() && codewords.size() == blocks.size(), "brick block count");
  coef.assign(size[0] * size[1] * size[2], T(0));
  std::vector<std::int32_t> indices;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const CodeBlock& b = blocks[i];
    if (b.resolution > c.levels - level || entries[i].passes == 0) continue;
    if (c.coef) {
      require_stream(entries[i].passes == 1, "volume stream: a coefficient-coded block has one pass");
      indices.resize(b.count());
      decode_coefficients(codewords[i], entries[i].planes, b.size, indices);
      place_indices<T>(indices, c, size, b, steps[b.band], coef);
      continue;
    }
    const DecodedBlock d =
        decode_block(codewords[i], entries[i].planes, entries[i].passes, b.size, b.orientation);
    // Straight into the block's place in the brick (no block-sized copy in between).
    std::size_t k = 0;
    for (std::size_t z = 0; z < b.size[2]; ++z)
      for (std::size_t y = 0; y < b.size[1]; ++y) {
        T* row = coef.data() + b.offset[0] + size[0] * ((b.offset[1] + y) + size[1] * (b.offset[2] + z));
        for (std::size_t x = 0; x < b.size[0]; ++x, ++k) {
          const float v = reconstruct(d, k, c.delta, c.reversible);
          if constexpr (std::is_floating_point_v<T>)
            row[x] = v * steps[b.band];
          else
            row[x] = T(v);
        }
      }
  }
}

// The low corner (extent `part`) of an array laid out over `size`, as double times `gain`.
template <class T>
std::vector<double> corner(const std::vector<T>& data, const Extent& size, const Extent& part, double gain) {
  std::vector<double> out;
  out.reserve(part[0] * part[1] * part[2]);
  for (std::size_t z = 0; z < part[2]; ++z)
    for (std::size_t y = 0; y < part[1]; ++y)
      for (std::size_t x = 0; x < part[0]; ++x)
        out.push_back(double(data[x + size[0] * (y + size[1] * z)]) / gain);
  return out;
}

}  // namespace

std::vector<double> decode_brick(const BrickCoding& c, const Extent& size, double base_step,
                                 std::span<const BlockEntry> entries,
                                 std::span<const std::span<const std::uint8_t>> codewords, int level) {
  const Extent part = level_extent(size, level);
  const std::vector<float> steps = brick_steps(c, size, base_step);
  const double gain = level > 0 ? coarse_gain(*c.transform, size, level) : 1.0;
  if (c.reversible) {
    std::vector<std::int32_t> coef;
    dequantize_brick<std::int32_t>(c, size, steps, entries, codewords, level, coef);
    inverse(*c.transform, coef.data(), size, c.levels, level);
    return corner(coef, size, part, gain);
  }
  std::vector<float> coef;
  dequantize_brick<float>(c, size, steps, entries, codewords, level, coef);
  inverse(*c.transform, coef.data(), size, c.levels, level);
  return corner(coef, size, part, gain);
}

template <class T>
void decode_brick_into(const BrickCoding& c, const Extent& size, double base_step,
                       std::span<const BlockEntry> entries,
                       std::span<const std::span<const std::uint8_t>> codewords, std::vector<T>& out) {
  if (c.reversible != std::is_integral_v<T>)
    throw std::invalid_argument("decode_brick_into: int32 output for reversible coding, float otherwise");
  dequantize_brick<T>(c, size, brick_steps(c, size, base_step), entries, codewords, 0, out);
  inverse(*c.transform, out.data(), size, c.levels, 0);
}

template void decode_brick_into(const BrickCoding&, const Extent&, double, std::span<const BlockEntry>,
                                std::span<const std::span<const std::uint8_t>>, std::vector<std::int32_t>&);
template void decode_brick_into(const BrickCoding&, const Extent&, double, std::span<const BlockEntry>,
                                std::span<const std::span<const std::uint8_t>>, std::vector<float>&);

}  // namespace pupwave
