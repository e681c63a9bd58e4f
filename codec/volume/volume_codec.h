#pragma once
// Volume compression: every grid is cut into bricks (default 64^3) so memory stays bounded and
// any brick decodes alone; each brick goes through the 3-D separable transform of any transform
// spec, the dead-zone quantizer and the bit-plane coder over 3-D code-blocks (max-error
// bricks: the non-embedded coefficient coder, codec/entropy/coef_encoder.h). For float data a
// point-wise error bound is guaranteed by coding the voxels the transform coding leaves outside
// the bound as explicit corrections (as SPERR does). Sparse grids code only bricks holding
// active voxels; the active mask, background and inactive values are restored exactly.
// The stream layout ("PUPV") is in docs/bitstream.md, section Volumes.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "codec/format/decode_limits.h"
#include "codec/volume/volume.h"
#include "codec/volume/volume_view.h"
#include "transforms/executor.h"

namespace pupwave {

enum class VolumeRateMode : std::uint8_t {
  step,       // fixed quantizer base step `target` (sample units), every bit-plane coded
  bpv,        // best quality within `target` bits per voxel (whole file), PCRD over all bricks
  psnr,       // smallest file whose PSNR (peak = value range) reaches `target` dB (estimated)
  lossless,   // reversible integer transform, bit exact (u8/u16 volumes only)
  max_error,  // every active voxel within `target` (absolute) of its original, guaranteed; for
              // integer grids a target below 1 allows no error at all: coded lossless instead
};

// The transform the CLI and the C/C++/Python API use for max-error volumes when none is named:
// whole volumes are 1.7-3.5% smaller than with cdf97 (wmag91, turbulence 256^3, 1e-2..1e-4 of the
// range) at 1.1-1.2x the encode CPU (bench/results/volumes.md).
// VolumeEncodeOptions itself keeps cdf97, the bank of the other rate modes: each entry point (CLI, C/C++
// and Python APIs, numcodecs, the HDF5 filter) picks this one when the mode is max-error.
inline constexpr const char* kMaxErrorVolumeTransform = "pups:cinpact-interp-vm4";

struct VolumeEncodeOptions {
  std::string transform = "cdf97";  // spec for make_transform; lossless needs a reversible one
  int levels = -1;                  // per brick; -1: default_levels of a full brick
  VolumeRateMode mode = VolumeRateMode::max_error;
  double target = 1e-3;    // step, bits per voxel, dB or absolute error bound, by mode
  std::size_t brick = 64;  // brick edge (power of two, 8..256); edge bricks are smaller
  std::size_t block = 32;  // code-block edge inside a brick (power of two, 16..64)
  // Runs the bricks as parallel tasks; null: default_executor(). Streams never depend on it.
  const Executor* executor = nullptr;
  // Missing values of dense grids, restored bit for bit and left out of the bound, the range
  // and the statistics: NaN and infinities always, and voxels equal to this value when set
  // (e.g. -999, or netCDF's 9.96921e36). Must be finite. Sparse grids keep refusing NaN.
  std::optional<double> fill_value;
};

struct VolumeEncodeResult {
  std::vector<std::uint8_t> bytes;  // the complete .pw volume stream (empty when given to a writer)
  std::size_t size = 0;             // bytes of the stream
  double bpv = 0.0;                 // bits per active voxel (all grids; active tiles count their voxels)
  double max_error = 0.0;           // largest |x - x'| over active voxels of all grids
  double psnr = 0.0;                // peak = value range of each grid's active voxels (worst grid)
  std::size_t outliers = 0;         // voxels corrected explicitly (max_error mode)
  // max_error mode on integer grids with a bound below 1: coded lossless (the given transform
  // when reversible, else cdf53), the only way to meet it and smaller than corrections.
  bool switched_to_lossless = false;
  // Whether the stream meets the rate target: bpv within `target` bits per voxel, psnr at
  // least `target` dB, max_error within the bound (always: it is guaranteed); `bpv`, `psnr`
  // and `max_error` say what it reached. A missed target still gives the stream, the nearest
  // the encoder reaches (a tiny volume's head alone can exceed a bpv budget). step and lossless
  // set no target to miss: true.
  bool target_met = true;
};

// Compresses grids (each a Volume with its name, class, transform and metadata). Throws
// std::invalid_argument for bad options (unknown transform, lossless of float data or with a
// non-reversible transform, non-positive target, bad brick/block size, a non-finite fill value)
// and EncodeError for volumes the format cannot hold (no grids, empty or too large volumes,
// non-finite samples in a sparse grid). Dense grids may hold missing values (fill_value).
VolumeEncodeResult encode_volumes(const std::vector<VolumeGrid>& grids, const VolumeEncodeOptions& options);

// The same with box grids read in place through views of the caller's memory (typed, strided;
// see volume_view.h): bricks are gathered one at a time as the view's storage type, so a
// volume is never copied. views[i] with data set gives grid i's values: grids[i] then carries
// only the description (name, class, placement, metadata; volume.dims, type and background
// equal to the view's, volume.samples and active empty; the mask comes from the view). A view
// with null data (or an empty span) means the grid's own values. Throws like the above, and
// std::invalid_argument for a view that does not fit its grid.
VolumeEncodeResult encode_volumes(const std::vector<VolumeGrid>& grids, std::span<const VolumeView> views,
                                  const VolumeEncodeOptions& options);

// Receives the stream piece by piece, in order (see encode_volumes with a writer), one call at a
// time but possibly from the executor's worker threads.
using StreamWriter = std::function<void(std::span<const std::uint8_t>)>;

// The same, handing the stream to `write` piece by piece instead of returning it (result.bytes
// stays empty): the head, then each brick's chunk as soon as it and the bricks before it are
// coded (rate modes, whose allocation needs every brick first: after all are coded), so an encode
// writing to a file holds only the bricks in flight, never the stream. A null writer: as above.
VolumeEncodeResult encode_volumes(const std::vector<VolumeGrid>& grids, std::span<const VolumeView> views,
                                  const VolumeEncodeOptions& options, const StreamWriter& write);

// A box grid's description for encode_volumes with a view: dims, type and background of the
// view, no samples.
VolumeGrid describe_view(const VolumeView& view, std::string name);

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

// How decode_volumes returns a sparse box grid (one stored with a MASK chunk).
enum class SparseBoxForm : std::uint8_t {
  box,     // a Volume over its whole box with its active mask (what raw output and arrays need);
           // the decode limit counts every voxel of the box
  blocks,  // sparse-native (VolumeGrid::blocks): one block per brick holding anything but inactive
           // background, nothing else allocated (what .vdb output needs; volume.dims stays the
           // box, or 0 when every voxel is inactive background); the decode limit counts the
           // voxels of those bricks at full resolution
};
// The same, choosing the form of sparse box grids (the above: SparseBoxForm::box).
std::vector<VolumeGrid> decode_volumes(std::span<const std::uint8_t> bytes, int level,
                                       const Executor& executor, const DecodeLimits& limits,
                                       SparseBoxForm form);

// Decodes one box grid straight into the caller's typed buffer, brick by brick, so the grid is
// never held as double: `allocate` is called once with the grid's description at `level` (name,
// placement, volume.dims, type, background; no samples; volume.is_sparse() tells a sparse box,
// its `active` then only a marker) and returns where to write (dims equal
// to the described ones, storage able to hold the type; `active`, if set, receives the mask of a
// sparse grid). `name` selects the grid ("": the only one). Returns nullopt, having decoded
// nothing, when there is no such grid, when `name` is empty and the stream holds several, or
// for a grid decode_volumes must give (sparse-native, opaque, or a sparse box below full
// resolution). Throws like decode_volumes.
std::optional<VolumeGrid> decode_volume_into(std::span<const std::uint8_t> bytes, std::string_view name,
                                             int level, const Executor& executor, const DecodeLimits& limits,
                                             const std::function<VolumeOutput(const VolumeGrid&)>& allocate);

// A box of full-resolution voxels: [lo[a], hi[a]) along x, y and z (half-open).
struct VoxelBox {
  Extent lo{0, 0, 0};
  Extent hi{0, 0, 0};
};
// "[x0,x1) x [y0,y1) x [z0,z1)", for messages.
std::string to_string(const VoxelBox& box);

// Decodes the voxels of `box` of one grid (`name`; "": the only one) at 1/2^level resolution,
// decoding only the bricks the box touches (one executor task per such brick; the stream is
// still parsed and checked whole). The box is in the grid's box: its volume, a sparse grid's
// dense bounding box (a sparse-native grid's: its active bounding box, as make_dense_box). The
// result holds the level-`level` voxels whose full-resolution footprint
// [c 2^level, (c + 1) 2^level) meets the box: along each axis c runs from floor(lo / 2^level) to
// floor((hi - 1) / 2^level), volume.dims counts them, and origin is the grid's level-`level`
// origin plus the first. Its values, active mask and inactive values equal that crop of
// decode_volumes at the level (then make_dense_box for a sparse-native grid), bit for bit. The
// decode limit counts the box's voxels at full resolution, not the grid's. Throws
// std::invalid_argument for a box that is empty, inverted or outside the grid (naming the box
// and the grid's dims), no such grid, an empty name with several grids, an opaque grid, a level
// past the stream's (or above 3 for a sparse-native grid); DecodeError like decode_volumes.
VolumeGrid decode_volume_box(std::span<const std::uint8_t> bytes, std::string_view name, const VoxelBox& box,
                             int level, const Executor& executor, const DecodeLimits& limits);
// The same straight into the caller's typed buffer (as decode_volume_into): `allocate` is called
// once with the box grid's description (name, placement, volume.dims of the box at `level`,
// type, background; no samples; volume.is_sparse() tells a sparse grid) and returns where to
// write (dims equal to the described ones; `active`, if set, receives a sparse grid's mask).
// Values are stored as VolumeOutput::set stores them. Returns the description.
VolumeGrid decode_volume_box_into(std::span<const std::uint8_t> bytes, std::string_view name,
                                  const VoxelBox& box, int level, const Executor& executor,
                                  const DecodeLimits& limits,
                                  const std::function<VolumeOutput(const VolumeGrid&)>& allocate);

// True when bytes start with the volume stream signature (cheap; validates nothing else).
bool is_volume_stream(std::span<const std::uint8_t> bytes);

// Human-readable description of a volume stream (grids, transform, mode, chunk sizes), after
// validating the whole stream. Throws DecodeError for a corrupt or truncated stream.
std::string describe_volume_stream(std::span<const std::uint8_t> bytes);

}  // namespace pupwave
