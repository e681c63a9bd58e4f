#include "codec/rate/rdoq.h"

#include <algorithm>
#include <cmath>

namespace pupwave {

int last_cleanup_plane(int planes, int passes) {
  if (passes <= 0 || planes <= 0) return -1;
  // Pass 1 is the top plane's cleanup; pass 1 + 3k is the cleanup of plane planes - 1 - k.
  return planes - 1 - (passes - 1) / 3;
}

std::size_t pull_isolated(std::span<float> magnitude, const Extent& size, int plane, double delta,
                          double max_gain) {
  if (plane < 0) return 0;
  const float w = std::ldexp(1.0f, plane);
  // Just under the plane: the block then codes the coefficient in the next plane down.
  const float below = std::nextafter(w, 0.0f);
  const double reconstruction = (1.0 + delta) * double(w);
  const std::size_t nx = size[0], ny = size[1];
  std::size_t changed = 0;
  for (std::size_t z = 0; z < size[2]; ++z) {
    float* slice = magnitude.data() + z * nx * ny;
    for (std::size_t y = 0; y < ny; ++y)
      for (std::size_t x = 0; x < nx; ++x) {
        const float m = slice[x + y * nx];
        if (!(m >= w && m < 2.0f * w)) continue;
        const double d = double(m) - reconstruction;
        if (double(m) * double(m) - d * d >= max_gain) continue;
        bool alone = true;
        for (std::size_t v = y > 0 ? y - 1 : 0; alone && v <= std::min(y + 1, ny - 1); ++v)
          for (std::size_t u = x > 0 ? x - 1 : 0; u <= std::min(x + 1, nx - 1); ++u)
            if ((u != x || v != y) && slice[u + v * nx] >= w) {
              alone = false;
              break;
            }
        if (!alone) continue;
        slice[x + y * nx] = below;
        ++changed;
      }
  }
  return changed;
}

}  // namespace pupwave
