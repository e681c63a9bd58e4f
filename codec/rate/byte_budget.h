#pragma once
// The one rule that turns a bits-per-pixel (or per-voxel) target into a byte budget: the largest
// whole number of bytes whose rate does not exceed the target. Every rate search and every
// "target met" check uses it, so a stream the encoder accepts is one the check accepts.
#include <cmath>
#include <cstddef>

namespace pupwave {

inline double byte_budget(double bits_per_sample, std::size_t samples) {
  return std::floor(bits_per_sample * double(samples) / 8.0);
}

}  // namespace pupwave
