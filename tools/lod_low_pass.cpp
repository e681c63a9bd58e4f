#include "tools/lod_low_pass.h"

#include <cmath>
#include <random>
#include <span>
#include <stdexcept>
#include <string>

namespace pupwave::cli {

LowPass low_pass_of(const Transform1D& t) {
  constexpr int kLine = 256, kMid = 128, kMaxRadius = 24;
  std::vector<double> g(2 * kMaxRadius + 1, 0.0);
  for (int parity = 0; parity < 2; ++parity) {
    std::vector<double> line(kLine, 0.0);
    const int n0 = kMid + parity;
    line[std::size_t(n0)] = 1.0;
    t.analyze(std::span<double>(line));
    for (int c = 0; c < kLine / 2; ++c)
      if (std::abs(n0 - 2 * c) <= kMaxRadius) g[std::size_t(n0 - 2 * c + kMaxRadius)] = line[std::size_t(c)];
  }
  LowPass h;
  for (int d = 0; d <= kMaxRadius; ++d)
    if (std::abs(g[std::size_t(kMaxRadius + d)]) > 1e-12 || std::abs(g[std::size_t(kMaxRadius - d)]) > 1e-12)
      h.radius = d;
  h.taps.assign(g.begin() + (kMaxRadius - h.radius), g.begin() + (kMaxRadius + h.radius + 1));
  h.gain = 0.0;
  for (double tap : h.taps) h.gain += tap;
  if (!(std::abs(h.gain) > 1e-3))
    throw std::runtime_error("transform " + t.spec() + " has no usable coarse-band response to a constant");
  // The interior of a random line must be exactly this filter, or the transform is not one.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x(kLine), y;
  for (double& v : x) v = u(rng);
  y = x;
  t.analyze(std::span<double>(y));
  for (int c = kMaxRadius; c < kLine / 2 - kMaxRadius; ++c) {
    double sum = 0.0;
    for (int d = -h.radius; d <= h.radius; ++d)
      sum += h.taps[std::size_t(d + h.radius)] * x[std::size_t(2 * c + d)];
    if (std::abs(sum - y[std::size_t(c)]) > 1e-9)
      throw std::runtime_error("transform " + t.spec() +
                               " is not a linear shift-invariant filter bank, which lod needs");
  }
  return h;
}

}  // namespace pupwave::cli
