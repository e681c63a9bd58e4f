#pragma once
// Strip-wise image decoding: the inverse wavelet transform runs over horizontal strips, level
// by level, decoding each subband's code-blocks one block row at a time as the strips reach
// them, so the image is never whole in memory (the whole-image decoder holds every component
// plane in float). Each level keeps only the rows its next strip still needs: a strip of
// output rows needs the rows within the synthesis reach of it at the next coarser level
// (windowed lifting gives the same samples as the whole line, bit for bit, wherever the
// window holds every coefficient the sample depends on). Pixels are identical to decode_image.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "codec/image/image.h"
#include "codec/image/image_stream.h"
#include "codec/image/image_view.h"
#include "transforms/executor.h"
#include "transforms/transform1d.h"

namespace pupwave {

// Block i of a parsed stream decoded and dequantized into rows of `stride` samples starting at
// `first` (zeros for a block with no passes). T is float (irreversible) or int32_t.
template <class T>
void decode_block_at(const ParsedStream& s, std::size_t i, T* first, std::size_t stride);

// What an image decoded from a stream with header `h` at 1/2^level size keeps besides its
// samples: channel names and attributes, and the windows at full size only (they are those of
// the full-size image).
ImageMetadata decoded_metadata(const StreamHeader& h, int level);

// measure_psnr's figure (the PSNR of the stream's full-resolution decode against `reference`,
// compared in the coded domain), decoded and compared strip by strip so that no component plane
// is ever whole; nullopt where the stream cannot be decoded by strips (lc and pc blocks need
// their parent bands, a transform whose synthesis is not local). Equal to the whole-plane
// figure up to the order of the additions.
std::optional<double> strip_psnr(const ImageView& reference, const ParsedStream& s, const Executor& ex);

class ImageStripDecoder {
 public:
  // A decoder for an integer-sample image stream at 1/2^level size, or null when the stream is
  // not strip-decodable (float samples, a transform whose synthesis is not local): use
  // decode_image then. Throws what decode_image throws for a bad stream or level. `bytes` and
  // `ex` must outlive the decoder.
  static std::unique_ptr<ImageStripDecoder> open(std::span<const std::uint8_t> bytes, int level,
                                                 const Executor& ex, const DecodeLimits& limits);
  ~ImageStripDecoder();
  ImageStripDecoder(const ImageStripDecoder&) = delete;
  ImageStripDecoder& operator=(const ImageStripDecoder&) = delete;

  std::size_t width() const;
  std::size_t height() const;
  std::size_t channels() const;
  SampleType type() const;
  // The decoded image's metadata (decoded_metadata).
  ImageMetadata metadata() const;

  // The next rows of the decoded image (at most `rows`, at least 1 until the end) as an image
  // of width() columns, samples rounded and clamped as decode_image's; height 0 at the end.
  Image next(std::size_t rows = 64);

 private:
  struct State;
  explicit ImageStripDecoder(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace pupwave
