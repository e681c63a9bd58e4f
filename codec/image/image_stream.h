#pragma once
// The image stream (docs/bitstream.md): a signature, then chunks
//   HEAD (image and coding parameters), INDX (code-block index), DATA x (levels + 1)
// each framed as tag, length, payload, CRC-32 by the chunk layer every stream kind shares
// (codec/format/chunks.h). DATA chunk r holds the code-blocks of
// resolution r, so a reduced-resolution decode reads (and checks) only a prefix.
// The parser treats its input as hostile: every field and length is validated before use.

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "codec/entropy/block_index.h"
#include "codec/entropy/codeblocks.h"
#include "codec/entropy/coder_traits.h"
#include "codec/format/decode_limits.h"
#include "codec/image/colour.h"
#include "codec/image/image.h"
#include "transforms/subband.h"
#include "transforms/transform1d.h"

namespace pupwave {

// Version 2: HEAD gained the transfer and flags bytes; optional META and NFIN chunks.
// Version 3: the bit-plane block coder's far-neighbour contexts and trained priors.
// Version 4: the priors retrained on photographs other than the scored ones, each with its own
// weight (codec/entropy/ctx_priors.h).
// Version 5: the pc coder's contexts (parent's neighbours, luma and Cb parents, class-0 rate); the
// other coders' streams are unchanged, so version 4 streams of coders other than pc still decode.
// Version 6: the pc coder predicts chroma detail blocks from luma (and Cr from Cb), and its models
// start from trained states per band class (pc_priors.h); the other coders' streams are
// unchanged, so their version 4 and 5 streams still decode.
inline constexpr std::uint8_t kStreamVersion = 6;
inline constexpr std::uint8_t kOldestStreamVersion = 4;
// Caps that keep a hostile header from demanding unbounded memory.
inline constexpr std::size_t kMaxAxisExtent = std::size_t(1) << 16;
inline constexpr std::size_t kMaxTotalSamples = std::size_t(1) << 31;
inline constexpr std::size_t kMaxSpecLength = 4096;
inline constexpr std::uint32_t kMaxChannels = 64;

// Domain the samples are coded in (float images): see codec/image/transfer.h. log2_adaptive is
// log2 with an offset chosen per image (StreamHeader::transfer_offset_log2).
enum class Transfer : std::uint8_t { linear = 0, log2 = 1, log2_adaptive = 2 };
// The log2 transfer's offset a = 2^kLogOffsetLog2 (the smallest normal half float), and the
// largest offset exponent log2_adaptive may signal (a = 2^16, above the half range).
inline constexpr int kLogOffsetLog2 = -14;
inline constexpr int kMaxAdaptiveOffsetLog2 = 16;

// A sample the coded planes cannot hold (NaN, +-infinity), restored exactly after decoding.
struct NonFiniteSample {
  std::uint32_t channel = 0;
  std::uint64_t index = 0;  // y * width + x
  std::uint32_t bits = 0;   // binary32 bits of the value
};

struct StreamHeader {
  Extent dims{1, 1, 1};        // width, height, depth (depth 1 for images)
  std::uint32_t channels = 1;  // 1..kMaxChannels
  SampleType type = SampleType::u8;
  ColourTransform colour = ColourTransform::none;
  EntropyCoder entropy = EntropyCoder::ebcot;
  bool reversible = false;  // integer transform, no quantization: lossless
  int levels = 0;
  Extent block_log2{6, 6, 0};            // code-block extent 2^k per axis
  double delta = 0.375;                  // reconstruction offset in a bin (index units), [0, 1)
  std::string spec;                      // transform spec for make_transform
  std::vector<float> steps;              // quantizer step per (component, band): c * bands + b
  Transfer transfer = Transfer::linear;  // float images: coded as transfer(x), inverted on decode
  int transfer_offset_log2 =
      kLogOffsetLog2;        // log2 of the log transfers' offset a (signalled for log2_adaptive)
  bool nonnegative = false;  // every input sample was >= 0: decoded values are clamped at 0
  ImageMetadata metadata;    // META chunk (written when not empty)
  std::vector<NonFiniteSample> nonfinite;  // NFIN chunk (written when not empty)

  Extent block_size() const {
    return {std::size_t(1) << block_log2[0], std::size_t(1) << block_log2[1],
            std::size_t(1) << block_log2[2]};
  }
};

// Assembles a file: header, index of all blocks, and one data payload per resolution.
std::vector<std::uint8_t> write_container(const StreamHeader& header, std::span<const BlockEntry> index,
                                          const std::vector<std::vector<std::uint8_t>>& resolution_data);

// Appends resolution r's DATA payload to the stream being written.
using PayloadWriter = std::function<void(std::size_t r, std::vector<std::uint8_t>& out)>;

// write_container with each payload appended in place by `append` (resolution_sizes[r] bytes
// for resolution r; a different count throws std::logic_error), so a large stream's payloads
// are never held beside it.
std::vector<std::uint8_t> write_container(const StreamHeader& header, std::span<const BlockEntry> index,
                                          std::span<const std::size_t> resolution_sizes,
                                          const PayloadWriter& append);

// Size in bytes write_container would produce for these parts (without building it).
std::size_t container_size(const StreamHeader& header, std::size_t index_bytes, std::size_t data_bytes);

struct ParsedStream {
  StreamHeader header;
  std::vector<Subband> bands;        // subbands(dims, levels)
  std::vector<CodeBlock> blocks;     // partition_blocks order, of the resolutions read only
  std::vector<BlockEntry> index;     // one per block
  std::vector<std::size_t> offsets;  // codeword start in its DATA payload
  std::vector<std::span<const std::uint8_t>> resolution_data;  // DATA payloads read (0..max)

  // Codeword of block i (whose resolution must have been read).
  std::span<const std::uint8_t> codeword(std::size_t i) const {
    return resolution_data[std::size_t(blocks[i].resolution)].subspan(offsets[i], index[i].length);
  }
};

// Parses and validates a stream, reading the DATA chunks and index entries of all but the
// `drop_levels` finest resolutions (those a decode at 1/2^drop_levels size needs). Throws
// DecodeError for the reason for any inconsistency or when the decoded size exceeds
// `limits`, std::invalid_argument when drop_levels exceeds the levels. The transform spec is
// checked against the stream bounds but no filter bank is designed (make_stream_transform).
ParsedStream parse_container(std::span<const std::uint8_t> bytes, int drop_levels = 0,
                             const DecodeLimits& limits = {});

// The transform of a parsed header (designs a PUPs bank within the stream bounds); throws
// DecodeError when it cannot be built or a reversible stream names an irreversible one.
Transform1DPtr make_stream_transform(const StreamHeader& header);

// Human-readable description of a stream's header fields and chunk sizes (for `pupwave info`).
// Throws DecodeError for a stream it cannot parse.
std::string describe_stream(std::span<const std::uint8_t> bytes);

}  // namespace pupwave
