#include "codec/image_components.h"

#include <algorithm>
#include <cmath>
#include <span>

namespace pupwave {
namespace {

// Copies the low-corner region of a plane into a compact one (rows of size[0]).
template <class T>
std::vector<T> crop(const std::vector<T>& plane, const Extent& dims, const Extent& size) {
  if (size == dims) return plane;
  std::vector<T> out(size[0] * size[1]);
  for (std::size_t y = 0; y < size[1]; ++y)
    std::copy_n(plane.begin() + std::ptrdiff_t(y * dims[0]), size[0],
                out.begin() + std::ptrdiff_t(y * size[0]));
  return out;
}

// Rounds and clamps decoded values to what the sample type can hold.
float finish_sample(double v, SampleType type) {
  if (is_integer(type)) return float(std::clamp(std::nearbyint(v), 0.0, nominal_max(type)));
  if (type == SampleType::f16) return float(std::clamp(v, -65504.0, 65504.0));
  return float(v);
}

}  // namespace

ColourTransform colour_for(std::size_t channels, bool reversible) {
  if (channels < 3) return ColourTransform::none;
  return reversible ? ColourTransform::rct : ColourTransform::ict;
}

double level_shift(SampleType type) { return is_integer(type) ? (nominal_max(type) + 1.0) / 2.0 : 0.0; }

std::vector<std::vector<float>> float_components(const Image& image, ColourTransform colour) {
  const std::size_t n = image.plane_size();
  const auto shift = float(level_shift(image.type));
  std::vector<std::vector<float>> planes(image.channels);
  for (std::size_t c = 0; c < image.channels; ++c) {
    planes[c].assign(image.plane(c), image.plane(c) + n);
    for (float& v : planes[c]) v -= shift;
  }
  if (colour == ColourTransform::ict) forward_ict(planes[0].data(), planes[1].data(), planes[2].data(), n);
  return planes;
}

std::vector<std::vector<std::int32_t>> integer_components(const Image& image, ColourTransform colour) {
  const std::size_t n = image.plane_size();
  const auto shift = std::int32_t(level_shift(image.type));
  std::vector<std::vector<std::int32_t>> planes(image.channels, std::vector<std::int32_t>(n));
  for (std::size_t c = 0; c < image.channels; ++c)
    for (std::size_t i = 0; i < n; ++i) planes[c][i] = std::int32_t(image.plane(c)[i]) - shift;
  if (colour == ColourTransform::rct) forward_rct(planes[0].data(), planes[1].data(), planes[2].data(), n);
  return planes;
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
  Image out(size[0], size[1], planes.size(), type);
  const std::size_t n = out.plane_size();
  std::vector<std::vector<float>> cropped;
  for (auto& p : planes) {
    cropped.push_back(crop(p, dims, size));
    for (float& v : cropped.back()) v = float(double(v) / gain);
  }
  if (colour == ColourTransform::ict) inverse_ict(cropped[0].data(), cropped[1].data(), cropped[2].data(), n);
  const double shift = level_shift(type);
  for (std::size_t c = 0; c < planes.size(); ++c)
    for (std::size_t i = 0; i < n; ++i) out.plane(c)[i] = finish_sample(double(cropped[c][i]) + shift, type);
  return out;
}

Image image_from_components(std::vector<std::vector<std::int32_t>>& planes, const Extent& dims,
                            const Extent& size, SampleType type, ColourTransform colour) {
  Image out(size[0], size[1], planes.size(), type);
  const std::size_t n = out.plane_size();
  std::vector<std::vector<std::int32_t>> cropped;
  for (auto& p : planes) cropped.push_back(crop(p, dims, size));
  if (colour == ColourTransform::rct) inverse_rct(cropped[0].data(), cropped[1].data(), cropped[2].data(), n);
  const double shift = level_shift(type);
  for (std::size_t c = 0; c < planes.size(); ++c)
    for (std::size_t i = 0; i < n; ++i) out.plane(c)[i] = finish_sample(double(cropped[c][i]) + shift, type);
  return out;
}

}  // namespace pupwave
