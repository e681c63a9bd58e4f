#pragma once
// Pupwave's public C++20 API: images and volumes in, .pw bytes out; bytes in, samples out at
// any resolution level; stream description. Self-contained (no internal header is included or
// installed); the C API for FFI is pupwave/pupwave.h. docs/api.md has examples.
//
// Errors: every function throws pupwave::api::Error (a std::runtime_error) carrying a Status
// and the library's message: Status::invalid_argument for bad parameters or views,
// Status::unsupported for input the format cannot hold, Status::corrupt_stream for bytes that
// are truncated, corrupted or not a Pupwave stream. std::bad_alloc passes through.
//
// Thread safety: independent calls on different threads are safe (no global mutable state;
// parallel work runs on the process's shared thread pool, limited per call by `threads`).
// Output never depends on `threads`.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace pupwave::api {

enum class Status : int {
  ok = 0,
  invalid_argument = 1,
  unsupported = 2,
  corrupt_stream = 3,
  out_of_memory = 4
};

class Error : public std::runtime_error {
 public:
  Error(Status status, const std::string& message) : std::runtime_error(message), status_(status) {}
  Status status() const { return status_; }

 private:
  Status status_;
};

// A named text attribute carried in a stream (an image's META chunk, a volume grid's metadata):
// stored on encode and handed back on decode, read by nothing else in the library. Bindings
// name theirs "pupwave:..." (the Python module records a converted array's dtype as
// "pupwave:dtype"). Names are non-empty, unique and at most 4096 bytes; values at most 65535.
struct Attribute {
  std::string name;
  std::string value;
  bool operator==(const Attribute&) const = default;
};

// ---- images ----------------------------------------------------------------------------------

// Sample types: 8/16-bit unsigned integers, IEEE binary16 (as uint16 bits) and binary32.
enum class SampleType : std::uint8_t { u8 = 0, u16 = 1, f16 = 2, f32 = 3 };
std::size_t bytes_per_sample(SampleType type);

// A read-only, typed, strided view of the caller's samples: sample (c, x, y) is the element at
//   data + c * channel_stride + x * pixel_stride + y * row_stride   (strides in ELEMENTS).
// Planar, interleaved and padded-row buffers are all views; nothing is copied to encode.
struct ImageView {
  const void* data = nullptr;
  std::size_t width = 0, height = 0, channels = 0;  // channels 1..64 (grey, grey+alpha, RGB, RGBA, more)
  SampleType type = SampleType::u8;
  std::ptrdiff_t channel_stride = 0, pixel_stride = 0, row_stride = 0;
};
// Interleaved (RGBRGB...) rows of row_stride elements (0: width * channels).
ImageView interleaved_view(const void* data, std::size_t width, std::size_t height, std::size_t channels,
                           SampleType type, std::ptrdiff_t row_stride = 0);
// Planar (plane after plane, rows of width elements).
ImageView planar_view(const void* data, std::size_t width, std::size_t height, std::size_t channels,
                      SampleType type);

// The CLI's rate modes (pupwave compress --psnr/--bpp/--step/--lossless).
enum class ImageRate : std::uint8_t {
  psnr,      // smallest stream whose PSNR (dB, all channels) reaches target
  bpp,       // best quality within target bits per pixel (whole stream)
  step,      // fixed quantizer base step target (sample units)
  lossless,  // bit exact (integer samples only; reversible transform)
};

// The image entropy coders. One set of names for every front door: the CLI's --entropy NAME,
// Python's entropy="NAME" and the C API's PUPWAVE_CODER_* (same order):
//   auto   lc for lossless; for rate targets pc on images of up to 4 Mpixel, ebcot on larger
//          ones
//   ebcot  bit-plane coder: embedded, bounded memory from 8-bit PGM/PPM; effort 2 applies to it
//   pc     parent-context coder: the smallest lossy files; lossy only, holds the transformed image
//   lc     lossless context coder: the smallest lossless files; lossless only
//   ht     high-throughput block coder: no arithmetic coding, fastest, larger files
enum class Coder : std::uint8_t { automatic, ebcot, pc, lc, ht };
std::string_view coder_name(Coder coder);                     // "auto", "ebcot", ...
std::optional<Coder> coder_from_name(std::string_view name);  // any case; nullopt when unknown
std::string coder_names();                                    // "auto, ebcot, pc, lc, ht"

// What lossy image coding minimises. One set of names for every front door (the CLI's --tune
// NAME, Python's tune="NAME", the C API's PUPWAVE_TUNE_*, the OIIO plugin's "pupwave:tune"):
//   psnr    the squared error (default): the best PSNR at a size
//   visual  a contrast-sensitivity-weighted squared error with less weight on chroma: better
//           perceptual scores (butteraugli, MS-SSIM) at a size, a lower PSNR
// Rate targets keep their meaning in both (a PSNR target is met in real PSNR).
enum class Tune : std::uint8_t { psnr, visual };
std::string_view tune_name(Tune tune);                      // "psnr", "visual"
std::optional<Tune> tune_from_name(std::string_view name);  // any case; nullopt when unknown

struct ImageOptions {
  ImageRate rate = ImageRate::psnr;
  double target = 40.0;   // dB, bits per pixel or step; ignored for lossless
  std::string transform;  // transform spec (cdf97, cdf53, pups:..., kobbelt:...); "": cdf97, cdf53 lossless
  int levels = -1;        // decomposition levels, -1: from the image size
  Coder coder = Coder::automatic;  // entropy coder (Coder above)
  unsigned threads = 0;            // most worker threads (0: all cores, 1: the calling thread)
  // Encoder effort for bpp targets with ebcot: 1 fastest, 2 about 1 % less rate for up to 1.9x the time
  // and more memory (same format; other rates ignore it).
  int effort = 1;
  Tune tune = Tune::psnr;  // what lossy coding minimises (Tune above); lossless ignores it
  // Stored in the stream (its META chunk).
  std::vector<Attribute> attributes;
};

// What a rate target gave, for the compress_* overloads that take one.
struct TargetOutcome {
  // False when the stream misses the target: over a bpp/bpv budget (a tiny input's header alone
  // can exceed it), under a PSNR target, or over an error bound. The stream is complete either
  // way. Step and lossless set no target to miss: true.
  bool met = true;
  // The stream's value in the target's unit: bits per pixel or voxel, PSNR in dB (log-PSNR for
  // half/float images), the largest error (for max_error_rel as a fraction of the value range);
  // NaN for step and lossless.
  double achieved = 0.0;
};

// Compresses an image to a complete .pw stream.
std::vector<std::uint8_t> compress_image(const ImageView& image, const ImageOptions& options = {});
// The same, saying in `outcome` whether the target was met and what was reached.
std::vector<std::uint8_t> compress_image(const ImageView& image, const ImageOptions& options,
                                         TargetOutcome& outcome);

// A decoded image: interleaved samples (pixel after pixel, channels adjacent) of `type`.
struct Image {
  std::size_t width = 0, height = 0, channels = 0;
  SampleType type = SampleType::u8;
  std::vector<std::byte> data;  // width * height * channels * bytes_per_sample(type)
  // The stream's text attributes (integer and real ones are not listed).
  std::vector<Attribute> attributes;
};

// Decodes at full size (level 0) or 1/2^level size (ceil per halving), reading only that data.
Image decompress_image(std::span<const std::uint8_t> stream, int level = 0, unsigned threads = 0);

// ---- volumes ---------------------------------------------------------------------------------

enum class VoxelType : std::uint8_t { u8 = 0, u16 = 1, f32 = 2, f64 = 3 };
std::size_t bytes_per_voxel(VoxelType type);

// A read-only, typed 3-D array in the caller's memory, read in place (never copied or widened
// to double to encode): voxel (x, y, z) is the element at
//   data + x * strides[0] + y * strides[1] + z * strides[2]   (strides in ELEMENTS);
// strides all 0 means dense, x fastest: element x + dims[0] * (y + dims[1] * z) (a C-order
// numpy array of shape (z, y, x)). Strides select a sub-box of a larger array, any axis order.
struct VolumeView {
  const void* data = nullptr;
  std::array<std::size_t, 3> dims{0, 0, 0};
  VoxelType type = VoxelType::f32;
  std::array<std::ptrdiff_t, 3> strides{0, 0, 0};
};

// One brick of a sparse grid: a dense box of voxels at integer position `origin`, optionally
// with an activity mask (one byte per voxel, nonzero = active; null: all active).
struct BrickView {
  std::array<std::int64_t, 3> origin{0, 0, 0};
  VolumeView voxels;
  const std::uint8_t* active = nullptr;
};

// The CLI's volume rate modes (pupwave compress --max-error/--max-error-rel/--bpv/--psnr/--step/--lossless;
// automatic is what the CLI codes when none is given).
enum class VolumeRate : std::uint8_t {
  max_error,      // every voxel within target (absolute) of its original, guaranteed
  max_error_rel,  // the same with bound target * (max - min) of the data
  bpv,            // best quality within target bits per voxel
  psnr,           // smallest stream reaching target dB (peak = value range), estimated
  step,           // fixed quantizer base step target
  lossless,       // bit exact (u8/u16 only)
  automatic,      // lossless for u8/u16 data, else max_error_rel 1e-3 (target ignored)
};

struct VolumeOptions {
  VolumeRate rate = VolumeRate::automatic;
  double target = 1e-3;    // by rate: absolute error, fraction of the range, bpv, dB or step
  std::string transform;   // "": pups:cinpact-interp-vm4 for max error, cdf53 lossless, else cdf97
  int levels = -1;         // per brick, -1: default
  std::size_t brick = 64;  // brick edge (power of two, 8..256)
  unsigned threads = 0;    // as ImageOptions::threads
  // Stored as the grid's metadata.
  std::vector<Attribute> attributes;
  // Dense volumes: voxels equal to this value are missing (as NaN and infinities always are):
  // restored bit for bit, outside the bound, the range and the statistics. Must be finite.
  std::optional<double> fill_value;
};

std::vector<std::uint8_t> compress_volume(const VolumeView& volume, const VolumeOptions& options = {});
// A sparse grid from bricks (same voxel type; bricks may not overlap): only active voxels are
// coded; the box outside the bricks is inactive with value `background`, restored exactly.
std::vector<std::uint8_t> compress_sparse_volume(std::span<const BrickView> bricks, double background,
                                                 const VolumeOptions& options = {});
// The same two, saying in `outcome` whether the target was met and what was reached.
std::vector<std::uint8_t> compress_volume(const VolumeView& volume, const VolumeOptions& options,
                                          TargetOutcome& outcome);
std::vector<std::uint8_t> compress_sparse_volume(std::span<const BrickView> bricks, double background,
                                                 const VolumeOptions& options, TargetOutcome& outcome);

// A decoded grid: dims voxels (x fastest) of `type` starting at `origin` (halved per level).
struct Volume {
  std::string name;
  std::array<std::int64_t, 3> origin{0, 0, 0};
  std::array<std::size_t, 3> dims{0, 0, 0};
  VoxelType type = VoxelType::f32;
  std::vector<std::byte> data;       // dims product * bytes_per_voxel(type)
  std::vector<std::uint8_t> active;  // one byte per voxel (1 active) for sparse grids; empty if dense
  double background = 0.0;           // value of inactive voxels outside the box
  // The grid's text metadata (other kinds are not listed).
  std::vector<Attribute> attributes;
};

// Decodes every grid of a volume stream (a stream from the CLI may hold several).
std::vector<Volume> decompress_volume(std::span<const std::uint8_t> stream, int level = 0,
                                      unsigned threads = 0);

// A box of full-resolution voxels: [lo[a], hi[a]) along x, y and z (half-open).
struct VoxelBox {
  std::array<std::size_t, 3> lo{0, 0, 0};
  std::array<std::size_t, 3> hi{0, 0, 0};
};

// Decodes the voxels of `box` of one grid (`grid`, or the only one) at level, decoding only the
// bricks the box touches: the level-`level` voxels whose full-resolution footprint
// [c 2^level, (c + 1) 2^level) meets the box (c from lo / 2^level to (hi - 1) / 2^level, rounded
// down); `origin` is the first one's index-space position. Equal to that box cropped out of
// decompress_volume at the level (a sparse grid's box is its dense bounding box, a .vdb grid's
// its active bounding box; `active` and inactive values included). The decode limit counts the
// box's voxels, not the grid's. Status::invalid_argument for a box that is empty, inverted or
// outside the grid (the message names the box and the grid's dims), no such grid, several grids
// and no name, or a grid carried as OpenVDB bytes only.
Volume decompress_volume_box(std::span<const std::uint8_t> stream, const VoxelBox& box, int level = 0,
                             unsigned threads = 0, std::string_view grid = {});

// ---- description -----------------------------------------------------------------------------

struct StreamInfo {
  bool volume = false;                // "PUPV" volume stream, else "PUPW" image stream
  std::array<std::size_t, 3> dims{};  // width, height, 1 (images) or x, y, z (first grid)
  std::size_t channels = 1;           // images; grids for volumes
  std::string type;                   // "u8", "u16", "f16", "f32", "f64"
  int levels = 0;
  std::string transform;
  bool lossless = false;
  double max_error = 0.0;   // volumes coded with a point-wise bound (0: none)
  bool sparse = false;      // volumes: first grid is sparse
  std::string description;  // `pupwave info` text; every checksum verified
  // Text attributes of the image, or of a volume's first grid.
  std::vector<Attribute> attributes;
};
StreamInfo info(std::span<const std::uint8_t> stream);

}  // namespace pupwave::api
