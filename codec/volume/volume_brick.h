#pragma once
// Internal to the volume codec: brick geometry and the coding of one brick (3-D transform,
// quantizer, 3-D code-blocks through the bit-plane coder) and its inverse. The encoder and the
// decoder both reconstruct bricks through decode_brick, so the encoder sees exactly the values
// the decoder will produce (needed for the max-error guarantee).

#include <cstdint>
#include <span>
#include <vector>

#include "codec/entropy/block_encoder.h"
#include "codec/entropy/block_index.h"
#include "codec/entropy/codeblocks.h"
#include "transforms/transform1d.h"

namespace pupwave {

// A brick: a box of a grid's volume.
struct BrickBox {
  Extent offset{0, 0, 0};
  Extent size{1, 1, 1};
  std::size_t count() const { return size[0] * size[1] * size[2]; }
};

// Bricks of `dims` with edge `brick`, x fastest; edge bricks are smaller.
std::vector<BrickBox> brick_boxes(const Extent& dims, std::size_t brick);

// Parameters every brick of a stream shares.
struct BrickCoding {
  const Transform1D* transform = nullptr;
  int levels = 0;           // brick levels (clamped per brick by the engine's axis rules)
  std::size_t block = 32;   // code-block edge
  double delta = 0.4375;    // reconstruction offset inside a bin (index units)
  bool reversible = false;  // integer transform, steps 1, bit exact
  bool coef = false;        // non-embedded coefficient coder (coef_encoder.h), not the bit-plane coder
  // Encoder only: index = floor(|c| / step + rounding) (0: the dead-zone quantizer; the stream
  // only carries delta, so decoders need not know it).
  float rounding = 0.0f;
};

// Code-blocks of a brick of `size`, in partition_blocks order.
std::vector<CodeBlock> brick_blocks(const BrickCoding& c, const Extent& size);

// Quantizer step per band of a brick: base / synthesis norm (1 when reversible).
std::vector<float> brick_steps(const BrickCoding& c, const Extent& size, double base_step);

// Transform coefficients of a brick, coded block by block with every pass kept.
struct CodedBrick {
  std::vector<CodeBlock> blocks;
  std::vector<EncodedBlock> coded;
};

// Coefficient buffers reused from brick to brick: code_brick transforms a brick in one of them,
// and the encoder's check of its coding decodes into the same one (decode_brick_into) once the
// blocks are coded, so a worker holds one brick-sized coefficient array, not two.
struct BrickWork {
  std::vector<std::int32_t> integer;  // reversible coding
  std::vector<float> real;            // irreversible coding
};

// Forward-transforms a brick's samples (integers when reversible) and codes every code-block at
// `base_step`, the coefficients in `work`. S: std::uint8_t, std::uint16_t, float or double (the
// input's own type, as gather_box gives it; the transform runs in int32 or float either way).
template <class S>
CodedBrick code_brick(const BrickCoding& c, std::span<const S> samples, const Extent& size, double base_step,
                      BrickWork& work);
inline CodedBrick code_brick(const BrickCoding& c, std::span<const double> samples, const Extent& size,
                             double base_step) {
  BrickWork work;
  return code_brick<double>(c, samples, size, base_step, work);
}

// Irreversible coding in two steps, so that one forward transform serves several base steps:
// the float coefficients of a brick (in-place layout, into `coef`, resized), then their code at
// one base step.
template <class S>
void analyze_brick(const BrickCoding& c, std::span<const S> samples, const Extent& size,
                   std::vector<float>& coef);
inline std::vector<float> analyze_brick(const BrickCoding& c, std::span<const double> samples,
                                        const Extent& size) {
  std::vector<float> coef;
  analyze_brick<double>(c, samples, size, coef);
  return coef;
}
CodedBrick code_coefficients(const BrickCoding& c, std::span<const float> coef, const Extent& size,
                             double base_step);

// Statistics of a brick's quantization indices at one base step (the encoder's size model).
struct IndexStats {
  double significant = 0.0;  // indices >= 1
  double log2_sum = 0.0;     // sum of log2(index) over them
  double map_bits = 0.0;     // sum over code-blocks of n h(significant / n), n its coefficients
};

// What decode_brick returns at level 0 when every pass of every block is decoded, computed
// from the coefficients with the decoder's arithmetic (quantize, reconstruct at delta, scale,
// inverse transform) but without coding or decoding a bit, into `out` (float, as the decoder
// holds it before widening to double). Irreversible coding only. Fills `stats` when given.
void requantize_brick(const BrickCoding& c, std::span<const float> coef, const Extent& size, double base_step,
                      std::vector<float>& out, IndexStats* stats = nullptr);

// Decodes a brick from its block entries and codewords (one per block, passes as entries say),
// inverse-transforming down to `level` (the level-`level` coarse band scaled to sample units,
// extent level_extent(size, level), x fastest). Throws DecodeError for inconsistent entries.
std::vector<double> decode_brick(const BrickCoding& c, const Extent& size, double base_step,
                                 std::span<const BlockEntry> entries,
                                 std::span<const std::span<const std::uint8_t>> codewords, int level);

// decode_brick at level 0 into `out` (resized, its storage reused from brick to brick), before the
// widening to double: int32 when reversible, float otherwise (std::invalid_argument for the
// other), x fastest. The encoder checks its own bricks with it without brick-sized allocations.
template <class T>
void decode_brick_into(const BrickCoding& c, const Extent& size, double base_step,
                       std::span<const BlockEntry> entries,
                       std::span<const std::span<const std::uint8_t>> codewords, std::vector<T>& out);

}  // namespace pupwave
