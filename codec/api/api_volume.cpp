// The public volume API (pupwave/pupwave.hpp) over codec/volume/volume_codec.h: dense arrays
// and sparse grids given as bricks become the codec's VolumeGrid; the options are resolved by
// resolve_volume_options (api_volume_options.h), as the CLI's, so equal settings give equal bytes.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>

#include "codec/api/api_attributes.h"
#include "codec/api/api_errors.h"
#include "codec/api/api_volume_options.h"
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
void store(const std::vector<double>& in, std::byte* out) {
  T* dst = reinterpret_cast<T*>(out);
  for (std::size_t i = 0; i < in.size(); ++i) dst[i] = T(in[i]);
}

// The typed buffer (and mask) of `typed` for grid `g`, as the decoders' output.
pupwave::VolumeOutput typed_output(Volume& typed, const VolumeGrid& g) {
  typed.type = VoxelType(g.volume.type);  // same numbering (volume.h)
  typed.data.resize(g.volume.count() * bytes_per_voxel(typed.type));
  pupwave::VolumeOutput o = contiguous_output(typed.data.data(), g.volume.dims, g.volume.type);
  if (g.volume.is_sparse()) typed.active.resize(g.volume.count()), o.active = typed.active.data();
  return o;
}

// Name, placement, dims, background and attributes of a grid decoded by typed_output.
void describe(Volume& typed, const VolumeGrid& grid) {
  typed.name = grid.name;
  typed.origin = grid.origin;
  typed.dims = {grid.volume.dims[0], grid.volume.dims[1], grid.volume.dims[2]};
  typed.background = grid.volume.background;
  typed.attributes = detail::text_attributes(grid.metadata);
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

// What a result reached, in the unit of the caller's target (TargetOutcome::achieved): a
// relative bound's error is scaled back by the range it was scaled by.
double achieved(const VolumeEncodeResult& r, const ResolvedVolumeOptions& resolved) {
  switch (resolved.encode.mode) {
    case VolumeRateMode::bpv: return r.bpv;
    case VolumeRateMode::psnr: return r.psnr;
    case VolumeRateMode::max_error: return r.max_error / resolved.error_unit;
    default: return std::numeric_limits<double>::quiet_NaN();
  }
}

// Encodes one box grid read in place through `view` (nothing is copied or widened to double).
std::vector<std::uint8_t> encode_grid(const pupwave::VolumeView& view,
                                      const std::array<std::int64_t, 3>& origin, const VolumeOptions& options,
                                      TargetOutcome& outcome) {
  detail::check_attributes(options.attributes);
  VolumeGrid grid = describe_view(view, "volume");
  grid.origin = origin;
  grid.metadata = detail::grid_metadata(options.attributes);
  const std::vector<VolumeGrid> grids{std::move(grid)};
  const pupwave::VolumeView views[] = {view};
  const ResolvedVolumeOptions resolved = resolve_volume_options(options, grids, views);
  VolumeEncodeOptions enc = resolved.encode;
  const std::unique_ptr<Executor> executor = make_pool_executor(options.threads);
  enc.executor = executor.get();
  VolumeEncodeResult r = encode_volumes(grids, views, enc);
  outcome.met = r.target_met;
  outcome.achieved = achieved(r, resolved);
  return std::move(r.bytes);
}

// The codec's view of a caller's dense array (strides 0: contiguous, x fastest).
pupwave::VolumeView internal_view(const VolumeView& volume) {
  const Extent dims{volume.dims[0], volume.dims[1], volume.dims[2]};
  pupwave::VolumeView v = contiguous_view(volume.data, dims, internal_type(volume.type));
  if (volume.strides != std::array<std::ptrdiff_t, 3>{0, 0, 0}) v.strides = volume.strides;
  return v;
}

// A box held as type T when the background is one of its values (else as double), filled with
// the background: what the bricks of a sparse grid are copied into.
struct SparseBox {
  std::vector<std::byte> bytes;
  pupwave::VolumeView view;
  std::vector<std::uint8_t> active;
};

bool holds_value(pupwave::VoxelType type, double v) {
  switch (type) {
    case pupwave::VoxelType::u8: return v >= 0 && v <= 255 && v == std::floor(v);
    case pupwave::VoxelType::u16: return v >= 0 && v <= 65535 && v == std::floor(v);
    case pupwave::VoxelType::f32: return double(float(v)) == v;
    case pupwave::VoxelType::f64: return true;
  }
  return false;
}

template <class T>
void fill_as(std::vector<std::byte>& bytes, double value) {
  T* p = reinterpret_cast<T*>(bytes.data());
  std::fill(p, p + bytes.size() / sizeof(T), T(value));
}

void fill(std::vector<std::byte>& bytes, pupwave::VoxelType storage, double value) {
  switch (storage) {
    case pupwave::VoxelType::u8: return fill_as<std::uint8_t>(bytes, value);
    case pupwave::VoxelType::u16: return fill_as<std::uint16_t>(bytes, value);
    case pupwave::VoxelType::f32: return fill_as<float>(bytes, value);
    case pupwave::VoxelType::f64: return fill_as<double>(bytes, value);
  }
}

// Copies row `n` voxels from a brick (its own type) into the box storage at element `at`.
template <class T>
void copy_row_as(const void* src, pupwave::VoxelType type, std::size_t n, std::byte* box, std::size_t at) {
  T* out = reinterpret_cast<T*>(box) + at;
  switch (type) {
    case pupwave::VoxelType::u8: std::copy_n(static_cast<const std::uint8_t*>(src), n, out); break;
    case pupwave::VoxelType::u16: std::copy_n(static_cast<const std::uint16_t*>(src), n, out); break;
    case pupwave::VoxelType::f32: std::copy_n(static_cast<const float*>(src), n, out); break;
    case pupwave::VoxelType::f64: std::copy_n(static_cast<const double*>(src), n, out); break;
  }
}

void check_data(const void* data) {
  if (!data) detail::fail("volume data is null");
}

}  // namespace

std::size_t bytes_per_voxel(VoxelType type) { return pupwave::bytes_per_voxel(internal_type(type)); }

std::vector<std::uint8_t> compress_volume(const VolumeView& volume, const VolumeOptions& options) {
  TargetOutcome ignored;
  return compress_volume(volume, options, ignored);
}

std::vector<std::uint8_t> compress_volume(const VolumeView& volume, const VolumeOptions& options,
                                          TargetOutcome& outcome) {
  return detail::translate_errors([&] {
    checked_count(volume.dims);
    check_data(volume.data);
    return encode_grid(internal_view(volume), {0, 0, 0}, options, outcome);
  });
}

std::vector<std::uint8_t> compress_sparse_volume(std::span<const BrickView> bricks, double background,
                                                 const VolumeOptions& options) {
  TargetOutcome ignored;
  return compress_sparse_volume(bricks, background, options, ignored);
}

std::vector<std::uint8_t> compress_sparse_volume(std::span<const BrickView> bricks, double background,
                                                 const VolumeOptions& options, TargetOutcome& outcome) {
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
    const pupwave::VoxelType type = internal_type(bricks[0].voxels.type);
    const pupwave::VoxelType storage = holds_value(type, background) ? type : pupwave::VoxelType::f64;
    const Extent dims{box[0], box[1], box[2]};
    SparseBox out;
    out.bytes.resize(box[0] * box[1] * box[2] * pupwave::bytes_per_voxel(storage));
    fill(out.bytes, storage, background);
    out.active.assign(box[0] * box[1] * box[2], 0);
    out.view = contiguous_view(out.bytes.data(), dims, storage);
    out.view.type = type;
    out.view.active = out.active.data();
    out.view.background = background;
    std::vector<std::uint8_t> covered(out.active.size(), 0);  // by some brick (masked voxels included)
    const pupwave::VolumeOutput flat =
        contiguous_output(out.bytes.data(), {out.active.size(), 1, 1}, storage);
    for (const BrickView& b : bricks) {
      const auto& d = b.voxels.dims;
      const std::size_t bytes = bytes_per_voxel(b.voxels.type);
      for (std::size_t z = 0; z < d[2]; ++z)
        for (std::size_t y = 0; y < d[1]; ++y) {
          const std::size_t src = d[0] * (y + d[1] * z);
          const std::size_t dst = std::size_t(out.view.offset(std::size_t(b.origin[0] - lo[0]),
                                                              std::size_t(b.origin[1] - lo[1]) + y,
                                                              std::size_t(b.origin[2] - lo[2]) + z));
          const std::byte* row = static_cast<const std::byte*>(b.voxels.data) + src * bytes;
          for (std::size_t x = 0; x < d[0]; ++x) {
            if (covered[dst + x]) detail::fail("bricks overlap");
            covered[dst + x] = 1;
          }
          switch (storage) {
            case pupwave::VoxelType::u8:
              copy_row_as<std::uint8_t>(row, type, d[0], out.bytes.data(), dst);
              break;
            case pupwave::VoxelType::u16:
              copy_row_as<std::uint16_t>(row, type, d[0], out.bytes.data(), dst);
              break;
            case pupwave::VoxelType::f32: copy_row_as<float>(row, type, d[0], out.bytes.data(), dst); break;
            case pupwave::VoxelType::f64: copy_row_as<double>(row, type, d[0], out.bytes.data(), dst); break;
          }
          for (std::size_t x = 0; x < d[0]; ++x) {
            const bool on = !b.active || b.active[src + x] != 0;
            out.active[dst + x] = on ? 1 : 0;
            if (!on) flat.set(dst + x, 0, 0, background);  // masked voxels hold the background
          }
        }
    }
    return encode_grid(out.view, lo, options, outcome);
  });
}

std::vector<Volume> decompress_volume(std::span<const std::uint8_t> stream, int level, unsigned threads) {
  return detail::translate_errors([&] {
    if (level < 0) detail::fail("level must be >= 0, got " + std::to_string(level));
    if (!is_volume_stream(stream)) throw DecodeError("not a Pupwave volume stream (no PUPV signature)");
    const std::unique_ptr<Executor> executor = make_pool_executor(threads);
    Volume typed;  // a single box grid, decoded straight into its own type
    const auto grid = decode_volume_into(stream, "", level, *executor, DecodeLimits{},
                                         [&](const VolumeGrid& g) { return typed_output(typed, g); });
    if (grid) {
      describe(typed, *grid);
      return std::vector<Volume>{std::move(typed)};
    }
    std::vector<VolumeGrid> grids = decode_volumes(stream, level, *executor);
    std::vector<Volume> out;
    for (VolumeGrid& g : grids) {
      // A sparse-native grid (a .vdb's) decodes to blocks and tiles, no box samples: the API's
      // arrays are its dense active bounding box (without this they came back all zeros).
      if (g.is_opaque())
        detail::fail("grid '" + g.name + "' is carried as OpenVDB bytes only (use the CLI's .vdb output)");
      try {
        make_dense_box(g, kDefaultMaxDecodePixels);
      } catch (const std::runtime_error& e) {  // a box over the decode limit
        throw Error(Status::unsupported, e.what());
      }
      Volume v;
      v.name = g.name;
      v.origin = g.origin;
      v.dims = {g.volume.dims[0], g.volume.dims[1], g.volume.dims[2]};
      v.type = VoxelType(g.volume.type);  // same numbering (volume.h)
      v.background = g.volume.background;
      v.attributes = detail::text_attributes(g.metadata);
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

Volume decompress_volume_box(std::span<const std::uint8_t> stream, const VoxelBox& box, int level,
                             unsigned threads, std::string_view grid) {
  return detail::translate_errors([&] {
    if (level < 0) detail::fail("level must be >= 0, got " + std::to_string(level));
    if (!is_volume_stream(stream)) throw DecodeError("not a Pupwave volume stream (no PUPV signature)");
    const std::unique_ptr<Executor> executor = make_pool_executor(threads);
    const pupwave::VoxelBox voxels{{box.lo[0], box.lo[1], box.lo[2]}, {box.hi[0], box.hi[1], box.hi[2]}};
    Volume typed;  // decoded straight into its own type
    const VolumeGrid described =
        decode_volume_box_into(stream, grid, voxels, level, *executor, DecodeLimits{},
                               [&](const VolumeGrid& g) { return typed_output(typed, g); });
    describe(typed, described);
    return typed;
  });
}

}  // namespace pupwave::api
