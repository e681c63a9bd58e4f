#pragma once
// Volume compression: every grid is cut into bricks (default 64^3) so memory stays bounded and
// any brick decodes alone; each brick goes through the 3-D separable transform of any transform
// spec, the dead-zone quantizer and the bit-plane coder over 3-D code-blocks. For float data a
// point-wise error bound is guaranteed by coding the voxels the transform coding leaves outside
// the bound as explicit corrections (as SPERR does). Sparse grids code only bricks holding
// active voxels; the active mask, background and inactive values are restored exactly.
// The stream layout ("PUPV") is in docs/bitstream.md, section Volumes.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "codec/format/decode_limits.h"
#include "codec/volume/volume.h"
#include "transforms/executor.h"

namespace pupwave {

enum class VolumeRateMode : std::uint8_t {
  step,       // fixed quantizer base step `target` (sample units), every bit-plane coded
  bpv,        // best quality within `target` bits per voxel (whole file), PCRD over all bricks
  psnr,       // smallest file whose PSNR (peak = value range) reaches `target` dB (estimated)
  lossless,   // reversible integer transform, bit exact (u8/u16 volumes only)
  max_error,  // every active voxel within `target` (absolute) of its original, guaranteed
};

struct VolumeEncodeOptions {
  std::string transform = "cdf97";  // spec for make_transform; lossless needs a reversible one
  int levels = -1;                  // per brick; -1: default_levels of a full brick
  VolumeRateMode mode = VolumeRateMode::max_error;
  double target = 1e-3;    // step, bits per voxel, dB or absolute error bound, by mode
  std::size_t brick = 64;  // brick edge (power of two, 8..256); edge bricks are smaller
  std::size_t block = 32;  // code-block edge inside a brick (power of two, 16..64)
  // Runs the bricks as parallel tasks; null: default_executor(). Streams never depend on it.
  const Executor* executor = nullptr;
};

struct VolumeEncodeResult {
  std::vector<std::uint8_t> bytes;  // the complete .pw volume stream
  double bpv = 0.0;                 // bits per active voxel (all grids; active tiles count their voxels)
  double max_error = 0.0;           // largest |x - x'| over active voxels of all grids
  double psnr = 0.0;                // peak = value range of each grid's active voxels (worst grid)
  std::size_t outliers = 0;         // voxels corrected explicitly (max_error mode)
};

// Compresses grids (each a Volume with its name, class, transform and metadata). Throws
// std::invalid_argument for bad options (unknown transform, lossless of float data or with a
// non-reversible transform, non-positive target, bad brick/block size) and EncodeError for
// volumes the format cannot hold (no grids, empty or too large volumes, non-finite samples).
VolumeEncodeResult encode_volumes(const std::vector<VolumeGrid>& grids, const VolumeEncodeOptions& options);

// Decodes all grids at full resolution (level 0) or at 1/2^level resolution (each brick stops
// its inverse transform early; mask voxels of a coarse cell are active when any child is).
// Throws DecodeError for a corrupt or truncated stream and std::invalid_argument when level
// exceeds the stream's levels.
std::vector<VolumeGrid> decode_volumes(std::span<const std::uint8_t> bytes, int level = 0,
                                       const Executor& executor = default_executor());
// The same with a decode limit other than the default (2^28 voxels of all grids at full
// resolution); a larger stream throws DecodeError before any mask or output is allocated.
std::vector<VolumeGrid> decode_volumes(std::span<const std::uint8_t> bytes, int level,
                                       const Executor& executor, const DecodeLimits& limits);

// True when bytes start with the volume stream signature (cheap; validates nothing else).
bool is_volume_stream(std::span<const std::uint8_t> bytes);

// Human-readable description of a volume stream (grids, transform, mode, chunk sizes), after
// validating the whole stream. Throws DecodeError for a corrupt or truncated stream.
std::string describe_volume_stream(std::span<const std::uint8_t> bytes);

}  // namespace pupwave
