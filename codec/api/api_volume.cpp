// The public volume API (pupwave/pupwave.hpp) over codec/volume/volume_codec.h: dense arrays
// and sparse grids given as bricks become the codec's VolumeGrid; the rate flags map as in
// the CLI (tools/cmd_compress.cpp), so equal settings give equal bytes.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>

#include "codec/api/api_errors.h"
#include "codec/volume/volume_codec.h"
#include "pupwave/pupwave.hpp"

namespace pupwave::api {
namespace {

pupwave::VoxelType internal_type(VoxelType type) {
  switch (type) {
    case VoxelType::u8: return pupwave::VoxelType::u8;
    case VoxelType::u16: return pupwave::VoxelType::u16;
    case VoxelType::f32: return pupwave::VoxelType::f32;
    case VoxelType::f64: return pupwave::VoxelType::f64;
  }
  detail::fail("unknown voxel type " + std::to_string(int(type)));
}

template <class T>
void load(const void* data, std::size_t n, double* out) {
  const T* src = static_cast<const T*>(data);
  for (std::size_t i = 0; i < n; ++i) out[i] = double(src[i]);
}

// Copies n voxels of `type` to doubles (the codec's Volume holds every type exactly as double).
void load_voxels(const void* data, std::size_t n, VoxelType type, double* out) {
  switch (type) {
    case VoxelType::u8: return load<std::uint8_t>(data, n, out);
    case VoxelType::u16: return load<std::uint16_t>(data, n, out);
    case VoxelType::f32: return load<float>(data, n, out);
    case VoxelType::f64: return load<double>(data, n, out);
  }
}

template <class T>
void store(const std::vector<double>& in, std::byte* out) {
  T* dst = reinterpret_cast<T*>(out);
  for (std::size_t i = 0; i < in.size(); ++i) dst[i] = T(in[i]);
}

std::size_t checked_count(const std::array<std::size_t, 3>& dims) {
  std::size_t n = 1;
  for (std::size_t d : dims) {
    if (d == 0)
      detail::fail("volume extent is empty (" + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) +
                   " x " + std::to_string(dims[2]) + ")");
    if (n > std::numeric_limits<std::uint32_t>::max() / d) detail::fail("volume is too large");
    n *= d;
  }
  return n;
}

// Largest active value range over the grid (for max_error_rel), as the CLI computes it.
double value_range(const pupwave::Volume& v) {
  double lo = 0.0, hi = 0.0;
  bool any = false;
  for (std::size_t i = 0; i < v.count(); ++i)
    if (v.is_active(i)) {
      lo = any ? std::min(lo, v.samples[i]) : v.samples[i];
      hi = any ? std::max(hi, v.samples[i]) : v.samples[i];
      any = true;
    }
  return hi - lo;
}

VolumeEncodeOptions encode_options(const VolumeOptions& options, const VolumeGrid& grid) {
  VolumeEncodeOptions enc;
  enc.levels = options.levels;
  enc.brick = options.brick;
  enc.target = options.target;
  if (options.rate != VolumeRate::lossless && !(options.target > 0.0 && std::isfinite(options.target)))
    detail::fail("rate target must be a positive finite number, got " + std::to_string(options.target));
  if (options.levels < -1 || options.levels > 32)
    detail::fail("levels must be -1 (default) or 0..32, got " + std::to_string(options.levels));
  switch (options.rate) {
    case VolumeRate::max_error: enc.mode = VolumeRateMode::max_error; break;
    case VolumeRate::max_error_rel: {
      enc.mode = VolumeRateMode::max_error;
      const double range = value_range(grid.volume);
      enc.target = options.target * (range > 0.0 ? range : 1.0);
      break;
    }
    case VolumeRate::bpv: enc.mode = VolumeRateMode::bpv; break;
    case VolumeRate::psnr: enc.mode = VolumeRateMode::psnr; break;
    case VolumeRate::step: enc.mode = VolumeRateMode::step; break;
    case VolumeRate::lossless: enc.mode = VolumeRateMode::lossless; break;
    default: detail::fail("unknown volume rate mode " + std::to_string(int(options.rate)));
  }
  enc.transform = !options.transform.empty()             ? options.transform
                  : options.rate == VolumeRate::lossless ? "cdf53"
                                                         : "cdf97";
  return enc;
}

std::vector<std::uint8_t> encode_grid(const VolumeGrid& grid, const VolumeOptions& options) {
  VolumeEncodeOptions enc = encode_options(options, grid);
  const std::unique_ptr<Executor> executor = make_pool_executor(options.threads);
  enc.executor = executor.get();
  return encode_volumes({grid}, enc).bytes;
}

void check_data(const void* data) {
  if (!data) detail::fail("volume data is null");
}

}  // namespace

std::size_t bytes_per_voxel(VoxelType type) { return pupwave::bytes_per_voxel(internal_type(type)); }

std::vector<std::uint8_t> compress_volume(const VolumeView& volume, const VolumeOptions& options) {
  return detail::translate_errors([&] {
    const std::size_t n = checked_count(volume.dims);
    check_data(volume.data);
    VolumeGrid grid;
    grid.name = "volume";
    grid.volume =
        pupwave::Volume(Extent{volume.dims[0], volume.dims[1], volume.dims[2]}, internal_type(volume.type));
    load_voxels(volume.data, n, volume.type, grid.volume.samples.data());
    return encode_grid(grid, options);
  });
}

std::vector<std::uint8_t> compress_sparse_volume(std::span<const BrickView> bricks, double background,
                                                 const VolumeOptions& options) {
  return detail::translate_errors([&] {
    if (bricks.empty()) detail::fail("a sparse volume needs at least one brick");
    if (!std::isfinite(background)) detail::fail("background must be finite");
    std::array<std::int64_t, 3> lo = bricks[0].origin, hi = bricks[0].origin;
    for (const BrickView& b : bricks) {
      checked_count(b.voxels.dims);
      check_data(b.voxels.data);
      if (b.voxels.type != bricks[0].voxels.type) detail::fail("all bricks must have the same voxel type");
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], b.origin[a]);
        hi[a] = std::max(hi[a], b.origin[a] + std::int64_t(b.voxels.dims[a]));
      }
    }
    const std::array<std::size_t, 3> box{std::size_t(hi[0] - lo[0]), std::size_t(hi[1] - lo[1]),
                                         std::size_t(hi[2] - lo[2])};
    checked_count(box);
    VolumeGrid grid;
    grid.name = "volume";
    grid.origin = lo;
    pupwave::Volume& v = grid.volume;
    v = pupwave::Volume(Extent{box[0], box[1], box[2]}, internal_type(bricks[0].voxels.type));
    std::fill(v.samples.begin(), v.samples.end(), background);
    v.active.assign(v.count(), 0);
    v.background = background;
    std::vector<double> row;
    for (const BrickView& b : bricks) {
      const auto& d = b.voxels.dims;
      const std::size_t bytes = bytes_per_voxel(b.voxels.type);
      row.resize(d[0]);
      for (std::size_t z = 0; z < d[2]; ++z)
        for (std::size_t y = 0; y < d[1]; ++y) {
          const std::size_t src = d[0] * (y + d[1] * z);
          load_voxels(static_cast<const std::byte*>(b.voxels.data) + src * bytes, d[0], b.voxels.type,
                      row.data());
          const std::size_t dst =
              v.index(std::size_t(b.origin[0] - lo[0]), std::size_t(b.origin[1] - lo[1]) + y,
                      std::size_t(b.origin[2] - lo[2]) + z);
          for (std::size_t x = 0; x < d[0]; ++x) {
            if (v.active[dst + x]) detail::fail("bricks overlap");
            const bool on = !b.active || b.active[src + x] != 0;
            v.active[dst + x] = on ? 1 : 0;
            v.samples[dst + x] = on ? row[x] : background;
          }
        }
    }
    return encode_grid(grid, options);
  });
}

std::vector<Volume> decompress_volume(std::span<const std::uint8_t> stream, int level, unsigned threads) {
  return detail::translate_errors([&] {
    if (level < 0) detail::fail("level must be >= 0, got " + std::to_string(level));
    if (!is_volume_stream(stream)) throw DecodeError("not a Pupwave volume stream (no PUPV signature)");
    const std::unique_ptr<Executor> executor = make_pool_executor(threads);
    std::vector<VolumeGrid> grids = decode_volumes(stream, level, *executor);
    std::vector<Volume> out;
    for (VolumeGrid& g : grids) {
      Volume v;
      v.name = g.name;
      v.origin = g.origin;
      v.dims = {g.volume.dims[0], g.volume.dims[1], g.volume.dims[2]};
      v.type = VoxelType(g.volume.type);  // same numbering (volume.h)
      v.background = g.volume.background;
      v.active = std::move(g.volume.active);
      v.data.resize(g.volume.count() * bytes_per_voxel(v.type));
      switch (v.type) {
        case VoxelType::u8: store<std::uint8_t>(g.volume.samples, v.data.data()); break;
        case VoxelType::u16: store<std::uint16_t>(g.volume.samples, v.data.data()); break;
        case VoxelType::f32: store<float>(g.volume.samples, v.data.data()); break;
        case VoxelType::f64: store<double>(g.volume.samples, v.data.data()); break;
      }
      out.push_back(std::move(v));
    }
    return out;
  });
}

}  // namespace pupwave::api
