#pragma once
// Image compression and decompression: colour transform, separable wavelet transform,
// dead-zone quantization, code-blocks coded by the bit-plane coder (or the ht, lc or pc
// coder), rate control (PCRD for the bit-plane coder), and the .pw container. The CLI
// (tools/cmd_compress.cpp) is a thin layer over this.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "codec/image/image.h"
#include "codec/image/image_stream.h"
#include "codec/image/image_view.h"
#include "codec/image/visual_weights.h"
#include "transforms/executor.h"

namespace pupwave {

struct EncodeStats;  // encode_stats.h

enum class RateMode : std::uint8_t {
  psnr,      // smallest file whose PSNR (all channels, against the input) reaches target dB
  bpp,       // best quality within target bits per pixel (whole file, all channels)
  step,      // fixed quantizer base step `target` (sample units), every bit-plane coded
  lossless,  // reversible integer transform and colour transform, bit-exact (integer samples)
};

struct EncodeOptions {
  std::string transform = "cdf97";  // spec for make_transform; lossless needs a reversible one
  int levels = -1;                  // -1: default_levels(dims)
  RateMode mode = RateMode::psnr;
  double target = 40.0;  // dB, bits per pixel or base step, by mode
  EntropyCoder entropy = EntropyCoder::ebcot;
  // Runs the parallel work (transform lines, code-blocks); null: default_executor(), the
  // shared pool on all hardware threads. Streams never depend on it.
  const Executor* executor = nullptr;
  Extent block_size{64, 64, 1};  // code-block extent (powers of two, >= 1024 samples)
  // Encoder effort for byte budgets (RateMode::bpp); the format does not depend on it.
  // 1: one base step (fastest, one component transformed at a time). 2: the blocks are coded
  // at three base steps and each band takes the best (plus RDOQ): about 1 % less rate at equal
  // PSNR for 1.2-1.9x the encode time and the transformed components held in memory.
  int effort = 1;
  // What the rate allocation minimises (visual_weights.h): the squared error (psnr), or a
  // contrast-sensitivity-weighted one (visual). Only the quantizer steps differ; rate targets keep
  // their meaning (a PSNR target is the real PSNR). Lossless ignores it.
  Tune tune = Tune::psnr;
  // Decode the result to report its PSNR. Costs about a full decode, strip by strip (the strip
  // decoder's memory, not a decoded image's) except for lc and pc streams, whose decode holds
  // the component planes; PSNR targets measure it anyway.
  bool measure_psnr = true;
  // Float images: the domain they are coded in (transfer.h). Rate targets (--psnr) and the
  // reported PSNR are stated in it (log-PSNR for log2). Ignored for integer images.
  Transfer transfer = Transfer::log2;
  // Float images: NaN and infinite samples are coded exactly through a side list (NFIN chunk)
  // instead of refused.
  bool keep_nonfinite = false;
  // Channel names, windows and attributes stored in the stream (META chunk); null: none
  // (the Image overload of encode_image passes the image's own).
  const ImageMetadata* metadata = nullptr;
  // Integer images with a transform whose analysis is local are transformed strip by strip,
  // each code-block coded as soon as its rows are complete (image_strip_encoder.h), so memory
  // does not grow with the image; false holds each component whole instead. The bytes are
  // the same either way (tests compare the two).
  bool strip_encode = true;
  // Where the encode adds its statistics (encode_stats.h); null: none are kept. The bytes never
  // depend on it.
  EncodeStats* stats = nullptr;
};

struct EncodeResult {
  std::vector<std::uint8_t> bytes;  // the complete .pw file
  double bpp = 0.0;                 // bits per pixel of the whole file
  double psnr = 0.0;       // of the decoded image against the input, all channels (dB); NaN if not measured
  double base_step = 0.0;  // quantizer base step used (1 for lossless)
  std::string metric = "PSNR";  // what `psnr` measures: "PSNR", or "log-PSNR" for float images coded in log2
  std::size_t nonfinite = 0;    // non-finite samples kept in the side list
  // An integer image's rate target gave the lossless stream instead: it fit the --bpp budget,
  // only exact decoding reaches the --psnr target, or a lossy stream would not be smaller.
  bool switched_to_lossless = false;
  // Whether the file meets the rate target: RateMode::bpp within `target` bits per pixel,
  // RateMode::psnr at least `target` dB (in `metric`); `bpp` and `psnr` say what it reached.
  // A missed target still gives the file (a tiny image's header alone can exceed a bpp
  // budget). step and lossless set no target to miss: true.
  bool target_met = true;
};

// Compresses an image. For integer images no rate target gives a file larger than the
// lossless one (switched_to_lossless tells). Throws std::invalid_argument for bad options
// (unknown transform, a non-reversible transform for lossless, lossless float samples, a
// non-positive or non-finite target, more levels than the image takes, a float image's step
// below 2^-24 of its value range or PSNR target above 120 dB, effort other than 1 or 2) and
// EncodeError for images the format cannot hold (empty, over 2^16 per axis or 2^31 samples,
// more than 64 channels, non-finite samples unless keep_nonfinite).
// A rate target the file misses is no error: the file comes back with target_met false.
// The image is read through a typed strided view (image_view.h), never copied whole; a view
// that cannot be read throws std::invalid_argument.
EncodeResult encode_image(const ImageView& image, const EncodeOptions& options);
inline EncodeResult encode_image(const Image& image, const EncodeOptions& options) {
  EncodeOptions with_metadata = options;
  if (with_metadata.metadata == nullptr && !image.metadata.empty()) with_metadata.metadata = &image.metadata;
  return encode_image(view_of(image), with_metadata);
}

// Images of up to this many pixels (any sample type) take the pc coder for rate targets by
// default; larger ones the bit-plane coder, whose strip-wise encoder keeps memory bounded
// however large the image (pc holds every transformed component and its indices, about 8 bytes
// a sample: 100 MiB at this size in RGB). bench/results/image-speed-memory.md has the figures.
inline constexpr std::size_t kPcDefaultPixels = std::size_t(1) << 22;
// Whether encode_image_default_coder codes `image`'s rate targets with the pc coder.
bool pc_is_default_for(const ImageView& image);

// encode_image with the default coder (options.entropy is ignored): lossless uses the lc coder
// (smaller than the bit-plane coder's lossless stream, bench/results/image-lossless-hdr.md), rate targets
// the pc coder (pc_is_default_for) or the bit-plane coder, and a rate target that ends lossless
// (switched_to_lossless) or gives an integer image's lossy file of over a quarter of its raw size
// gives the lc stream when it is the smaller. The CLI without --entropy and the library both
// encode here.
EncodeResult encode_image_default_coder(const ImageView& image, EncodeOptions options);

// Decodes a stream, at full resolution (level 0) or at 1/2^level resolution, reading only
// the data that resolution needs. Throws DecodeError for a corrupt or truncated stream and
// std::invalid_argument when level exceeds the stream's level count.
// Parallel work runs on `executor`; the pixels never depend on it.
Image decode_image(std::span<const std::uint8_t> bytes, int level = 0,
                   const Executor& executor = default_executor());
// The same with a decode limit other than the default (DecodeLimits: 2^28 pixels at the
// decoded level); a stream whose decoded size exceeds it throws DecodeError before anything
// of that size is allocated.
Image decode_image(std::span<const std::uint8_t> bytes, int level, const Executor& executor,
                   const DecodeLimits& limits);

}  // namespace pupwave
