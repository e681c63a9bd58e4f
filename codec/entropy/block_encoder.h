#pragma once
// Bit-plane encoder of one code-block (EBCOT class): three coding passes per bit-plane
// (significance propagation, magnitude refinement, cleanup with run mode), each a possible
// truncation point with its exact codeword size and the distortion it removes.

#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "codec/entropy/range_encoder.h"
#include "transforms/subband.h"

namespace pupwave {

struct ContextTally;

// A quantization index beyond the coder's 2^kMaxBitPlanes range: coefficients too large for the
// step, as unstable filter banks produce after many levels. Callers may retry with fewer levels.
class IndexRangeError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The coded form of one block at every truncation point.
struct EncodedBlock {
  int planes = 0;                       // magnitude bit-planes (0: all coefficients zero)
  std::vector<std::uint8_t> committed;  // the stream shared by all truncation points
  std::vector<TruncationPoint> passes;  // codeword after each pass
  std::vector<double> distortion_drop;  // squared error removed by each pass (index units)
  double initial_distortion = 0.0;      // squared error with nothing coded (index units)

  int pass_count() const { return int(passes.size()); }
  // Size in bytes of the codeword that decodes the first n passes (0 for n == 0).
  std::size_t size(int n) const { return n > 0 ? passes[std::size_t(n - 1)].size() : 0; }
  // The codeword that decodes the first n passes.
  std::vector<std::uint8_t> codeword(int n) const;
};

// Encodes a block of coefficients given in quantizer index units: `magnitude[i]` >= 0 is
// |coefficient| / step (its integer part is the quantization index), `negative[i]` the sign,
// in block order (x fastest, then y, then z) over `size`. `orientation` is the subband's
// (bit a = high-pass along axis a). `delta` (0..1) is the reconstruction offset inside a
// quantization bin the decoder will use; the distortion estimates assume it. A non-null `tally`
// (prior training, block_tally.h) gets the block's first bits per context added.
// Throws IndexRangeError (a std::invalid_argument) if an index reaches 2^kMaxBitPlanes.
EncodedBlock encode_block(std::span<const float> magnitude, std::span<const std::uint8_t> negative,
                          const Extent& size, unsigned orientation, double delta,
                          ContextTally* tally = nullptr);

// A block coded with every pass as one codeword (no truncation points kept).
struct WholeBlock {
  int planes = 0;
  int passes = 0;
  std::vector<std::uint8_t> codeword;  // EncodedBlock::codeword(passes) of encode_block
};

// The same codeword as encode_block's with every pass, without the truncation points and
// distortion estimates (lossless, fixed-step and trial encodes need only the codeword).
WholeBlock encode_block_whole(std::span<const float> magnitude, std::span<const std::uint8_t> negative,
                              const Extent& size, unsigned orientation, double delta,
                              ContextTally* tally = nullptr);

}  // namespace pupwave
