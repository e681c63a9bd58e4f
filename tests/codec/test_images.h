#pragma once
// Synthetic test images for the codec tests: smooth shading, edges and texture, so every
// subband carries signal, in any shape, channel count and sample type.

#include <cmath>
#include <cstdint>
#include <random>

#include "codec/image/image.h"

namespace pupwave::testing {

inline Image synthetic_image(std::size_t w, std::size_t h, std::size_t channels, SampleType type,
                             unsigned seed = 1) {
  Image img(w, h, channels, type);
  std::mt19937 rng(seed);
  // Raw engine output (not std::*_distribution) keeps the images identical across standard
  // libraries, which the golden stream checksums rely on.
  auto noise = [&rng] { return (double(rng()) / 4294967296.0 - 0.5) * 0.07; };
  const double max = nominal_max(type);
  for (std::size_t c = 0; c < channels; ++c)
    for (std::size_t y = 0; y < h; ++y)
      for (std::size_t x = 0; x < w; ++x) {
        const double fx = double(x) / double(w), fy = double(y) / double(h);
        double v = 0.5 + 0.25 * std::sin(6.0 * fx + 2.0 * double(c)) * std::cos(4.0 * fy);
        if ((x / 16 + y / 16 + c) % 2 == 0) v += 0.12;  // edges
        v += 0.05 * std::sin(double(x * x + y) * 0.05) + noise();
        v = std::clamp(v, 0.0, 1.0) * max;
        if (is_integer(type)) v = std::round(v);
        if (c == 3) v = (x < w / 2) ? max : std::round(max * 0.25);  // alpha: two flat regions
        img.at(c, x, y) = float(v);
      }
  return img;
}

}  // namespace pupwave::testing
