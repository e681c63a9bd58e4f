#include "codec/image/image_components.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <span>

#include "codec/image/image_metrics.h"

namespace pupwave {
namespace {

// Compacts the low-corner region of a plane in place (rows of size[0]); each row moves to
// an earlier position, so a forward copy never overwrites rows not yet moved.
template <class T>
void crop_in_place(std::vector<T>& plane, const Extent& dims, const Extent& size) {
  if (size == dims) return;
  for (std::size_t y = 0; y < size[1]; ++y)
    std::copy_n(plane.begin() + std::ptrdiff_t(y * dims[0]), size[0],
                plane.begin() + std::ptrdiff_t(y * size[0]));
  plane.resize(size[0] * size[1]);
  plane.shrink_to_fit();
}

// Rounds and clamps decoded values to what the sample type can hold.
float finish_sample(double v, SampleType type) {
  if (is_integer(type)) return float(std::clamp(std::nearbyint(v), 0.0, nominal_max(type)));
  if (type == SampleType::f16) return float(std::clamp(v, -65504.0, 65504.0));
  return float(v);
}

// finish_sample of n integer-type samples in place, written so the compiler vectorizes it (no
// libm call per sample): clamping before rounding gives the same value, since rounding is
// monotone and keeps the integer bounds, and adding and subtracting 2^52 rounds a double in
// [0, 2^52) to the nearest integer, ties to even, as std::nearbyint does.
void finish_integer_samples(float* p, std::size_t n, double shift, double top) {
  constexpr double kRound = 4503599627370496.0;  // 2^52
  for (std::size_t i = 0; i < n; ++i) {
    double v = double(p[i]) + shift;
    v = v < 0.0 ? 0.0 : v;
    v = v > top ? top : v;
    p[i] = float((v + kRound) - kRound);
  }
}

// Writes component planes to the output image, freeing each plane once written so the
// decoder never holds more than one full copy of the image besides the output.
template <class T>
void write_planes(std::vector<std::vector<T>>& planes, Image& out) {
  const double shift = level_shift(out.type);
  const std::size_t n = out.plane_size();
  for (std::size_t c = 0; c < planes.size(); ++c) {
    float* dst = out.plane(c);
    const T* src = planes[c].data();
    for (std::size_t i = 0; i < n; ++i) dst[i] = finish_sample(double(src[i]) + shift, out.type);
    std::vector<T>().swap(planes[c]);
  }
}

// Squared error of rows [y0, y0 + rows) of every component (planes of `rows` rows) against the
// reference, summed in compare_images' order (channel by channel, sample by sample) so the PSNR
// of the whole image is the same to the last bit.
template <class T>
double squared_error_after_colour(const ImageView& reference, std::size_t y0, std::size_t rows,
                                  const std::vector<std::vector<T>>& planes, bool clamp_at_zero = false) {
  const double shift = level_shift(reference.type);
  const std::size_t w = reference.width;
  std::vector<float> row(w);
  double sum_sq = 0.0;
  for (std::size_t c = 0; c < planes.size(); ++c)
    for (std::size_t y = 0; y < rows; ++y) {
      reference.read_row(c, y0 + y, row.data());
      const T* b = planes[c].data() + y * w;
      for (std::size_t x = 0; x < w; ++x) {
        float v = finish_sample(double(b[x]) + shift, reference.type);
        if (clamp_at_zero && v < 0.0f) v = 0.0f;  // as the decoder of a non-negative float stream does
        const double d = double(row[x]) - double(v);
        sum_sq += d * d;
      }
    }
  return sum_sq;
}

}  // namespace

ColourTransform colour_for(std::size_t channels, bool reversible) {
  if (channels < 3) return ColourTransform::none;
  return reversible ? ColourTransform::rct : ColourTransform::ict;
}

double level_shift(SampleType type) { return is_integer(type) ? (nominal_max(type) + 1.0) / 2.0 : 0.0; }

namespace {

// Runs body(y0, y1) over row ranges of an image of `height` rows of `width` samples, in
// parallel chunks of at least 2^16 samples (each row is independent of the others).
void for_row_chunks(const Executor& ex, std::size_t width, std::size_t height,
                    const std::function<void(std::size_t, std::size_t)>& body) {
  const std::size_t rows = std::max<std::size_t>(1, (std::size_t(1) << 16) / std::max<std::size_t>(width, 1));
  const std::size_t chunks = (height + rows - 1) / rows;
  ex.run(chunks, [&](std::size_t k) { body(k * rows, std::min(height, (k + 1) * rows)); });
}

}  // namespace

namespace {

// Sample k of pixel x in the row starting at p (channel k at k * channel_stride elements).
inline std::uint8_t byte_at(const std::uint8_t* p, const ImageView& v, std::size_t k, std::size_t x) {
  return p[std::ptrdiff_t(k) * v.channel_stride + std::ptrdiff_t(x) * v.pixel_stride];
}

// Component c of the ICT of rows [y0, y1) of 8-bit samples (a mapped PPM), without converting
// the three channels to float rows first: each byte value's product with its channel weight is
// tabulated (the double forward_ict_row forms), so a pixel costs three look-ups and the same
// two additions in the same order, and the result is forward_ict_row's to the bit.
void ict_rows_from_bytes(const ImageView& image, std::size_t c, std::size_t y0, std::size_t y1, float shift,
                         float* out, const Executor& ex) {
  const std::size_t w = image.width;
  const auto weight = forward_ict_weights(c);
  std::vector<double> table(3 * 256);
  for (std::size_t k = 0; k < 3; ++k)
    for (int v = 0; v < 256; ++v) table[k * 256 + std::size_t(v)] = weight[k] * double(float(v) - shift);
  const double *tr = table.data(), *tg = tr + 256, *tb = tg + 256;
  for_row_chunks(ex, w, y1 - y0, [&](std::size_t a, std::size_t b) {
    for (std::size_t y = a; y < b; ++y) {
      const auto* p =
          static_cast<const std::uint8_t*>(image.data) + std::ptrdiff_t(y0 + y) * image.row_stride;
      float* dst = out + y * w;
      for (std::size_t x = 0; x < w; ++x)
        dst[x] =
            float(tr[byte_at(p, image, 0, x)] + tg[byte_at(p, image, 1, x)] + tb[byte_at(p, image, 2, x)]);
    }
  });
}

// Component c of the RCT of rows [y0, y1) of 8-bit samples, in integers from the bytes.
void rct_rows_from_bytes(const ImageView& image, std::size_t c, std::size_t y0, std::size_t y1,
                         std::int32_t shift, std::int32_t* out, const Executor& ex) {
  const std::size_t w = image.width;
  for_row_chunks(ex, w, y1 - y0, [&](std::size_t a, std::size_t b) {
    for (std::size_t y = a; y < b; ++y) {
      const auto* p =
          static_cast<const std::uint8_t*>(image.data) + std::ptrdiff_t(y0 + y) * image.row_stride;
      std::int32_t* dst = out + y * w;
      for (std::size_t x = 0; x < w; ++x) {
        const std::int32_t rgb[3] = {std::int32_t(byte_at(p, image, 0, x)) - shift,
                                     std::int32_t(byte_at(p, image, 1, x)) - shift,
                                     std::int32_t(byte_at(p, image, 2, x)) - shift};
        forward_rct(rgb, c, dst + x);
      }
    }
  });
}

}  // namespace

void float_component_rows(const ImageView& image, ColourTransform colour, std::size_t c, std::size_t y0,
                          std::size_t y1, float* out, const Executor& ex) {
  const std::size_t w = image.width;
  const auto shift = float(level_shift(image.type));
  if (colour != ColourTransform::ict || c >= 3) {
    for_row_chunks(ex, w, y1 - y0, [&](std::size_t a, std::size_t b) {
      for (std::size_t y = a; y < b; ++y) {
        float* row = out + y * w;
        image.read_row(c, y0 + y, row);
        for (std::size_t x = 0; x < w; ++x) row[x] -= shift;
      }
    });
    return;
  }
  if (image.storage == StorageType::u8) return ict_rows_from_bytes(image, c, y0, y1, shift, out, ex);
  for_row_chunks(ex, w, y1 - y0, [&](std::size_t a, std::size_t b) {
    std::vector<float> rows(3 * w);
    for (std::size_t y = a; y < b; ++y) {
      for (std::size_t k = 0; k < 3; ++k) image.read_row(k, y0 + y, rows.data() + k * w);
      const float* const rgb[3] = {rows.data(), rows.data() + w, rows.data() + 2 * w};
      forward_ict_row(rgb, shift, c, out + y * w, w);
    }
  });
}

void integer_component_rows(const ImageView& image, ColourTransform colour, std::size_t c, std::size_t y0,
                            std::size_t y1, std::int32_t* out, const Executor& ex) {
  const std::size_t w = image.width;
  const auto shift = std::int32_t(level_shift(image.type));
  const std::size_t used = colour == ColourTransform::rct && c < 3 ? 3 : 1;
  if (used == 3 && image.storage == StorageType::u8)
    return rct_rows_from_bytes(image, c, y0, y1, shift, out, ex);
  for_row_chunks(ex, w, y1 - y0, [&](std::size_t a, std::size_t b) {
    std::vector<float> rows(used * w);
    for (std::size_t y = a; y < b; ++y) {
      std::int32_t* dst = out + y * w;
      if (used == 1) {
        image.read_row(c, y0 + y, rows.data());
        for (std::size_t x = 0; x < w; ++x) dst[x] = std::int32_t(rows[x]) - shift;
        continue;
      }
      for (std::size_t k = 0; k < 3; ++k) image.read_row(k, y0 + y, rows.data() + k * w);
      for (std::size_t x = 0; x < w; ++x) {
        const std::int32_t rgb[3] = {std::int32_t(rows[x]) - shift, std::int32_t(rows[w + x]) - shift,
                                     std::int32_t(rows[2 * w + x]) - shift};
        forward_rct(rgb, c, dst + x);
      }
    }
  });
}

void float_component(const ImageView& image, ColourTransform colour, std::size_t c, std::vector<float>& out,
                     const Executor& ex) {
  out.resize(image.plane_size());
  float_component_rows(image, colour, c, 0, image.height, out.data(), ex);
}

void integer_component(const ImageView& image, ColourTransform colour, std::size_t c,
                       std::vector<std::int32_t>& out, const Executor& ex) {
  out.resize(image.plane_size());
  integer_component_rows(image, colour, c, 0, image.height, out.data(), ex);
}

std::vector<double> component_weights(std::size_t channels, ColourTransform colour) {
  std::vector<double> w(channels, 1.0);
  if (colour == ColourTransform::ict) {
    const auto ict = ict_error_weights();
    std::copy(ict.begin(), ict.end(), w.begin());
  }
  return w;
}

double coarse_gain(const Transform1D& t, const Extent& dims, int level) {
  double gain = 1.0;
  for (std::size_t n : dims) {
    if (n <= 1) continue;
    std::vector<double> line(n, 1.0);
    std::size_t len = n;
    for (int l = 0; l < level && len > 1; ++l) {
      t.analyze(std::span<double>(line.data(), len));
      len = coarse_size(len);
    }
    gain *= line[len / 2];  // a constant line has a constant coarse band
  }
  return gain;
}

Image image_from_components(std::vector<std::vector<float>>& planes, const Extent& dims, const Extent& size,
                            SampleType type, ColourTransform colour, double gain) {
  for (auto& p : planes) {
    crop_in_place(p, dims, size);
    if (gain != 1.0)  // dividing by exactly 1 would change no value
      for (float& v : p) v = float(double(v) / gain);
  }
  Image out(size[0], size[1], planes.size(), type);
  if (colour == ColourTransform::ict)
    inverse_ict(planes[0].data(), planes[1].data(), planes[2].data(), out.plane_size());
  write_planes(planes, out);
  return out;
}

Image image_from_components(std::vector<std::vector<std::int32_t>>& planes, const Extent& dims,
                            const Extent& size, SampleType type, ColourTransform colour) {
  for (auto& p : planes) crop_in_place(p, dims, size);
  Image out(size[0], size[1], planes.size(), type);
  if (colour == ColourTransform::rct)
    inverse_rct(planes[0].data(), planes[1].data(), planes[2].data(), out.plane_size());
  write_planes(planes, out);
  return out;
}

void finish_image_in_place(Image& image, ColourTransform colour, const Executor& ex) {
  constexpr std::size_t kRun = std::size_t(1) << 16;  // samples per task
  const std::size_t n = image.plane_size();
  const double shift = level_shift(image.type);
  ex.run((n + kRun - 1) / kRun, [&](std::size_t k) {
    const std::size_t first = k * kRun, count = std::min(kRun, n - first);
    if (colour == ColourTransform::ict)
      inverse_ict(image.plane(0) + first, image.plane(1) + first, image.plane(2) + first, count);
    for (std::size_t c = 0; c < image.channels; ++c) {
      float* p = image.plane(c) + first;
      if (is_integer(image.type)) {
        finish_integer_samples(p, count, shift, nominal_max(image.type));
        continue;
      }
      for (std::size_t i = 0; i < count; ++i) p[i] = finish_sample(double(p[i]) + shift, image.type);
    }
  });
}

double components_squared_error(const ImageView& reference, std::size_t y0, std::size_t rows,
                                std::vector<std::vector<float>>& planes, ColourTransform colour,
                                bool clamp_at_zero) {
  if (colour == ColourTransform::ict)
    inverse_ict(planes[0].data(), planes[1].data(), planes[2].data(), rows * reference.width);
  return squared_error_after_colour(reference, y0, rows, planes, clamp_at_zero);
}

double components_squared_error(const ImageView& reference, std::size_t y0, std::size_t rows,
                                std::vector<std::vector<std::int32_t>>& planes, ColourTransform colour) {
  if (colour == ColourTransform::rct)
    inverse_rct(planes[0].data(), planes[1].data(), planes[2].data(), rows * reference.width);
  return squared_error_after_colour(reference, y0, rows, planes);
}

double psnr_of_squared_error(const ImageView& reference, double sum_sq) {
  const std::size_t count = reference.plane_size() * reference.channels;
  return psnr_from_mse(count ? sum_sq / double(count) : 0.0, psnr_peak(reference));
}

double components_psnr(const ImageView& reference, std::vector<std::vector<float>>& planes,
                       ColourTransform colour, bool clamp_at_zero) {
  return psnr_of_squared_error(
      reference, components_squared_error(reference, 0, reference.height, planes, colour, clamp_at_zero));
}

double components_psnr(const ImageView& reference, std::vector<std::vector<std::int32_t>>& planes,
                       ColourTransform colour) {
  return psnr_of_squared_error(reference,
                               components_squared_error(reference, 0, reference.height, planes, colour));
}

}  // namespace pupwave
