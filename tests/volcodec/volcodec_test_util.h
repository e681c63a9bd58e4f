#pragma once
// Test volumes for the volume codec tests: smooth fields with noise, integer volumes, a sparse
// level set, and independent error measures.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <random>
#include <vector>

#include "codec/volume/volume.h"

namespace pupwave::test {

// testimages/wmag91.float: the real 91^3 float field (testimages/README.md).
inline Volume read_wmag91() {
  Volume v({91, 91, 91}, VoxelType::f32);
  std::ifstream in(PUPWAVE_TESTIMAGES_DIR "/wmag91.float", std::ios::binary);
  std::vector<float> raw(v.count());
  in.read(reinterpret_cast<char*>(raw.data()), std::streamsize(raw.size() * 4));
  EXPECT_TRUE(in.good()) << "cannot read wmag91.float";
  for (std::size_t i = 0; i < raw.size(); ++i) v.samples[i] = raw[i];
  return v;
}

// A smooth field (sum of waves) plus a little noise, of `type` (integer types are rounded).
inline Volume smooth_volume(const Extent& dims, VoxelType type, double scale, unsigned seed = 7) {
  Volume v(dims, type);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.02);
  for (std::size_t z = 0; z < dims[2]; ++z)
    for (std::size_t y = 0; y < dims[1]; ++y)
      for (std::size_t x = 0; x < dims[0]; ++x) {
        const double s =
            std::sin(0.31 * double(x) + 0.2 * double(y)) * std::cos(0.17 * double(z) - 0.1 * double(x)) +
            0.5 * std::sin(0.05 * double(x * y + z)) + noise(rng);
        double value = scale * (1.2 + s) / 2.4;
        if (type == VoxelType::f32) value = double(float(value));
        if (type == VoxelType::u8 || type == VoxelType::u16)
          value = std::round(std::clamp(value, 0.0, scale));
        v.at(x, y, z) = value;
      }
  return v;
}

// A level set of a sphere over `dims`: active within `band` voxels of the surface, inactive
// voxels at +background outside and -background inside; a few inactive voxels hold other values.
inline Volume sphere_level_set(const Extent& dims, double radius, double band, double background) {
  Volume v(dims, VoxelType::f32);
  v.background = background;
  v.active.assign(v.count(), 0);
  const double c[3] = {double(dims[0]) / 2.0, double(dims[1]) / 2.0, double(dims[2]) / 2.0};
  for (std::size_t z = 0; z < dims[2]; ++z)
    for (std::size_t y = 0; y < dims[1]; ++y)
      for (std::size_t x = 0; x < dims[0]; ++x) {
        const double d = std::hypot(double(x) - c[0], double(y) - c[1], double(z) - c[2]) - radius;
        const std::size_t i = v.index(x, y, z);
        v.active[i] = std::abs(d) < band;
        v.samples[i] = v.active[i] ? double(float(d * 0.1)) : (d > 0 ? background : -background);
      }
  v.samples[0] = 0.125;  // inactive voxels holding neither +-background
  v.samples[v.count() - 1] = -7.5;
  return v;
}

// Largest |a - b| over the voxels active in `a`, computed here independently of the codec.
inline double worst_error(const Volume& a, const Volume& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.count(); ++i)
    if (a.active.empty() || a.active[i]) worst = std::max(worst, std::abs(a.samples[i] - b.samples[i]));
  return worst;
}

inline double range_of(const Volume& v) {
  double lo = 1e300, hi = -1e300;
  for (std::size_t i = 0; i < v.count(); ++i)
    if (v.active.empty() || v.active[i]) {
      lo = std::min(lo, v.samples[i]);
      hi = std::max(hi, v.samples[i]);
    }
  return hi - lo;
}

}  // namespace pupwave::test
