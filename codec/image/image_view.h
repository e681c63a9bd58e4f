#pragma once
// The image encoder's input: a non-owning, typed, strided view of samples in the caller's
// memory (planar, interleaved, padded rows, any channel order), so a caller never copies or
// converts an image to hand it to the codec. The owning Image (image.h) is what decoders
// return; view_of() views one.

#include <cstddef>
#include <cstdint>

#include "codec/image/image.h"

namespace pupwave {

// How samples are laid out in memory.
enum class StorageType : std::uint8_t {
  u8 = 0,   // std::uint8_t
  u16 = 1,  // std::uint16_t
  f16 = 2,  // IEEE 754 binary16 bits in a std::uint16_t
  f32 = 3,  // float
};

// Bytes of one stored sample (1, 2, 2, 4).
std::size_t bytes_per_sample(StorageType storage);

// Sample (c, x, y) is the `storage` element at
//   data + c * channel_stride + x * pixel_stride + y * row_stride   (strides in elements).
// `type` is what the samples are (and what the stream records): an 8-bit image may be held as
// u8 or, as Image holds every type, as float values 0..255.
struct ImageView {
  const void* data = nullptr;
  std::size_t width = 0;
  std::size_t height = 0;
  std::size_t channels = 0;
  SampleType type = SampleType::u8;
  StorageType storage = StorageType::u8;
  std::ptrdiff_t channel_stride = 0;
  std::ptrdiff_t pixel_stride = 0;
  std::ptrdiff_t row_stride = 0;
  // PSNR peak of these samples if > 0 (a float image in the log transfer domain: 1 stop);
  // 0: derived from the type and the samples (psnr_peak).
  double peak = 0.0;
  // Optional, for views of a file mapped read-only: called (with drop_context) for rows
  // [y0, y1) the strip-wise encoder has read for now, so their pages can leave the process's
  // resident memory (read again, they come back from the page cache). Null: nothing is dropped.
  void (*drop_rows)(const void* context, const ImageView& view, std::size_t y0, std::size_t y1) = nullptr;
  const void* drop_context = nullptr;

  std::size_t plane_size() const { return width * height; }
  // Sample (c, x, y) as float (exact for every supported type).
  float at(std::size_t c, std::size_t x, std::size_t y) const;
  // Row y of channel c as width floats.
  void read_row(std::size_t c, std::size_t y, float* out) const;
};

// Interleaved samples (pixel after pixel, channels adjacent), rows of `row_stride` elements
// (0: width * channels), stored as the sample type itself.
ImageView interleaved_view(const void* data, std::size_t width, std::size_t height, std::size_t channels,
                           SampleType type, std::ptrdiff_t row_stride = 0);
// Planar samples (plane after plane), stored as the sample type itself.
ImageView planar_view(const void* data, std::size_t width, std::size_t height, std::size_t channels,
                      SampleType type);
// A view of an owning Image (planar float).
ImageView view_of(const Image& image);

// Throws std::invalid_argument naming the problem for a view that cannot be read: null data,
// zero strides where the extent needs them, a storage that cannot hold the type (u16 for 8-bit
// is fine; u8 for 16-bit, or integer storage for float samples, is not).
void check_view(const ImageView& view);

// binary16 bits to float (every half value, subnormals and infinities included, exactly).
float half_to_float(std::uint16_t bits);

}  // namespace pupwave
