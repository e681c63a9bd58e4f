#pragma once
// Internal to the volume codec: the MASK chunk of a sparse box grid without a byte per voxel in
// memory (empty sparse regions cost nothing). The zstd frame of voxel states stays
// compressed in the parsed stream and is streamed row by row when needed; one pass at parse time
// validates it and keeps one byte per brick saying which non-background states the brick holds.

#include <zstd.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/format/decode_limits.h"
#include "codec/volume/volume_brick.h"

namespace pupwave {

// The bricks of a box, as brick_boxes(dims, edge) lists them (x fastest), computed on demand:
// a box of 2^31 voxels with 8^3 bricks would otherwise list millions of boxes.
struct BoxBricks {
  Extent dims{0, 0, 0};
  Extent n{0, 0, 0};  // bricks along each axis
  int log2 = 0;       // brick edge 2^log2

  BoxBricks() = default;
  BoxBricks(const Extent& dims, int log2);
  std::size_t count() const { return n[0] * n[1] * n[2]; }
  BrickBox box(std::size_t index) const;
  // Index of the brick holding voxel (x, y, z).
  std::size_t at(std::size_t x, std::size_t y, std::size_t z) const {
    return (x >> log2) + n[0] * ((y >> log2) + n[1] * (z >> log2));
  }
};

// Bit (1 << state) of BoxMask::bricks for each non-background state (codec/volume/volume_format.h
// VoxelState) a brick holds; 0: every voxel of the brick is inactive background.
inline constexpr std::uint8_t kBrickHasActive = 1 << 1;

struct BoxMask {
  std::span<const std::uint8_t> frame;  // zstd frame of the states (into the parsed bytes)
  std::vector<double> other_values;     // values of the inactive_other voxels, in voxel order
  std::vector<std::uint8_t> bricks;     // per brick of BoxBricks: states held (bits above)
  std::size_t active = 0;               // active voxels
  std::size_t content_voxels = 0;       // voxels of the bricks whose bits are not 0
  std::size_t last_row = 0;             // one past the last row (y + dims[1] z) of such a brick
  bool empty() const { return frame.empty(); }
};

// Streams a box's states in batches of whole rows (dims[0] states, x fastest; row y + dims[1] z).
class MaskRows {
 public:
  MaskRows(std::span<const std::uint8_t> frame, const Extent& dims);
  ~MaskRows();
  MaskRows(const MaskRows&) = delete;
  MaskRows& operator=(const MaskRows&) = delete;
  // The next batch: its first row index, its row count (0 at the end of the box) and states.
  std::size_t next(std::size_t& first_row, const std::uint8_t*& states);
  // Throws DecodeError unless the frame ended exactly with the box's last row.
  void expect_end();

 private:
  std::span<const std::uint8_t> frame_;
  Extent dims_;
  std::size_t row_ = 0, rows_per_batch_ = 1;
  ZSTD_DCtx* ctx_ = nullptr;
  ZSTD_inBuffer in_{};
  std::size_t last_status_ = 1;  // ZSTD_decompressStream's last return (0: frame complete)
  std::vector<std::uint8_t> buffer_;
};

// Validates a MASK chunk's frame of `dims` voxel states (content size, states 0..3, as many
// inactive_other voxels as `other_values`) in one streamed pass and summarises it per brick.
// `content_budget`: how many voxels of non-empty bricks may be decoded; past it the decode limit
// error of `limits` is thrown (naming `already + content`) as soon as it is known.
BoxMask scan_box_mask(std::span<const std::uint8_t> frame, std::vector<double> other_values,
                      const Extent& dims, int brick_log2, const DecodeLimits& limits, std::size_t already);

}  // namespace pupwave
