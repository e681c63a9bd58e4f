#pragma once
// Internal to the volume codec: explicit corrections of the voxels the transform coding leaves
// outside a point-wise error bound E (the SPERR approach). A correction is k * E added to the
// reconstruction: k = round(residual / E) (|residual - k E| <= E / 2 before the value is rounded
// to its stored type, and <= E after, since the original is itself a stored value), or for
// float types k one nearer 0 when that stored value is still within E (|k| - 1 is coded in unary).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/volume/volume.h"

namespace pupwave {

struct Outlier {
  std::uint32_t index = 0;  // voxel index inside its brick (x fastest)
  std::int64_t k = 0;       // correction in units of the bound (never 0)
};

// A reconstructed value as the output file stores it: rounded to float for f32, rounded and
// clamped for u8/u16, unchanged for f64. Inline: it runs once per voxel in encoder and decoder.
inline double to_stored(double value, VoxelType type) {
  switch (type) {
    case VoxelType::u8: return std::clamp(std::round(value), 0.0, 255.0);
    case VoxelType::u16: return std::clamp(std::round(value), 0.0, 65535.0);
    case VoxelType::f32: return double(float(value));
    case VoxelType::f64: return value;
  }
  return value;
}

// Outliers of a brick: voxels with `check[i]` whose stored reconstruction is farther than
// `bound` from `original[i]`. Applies the corrections to `reconstruction` (stored values).
std::vector<Outlier> find_outliers(std::span<const double> original, std::span<double> reconstruction,
                                   std::span<const std::uint8_t> check, double bound, VoxelType type);

// Largest and squared error of a brick's stored values over the voxels that count.
struct StoredError {
  double max = 0.0;
  double sse = 0.0;
};

// find_outliers of a reconstruction held as float (`requantized`, as the decoder holds it before
// widening), in one pass (no separate conversion pass): the outliers to `out`, the error of the
// stored values (corrections applied) over the voxels `check` marks to `error` unless it is null,
// and the stored values themselves to `stored` unless it is empty (the encoder's candidate steps
// need neither, its chosen one only the error). Same result as converting with to_stored, then
// find_outliers. S: the originals' type (std::uint8_t, std::uint16_t, float or double; see
// gather_box), compared as double.
template <class S>
void store_and_find_outliers(std::span<const S> original, std::span<const float> requantized,
                             std::span<double> stored, std::span<const std::uint8_t> check, double bound,
                             VoxelType type, std::vector<Outlier>& out, StoredError* error);
inline void store_and_find_outliers(std::span<const double> original, std::span<const float> requantized,
                                    std::span<double> stored, std::span<const std::uint8_t> check,
                                    double bound, VoxelType type, std::vector<Outlier>& out,
                                    StoredError* error) {
  store_and_find_outliers<double>(original, requantized, stored, check, bound, type, out, error);
}

// Applies decoded corrections to a brick's reconstruction (then rounds to the stored type).
void apply_outliers(std::span<double> reconstruction, std::span<const Outlier> outliers, double bound,
                    VoxelType type);

// Indices as gaps and corrections, range coded with adaptive models (empty for none; docs/bitstream.md).
std::vector<std::uint8_t> encode_outliers(std::span<const Outlier> outliers);

// Inverse of encode_outliers for a brick of `count` voxels; throws DecodeError unless every
// index is in range and strictly increasing and every correction is non-zero.
std::vector<Outlier> decode_outliers(std::span<const std::uint8_t> bytes, std::size_t count);

}  // namespace pupwave
