#pragma once
// Internal to the volume codec: the "PUPV" stream (docs/bitstream.md, Volumes). A signature,
// then CRC-guarded chunks: VHDR (coding parameters and grid descriptions), MASK (per sparse
// grid: voxel states and inactive values), BRIK (one per coded brick). Parsing treats its input
// as hostile: every field is validated before use and sizes are capped.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "codec/entropy/block_index.h"
#include "codec/format/decode_limits.h"
#include "codec/volume/volume.h"
#include "codec/volume/volume_box_mask.h"

namespace pupwave {

// Version 2: chunks framed by codec/format/chunks.h (the CRC also covers the length field).
// Version 3: sparse-native grids (layout 2) with a BLKS chunk of blocks and tiles, and opaque
// grids (layout 3) carried as OpenVDB serialises them in an OPAQ chunk.
// Version 4: VHDR's coder byte; max-error streams code their blocks with the non-embedded
// coefficient coder (coef_encoder.h); the bit-plane block coder's far-neighbour contexts and
// trained priors (image version 3's coder), so version 3 streams are refused.
// Version 5: the bit-plane block coder's priors retrained, as image version 4.
// Version 6: a brick's outlier corrections range coded with adaptive models, not a zstd frame
// of varints (volume_outliers.cpp).
// Version 7: dense grids with missing values (layout 4: a MASK chunk whose inactive voxels are the
// missing ones, decoded as a dense grid), and the inactive values of MASK and BLKS as a zstd frame.
inline constexpr std::uint8_t kVolumeStreamVersion = 7;
// The oldest version this decoder reads (version 6 differs only by what version 7 added).
inline constexpr std::uint8_t kOldestVolumeStreamVersion = 6;
inline constexpr char kVolumeSignature[5] = "PUPV";
// Caps that keep a hostile header from demanding unbounded memory.
inline constexpr std::size_t kMaxVolumeAxis = std::size_t(1) << 20;
inline constexpr std::size_t kMaxVolumeVoxels = std::size_t(1) << 31;
inline constexpr std::size_t kMaxVolumeGrids = 1024;

// Voxel states of a sparse grid's MASK chunk (one byte per voxel, zstd-compressed).
enum class VoxelState : std::uint8_t {
  inactive_background = 0,
  active = 1,
  inactive_negative = 2,
  inactive_other = 3
};

struct VolumeStreamHeader {
  std::string spec;  // transform spec for make_transform
  bool reversible = false;
  int levels = 0;                  // per brick
  int brick_log2 = 6;              // brick edge 2^k
  int block_log2 = 5;              // code-block edge 2^k
  std::uint8_t coder = 0;          // 0 bit-plane coder, 1 coefficient coder (irreversible only)
  double delta = 0.4375;           // reconstruction offset in a bin (index units)
  double max_error = 0.0;          // bound the outlier corrections were quantized to (0: none)
  std::uint32_t brick_chunks = 0;  // BRIK chunks that follow (all grids)
  std::vector<VolumeGrid>
      grids;  // descriptions: volume.dims/type/background, active non-empty when sparse (size 1)
  std::vector<std::uint8_t> blocked;  // per grid: 1 sparse-native grid (BLKS chunk), 2 opaque (OPAQ chunk)
  // Per grid: 1 when a dense grid with missing values (its MASK's inactive voxels: NaN, infinities
  // or the fill value, kept exactly); grids[g].volume then carries the sparse marker, as a
  // sparse box does, and decoders return it dense.
  std::vector<std::uint8_t> missing;
  std::uint8_t version = kVolumeStreamVersion;  // as parsed (writers write the current one)
  bool has_missing(std::size_t g) const { return g < missing.size() && missing[g] != 0; }
};

// Per sparse grid: the state of every box voxel and the values of inactive_other voxels.
struct MaskChunk {
  std::vector<std::uint8_t> states;
  std::vector<double> other_values;
};

// Per sparse-native grid: block geometry (volume.dims only), tiles, and the states of the voxels
// of every block in order (with the values of inactive_other voxels).
struct BlocksChunk {
  std::vector<VolumeBlock> blocks;
  std::vector<VolumeTile> tiles;
  MaskChunk mask;
};

struct BrickChunk {
  std::uint32_t grid = 0;
  std::uint32_t brick = 0;  // index into brick_boxes(dims, brick edge), of each block in turn
  double base_step = 1.0;
  std::vector<BlockEntry> entries;
  // The blocks' codewords in order, one per block (parsed: into the stream); the writer only
  // concatenates them, so an encoder may give a block's codeword in several pieces.
  std::vector<std::span<const std::uint8_t>> codewords;
  std::vector<std::uint8_t> outliers;  // volume_outliers.h encoding (may be empty)
};

// Writers append one framed chunk each.
void write_volume_signature(std::vector<std::uint8_t>& out);
void write_header_chunk(std::vector<std::uint8_t>& out, const VolumeStreamHeader& header);
void write_mask_chunk(std::vector<std::uint8_t>& out, std::uint32_t grid, const MaskChunk& mask);
void write_opaque_chunk(std::vector<std::uint8_t>& out, std::uint32_t grid,
                        const std::vector<std::uint8_t>& bytes);
void write_blocks_chunk(std::vector<std::uint8_t>& out, std::uint32_t grid, const BlocksChunk& blocks);
void write_brick_chunk(std::vector<std::uint8_t>& out, const BrickChunk& brick);

struct ParsedVolumeStream {
  VolumeStreamHeader header;
  std::vector<BoxMask> masks;                     // one per grid (empty unless a sparse box)
  std::vector<BlocksChunk> layouts;               // one per grid (empty unless sparse-native)
  std::vector<std::vector<std::uint8_t>> opaque;  // one per grid (empty unless opaque)
  std::vector<std::size_t> grid_bytes;            // per grid: bytes of its MASK / BLKS / BRIK chunks
  std::vector<BrickChunk> bricks;                 // codewords point into the parsed bytes
};

// What the decode limit counts of a sparse box grid (docs/bitstream.md, Decoder bounds).
enum class SparseBoxCount : std::uint8_t {
  box,      // every voxel of its box (a dense output: raw, the API's arrays); checked on the header
  content,  // the voxels of its bricks holding anything but inactive background (sparse output)
};

// Parses and validates a whole stream. Throws DecodeError for any inconsistency, or when the
// voxels to decode (dense grids, sparse-native blocks, sparse boxes as `count` says) exceed
// `limits`: box voxels before any mask is read, content voxels as soon as the mask pass finds them.
ParsedVolumeStream parse_volume_stream(std::span<const std::uint8_t> bytes, const DecodeLimits& limits = {},
                                       SparseBoxCount count = SparseBoxCount::box);

}  // namespace pupwave
