#include "codec/image/image_view.h"

#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace pupwave {
namespace {

template <class T>
T load(const void* base, std::ptrdiff_t index) {
  T v;
  std::memcpy(&v, static_cast<const unsigned char*>(base) + index * std::ptrdiff_t(sizeof(T)), sizeof(T));
  return v;
}

// One row of samples `stride` elements apart.
template <class T>
void copy_row_strided(const void* data, std::ptrdiff_t first, std::size_t width, std::ptrdiff_t stride,
                      float* out) {
  for (std::size_t x = 0; x < width; ++x) out[x] = float(load<T>(data, first + std::ptrdiff_t(x) * stride));
}

// Every byte value as float: a table look-up per sample is cheaper than the integer-to-float
// conversion (which GCC's SSE2 code for interleaved strides assembles through the stack).
struct ByteFloats {
  float value[256];
  constexpr ByteFloats() : value() {
    for (int i = 0; i < 256; ++i) value[i] = float(i);
  }
};
constexpr ByteFloats kByteFloats;

template <class T>
void copy_row(const ImageView& v, std::ptrdiff_t first, float* out) {
  if (v.pixel_stride == 1) return copy_row_strided<T>(v.data, first, v.width, 1, out);  // vectorizes
  if constexpr (std::is_same_v<T, std::uint8_t>) {
    const auto* p = static_cast<const std::uint8_t*>(v.data) + first;
    for (std::size_t x = 0; x < v.width; ++x)
      out[x] = kByteFloats.value[p[std::ptrdiff_t(x) * v.pixel_stride]];
    return;
  }
  copy_row_strided<T>(v.data, first, v.width, v.pixel_stride, out);
}

bool storage_holds(StorageType storage, SampleType type) {
  switch (type) {
    case SampleType::u8: return true;
    case SampleType::u16: return storage != StorageType::u8;
    case SampleType::f16: return storage == StorageType::f16 || storage == StorageType::f32;
    case SampleType::f32: return storage == StorageType::f32;
  }
  return false;
}

}  // namespace

std::size_t bytes_per_sample(StorageType storage) {
  return storage == StorageType::u8 ? 1 : storage == StorageType::f32 ? 4 : 2;
}

float half_to_float(std::uint16_t bits) {
  const std::uint32_t sign = std::uint32_t(bits & 0x8000u) << 16;
  const std::uint32_t exponent = (bits >> 10) & 0x1Fu;
  std::uint32_t mantissa = bits & 0x3FFu;
  if (exponent == 0x1F) return std::bit_cast<float>(sign | 0x7F800000u | (mantissa << 13));  // inf, NaN
  if (exponent != 0) return std::bit_cast<float>(sign | ((exponent + 112u) << 23) | (mantissa << 13));
  if (mantissa == 0) return std::bit_cast<float>(sign);
  // Subnormal half: value = mantissa * 2^-24, exact in binary32.
  const float magnitude = float(mantissa) * 0x1p-24f;
  return sign ? -magnitude : magnitude;
}

float ImageView::at(std::size_t c, std::size_t x, std::size_t y) const {
  const std::ptrdiff_t i =
      std::ptrdiff_t(c) * channel_stride + std::ptrdiff_t(x) * pixel_stride + std::ptrdiff_t(y) * row_stride;
  switch (storage) {
    case StorageType::u8: return float(load<std::uint8_t>(data, i));
    case StorageType::u16: return float(load<std::uint16_t>(data, i));
    case StorageType::f16: return half_to_float(load<std::uint16_t>(data, i));
    case StorageType::f32: return load<float>(data, i);
  }
  return 0.0f;
}

void ImageView::read_row(std::size_t c, std::size_t y, float* out) const {
  const std::ptrdiff_t first = std::ptrdiff_t(c) * channel_stride + std::ptrdiff_t(y) * row_stride;
  switch (storage) {
    case StorageType::u8: return copy_row<std::uint8_t>(*this, first, out);
    case StorageType::u16: return copy_row<std::uint16_t>(*this, first, out);
    case StorageType::f16:
      for (std::size_t x = 0; x < width; ++x)
        out[x] = half_to_float(load<std::uint16_t>(data, first + std::ptrdiff_t(x) * pixel_stride));
      return;
    case StorageType::f32:
      if (pixel_stride == 1) {  // the common planar float case: one copy
        std::memcpy(out, static_cast<const float*>(data) + first, width * sizeof(float));
        return;
      }
      return copy_row<float>(*this, first, out);
  }
}

ImageView interleaved_view(const void* data, std::size_t width, std::size_t height, std::size_t channels,
                           SampleType type, std::ptrdiff_t row_stride) {
  ImageView v{data,      width, height, channels, type, StorageType(type), 1, std::ptrdiff_t(channels),
              row_stride};
  if (row_stride == 0) v.row_stride = std::ptrdiff_t(width * channels);
  return v;
}

ImageView planar_view(const void* data, std::size_t width, std::size_t height, std::size_t channels,
                      SampleType type) {
  return ImageView{data,
                   width,
                   height,
                   channels,
                   type,
                   StorageType(type),
                   std::ptrdiff_t(width * height),
                   1,
                   std::ptrdiff_t(width)};
}

ImageView view_of(const Image& image) {
  return ImageView{image.samples.data(),
                   image.width,
                   image.height,
                   image.channels,
                   image.type,
                   StorageType::f32,
                   std::ptrdiff_t(image.plane_size()),
                   1,
                   std::ptrdiff_t(image.width)};
}

void check_view(const ImageView& v) {
  if (v.width == 0 || v.height == 0 || v.channels == 0) return;  // the encoder reports empty images
  if (v.data == nullptr) throw std::invalid_argument("image view: null data pointer");
  if (int(v.storage) > 3 || int(v.type) > 3) throw std::invalid_argument("image view: unknown sample type");
  if (!storage_holds(v.storage, v.type))
    throw std::invalid_argument(
        "image view: " + to_string(v.type) + " samples cannot be stored as " +
        std::to_string(bytes_per_sample(v.storage) * 8) + "-bit " +
        (v.storage == StorageType::f16 || v.storage == StorageType::f32 ? "float" : "integers"));
  if ((v.width > 1 && v.pixel_stride == 0) || (v.height > 1 && v.row_stride == 0) ||
      (v.channels > 1 && v.channel_stride == 0))
    throw std::invalid_argument("image view: a zero stride along an axis of extent > 1");
}

}  // namespace pupwave
