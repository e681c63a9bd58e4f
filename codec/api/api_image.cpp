// The public image API (pupwave/pupwave.hpp) over codec/image/image_codec.h: views are mapped
// onto the codec's strided ImageView, so encoding never copies the caller's samples.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>

#include "codec/api/api_attributes.h"
#include "codec/api/api_errors.h"
#include "codec/api/api_image_options.h"
#include "codec/image/image_codec.h"
#include "pupwave/pupwave.hpp"

namespace pupwave::api {
namespace {

pupwave::SampleType internal_type(SampleType type) {
  switch (type) {
    case SampleType::u8: return pupwave::SampleType::u8;
    case SampleType::u16: return pupwave::SampleType::u16;
    case SampleType::f16: return pupwave::SampleType::f16;
    case SampleType::f32: return pupwave::SampleType::f32;
  }
  detail::fail("unknown sample type " + std::to_string(int(type)));
}

SampleType public_type(pupwave::SampleType type) {
  switch (type) {
    case pupwave::SampleType::u8: return SampleType::u8;
    case pupwave::SampleType::u16: return SampleType::u16;
    case pupwave::SampleType::f16: return SampleType::f16;
    case pupwave::SampleType::f32: break;
  }
  return SampleType::f32;
}

// Round-to-nearest-even binary32 -> binary16 (decoded values are already in half range).
std::uint16_t float_to_half(float value) {
  const std::uint32_t f = std::bit_cast<std::uint32_t>(value);
  const std::uint32_t sign = (f >> 16) & 0x8000u;
  const std::uint32_t abs = f & 0x7fffffffu;
  if (abs >= 0x7f800000u) return std::uint16_t(sign | 0x7c00u | (abs > 0x7f800000u ? 0x200u : 0u));
  if (abs >= 0x477ff000u) return std::uint16_t(sign | 0x7c00u);    // rounds past 65504: infinity
  if (abs < 0x38800000u) {                                         // subnormal half (or zero)
    const float scaled = std::bit_cast<float>(abs) * 16777216.0f;  // units of 2^-24, exact
    return std::uint16_t(sign | std::uint32_t(std::nearbyint(scaled)));
  }
  const std::uint32_t mantissa_lsb = (abs >> 13) & 1u;
  const std::uint32_t rounded = abs + 0xfffu + mantissa_lsb;  // ties to even
  return std::uint16_t(sign | ((rounded - 0x38000000u) >> 13));
}

template <class T>
void store_interleaved(const pupwave::Image& image, std::byte* out) {
  T* dst = reinterpret_cast<T*>(out);
  const std::size_t n = image.plane_size();
  for (std::size_t c = 0; c < image.channels; ++c) {
    const float* src = image.plane(c);
    for (std::size_t i = 0; i < n; ++i) {
      if constexpr (std::is_same_v<T, float>)
        dst[i * image.channels + c] = src[i];
      else if constexpr (std::is_same_v<T, std::uint8_t>)
        dst[i * image.channels + c] = T(std::clamp(std::nearbyint(src[i]), 0.0f, 255.0f));
      else if (image.type == pupwave::SampleType::f16)
        dst[i * image.channels + c] = float_to_half(src[i]);
      else
        dst[i * image.channels + c] = T(std::clamp(std::nearbyint(src[i]), 0.0f, 65535.0f));
    }
  }
}

}  // namespace

std::size_t bytes_per_sample(SampleType type) {
  return pupwave::bytes_per_sample(StorageType(internal_type(type)));
}

ImageView interleaved_view(const void* data, std::size_t width, std::size_t height, std::size_t channels,
                           SampleType type, std::ptrdiff_t row_stride) {
  const auto c = std::ptrdiff_t(channels);
  return {data, width, height, channels, type, 1, c, row_stride ? row_stride : std::ptrdiff_t(width) * c};
}

ImageView planar_view(const void* data, std::size_t width, std::size_t height, std::size_t channels,
                      SampleType type) {
  return {data, width, height, channels, type, std::ptrdiff_t(width * height), 1, std::ptrdiff_t(width)};
}

std::vector<std::uint8_t> compress_image(const ImageView& image, const ImageOptions& options) {
  TargetOutcome ignored;
  return compress_image(image, options, ignored);
}

std::vector<std::uint8_t> compress_image(const ImageView& image, const ImageOptions& options,
                                         TargetOutcome& outcome) {
  return detail::translate_errors([&] {
    EncodeOptions enc = resolve_image_options(options);
    detail::check_attributes(options.attributes);
    const ImageMetadata metadata = detail::image_metadata(options.attributes);
    if (!metadata.empty()) enc.metadata = &metadata;  // no META chunk without attributes
    const std::unique_ptr<Executor> executor = make_pool_executor(options.threads);
    enc.executor = executor.get();
    pupwave::ImageView view;
    view.data = image.data;
    view.width = image.width;
    view.height = image.height;
    view.channels = image.channels;
    view.type = internal_type(image.type);
    view.storage = StorageType(view.type);  // each public type is stored as itself
    view.channel_stride = image.channel_stride;
    view.pixel_stride = image.pixel_stride;
    view.row_stride = image.row_stride;
    EncodeResult r = encode_resolved(view, enc, options.coder);
    outcome.met = r.target_met;
    outcome.achieved = enc.mode == RateMode::bpp    ? r.bpp
                       : enc.mode == RateMode::psnr ? r.psnr
                                                    : std::numeric_limits<double>::quiet_NaN();
    return std::move(r.bytes);
  });
}

Image decompress_image(std::span<const std::uint8_t> stream, int level, unsigned threads) {
  return detail::translate_errors([&] {
    if (level < 0) detail::fail("level must be >= 0, got " + std::to_string(level));
    const std::unique_ptr<Executor> executor = make_pool_executor(threads);
    const pupwave::Image decoded = decode_image(stream, level, *executor);
    Image out;
    out.width = decoded.width;
    out.height = decoded.height;
    out.channels = decoded.channels;
    out.type = public_type(decoded.type);
    out.attributes = detail::text_attributes(decoded.metadata);
    out.data.resize(decoded.samples.size() * bytes_per_sample(out.type));
    switch (out.type) {
      case SampleType::u8: store_interleaved<std::uint8_t>(decoded, out.data.data()); break;
      case SampleType::u16:
      case SampleType::f16: store_interleaved<std::uint16_t>(decoded, out.data.data()); break;
      case SampleType::f32: store_interleaved<float>(decoded, out.data.data()); break;
    }
    return out;
  });
}

}  // namespace pupwave::api
