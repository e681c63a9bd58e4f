#include "tools/hdf5/chunk_codec.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "codec/api/api_volume_options.h"
#include "codec/error.h"
#include "codec/volume/volume_codec.h"
#include "tools/hdf5/chunk_format.h"

namespace pupwave::h5 {
namespace {

// Largest chunk the filter codes (HDF5 itself caps chunks at 4 GiB).
constexpr std::uint64_t kMaxChunkElements = std::uint64_t(1) << 32;

template <typename T>
void widen(std::span<const std::uint8_t> raw, std::vector<double>& out, double offset) {
  for (std::size_t i = 0; i < out.size(); ++i) {
    T v;
    std::memcpy(&v, raw.data() + i * sizeof(T), sizeof(T));
    out[i] = double(v) + offset;
  }
}

// The chunk as a volume grid; signed integers are offset into the unsigned type the codec holds.
// `raw` holds contiguous elements of `dims` (the chunk's or a trimmed box's).
VolumeGrid to_grid(const ChunkParams& p, const Extent& dims, std::span<const std::uint8_t> raw) {
  VolumeGrid grid;
  grid.name = "chunk";
  grid.volume = Volume(dims, stored_voxel_type(p.type));
  std::vector<double>& s = grid.volume.samples;
  switch (p.type) {
    case ChunkType::u8: widen<std::uint8_t>(raw, s, 0.0); break;
    case ChunkType::i8: widen<std::int8_t>(raw, s, kSignedOffset8); break;
    case ChunkType::u16: widen<std::uint16_t>(raw, s, 0.0); break;
    case ChunkType::i16: widen<std::int16_t>(raw, s, kSignedOffset16); break;
    case ChunkType::f32: widen<float>(raw, s, 0.0); break;
    case ChunkType::f64: widen<double>(raw, s, 0.0); break;
  }
  return grid;
}

// Unsigned and float chunks are coded in place through a typed view (no copy widened to double:
// half the memory traffic per chunk, which two workers on one socket share) when their buffer is
// aligned for the type; signed ones need the offset copy above.
bool codes_in_place(const ChunkParams& p, std::span<const std::uint8_t> raw) {
  const bool is_signed = p.type == ChunkType::i8 || p.type == ChunkType::i16;
  return !is_signed && reinterpret_cast<std::uintptr_t>(raw.data()) % element_size(p.type) == 0;
}

// The rows of the box [0, box) of the chunk, contiguous (for the copying path of encode_box).
std::vector<std::uint8_t> gather_box(const ChunkParams& p, std::span<const std::uint8_t> raw,
                                     const Extent& box) {
  const std::size_t es = element_size(p.type);
  std::vector<std::uint8_t> out(box[0] * box[1] * box[2] * es);
  std::uint8_t* to = out.data();
  for (std::size_t z = 0; z < box[2]; ++z)
    for (std::size_t y = 0; y < box[1]; ++y, to += box[0] * es)
      std::memcpy(to, raw.data() + (z * p.dims[1] + y) * p.dims[0] * es, box[0] * es);
  return out;
}

// Encodes a grid with the options every front door resolves (api_volume_options.h).
VolumeEncodeResult encode_resolved(const std::vector<VolumeGrid>& grids, std::span<const VolumeView> views,
                                   const api::VolumeOptions& options, const Executor* executor) {
  VolumeEncodeOptions enc = api::resolve_volume_options(options, grids, views).encode;
  enc.executor = executor;
  return encode_volumes(grids, views, enc);
}

// Codes the box [0, box) of the chunk (the whole chunk when box == p.dims).
VolumeEncodeResult encode_box(const ChunkParams& p, std::span<const std::uint8_t> raw, const Extent& box,
                              const api::VolumeOptions& options, const Executor* executor) {
  if (!codes_in_place(p, raw)) {
    if (box == p.dims) return encode_resolved({to_grid(p, box, raw)}, {}, options, executor);
    return encode_resolved({to_grid(p, box, gather_box(p, raw, box))}, {}, options, executor);
  }
  const VolumeView view =
      sub_view(contiguous_view(raw.data(), p.dims, stored_voxel_type(p.type)), {0, 0, 0}, box);
  const VolumeView views[] = {view};
  return encode_resolved({describe_view(view, "chunk")}, views, options, executor);
}

// The filter's mode as the library's volume options (whose resolution gives the transform and
// the rest, as for the CLI and the APIs).
api::VolumeOptions volume_options(const ChunkParams& p) {
  api::VolumeOptions o;
  switch (p.mode) {
    case Mode::max_error: o.rate = api::VolumeRate::max_error; break;
    case Mode::bpv: o.rate = api::VolumeRate::bpv; break;
    case Mode::lossless: o.rate = api::VolumeRate::lossless; break;
  }
  o.target = p.bound;
  return o;
}

std::vector<std::uint8_t> stored_raw(ChunkType type, std::span<const std::uint8_t> raw) {
  return stored_chunk(ChunkKind::raw, type, raw);
}

// Bitwise element equality as unsigned integers of the element's width (NaN fill values included).
template <typename U>
Extent box_of(const ChunkParams& p, std::span<const std::uint8_t> raw) {
  const auto at = [&](std::size_t i) {
    U v;
    std::memcpy(&v, raw.data() + i * sizeof(U), sizeof(U));
    return v;
  };
  const std::size_t nx = p.dims[0];
  const U c = at(p.count() - 1);
  Extent box{0, 0, 0};
  for (std::size_t z = 0; z < p.dims[2]; ++z)
    for (std::size_t y = 0; y < p.dims[1]; ++y) {
      const std::size_t row = (z * p.dims[1] + y) * nx;
      std::size_t end = nx;  // one past the row's last element differing from c (0: none)
      while (end > 0 && at(row + end - 1) == c) --end;
      if (end == 0) continue;
      box = {std::max(box[0], end), std::max(box[1], y + 1), z + 1};
    }
  return box;
}

// The smallest box [0, box) holding every element not bitwise equal to the chunk's last one, c:
// outside it lie the trailing planes of each axis that are all c (HDF5's and Zarr's padding of
// edge chunks with the fill value). {0, 0, 0} when the whole chunk is c.
Extent untrimmed_box(const ChunkParams& p, std::span<const std::uint8_t> raw) {
  switch (element_size(p.type)) {
    case 1: return box_of<std::uint8_t>(p, raw);
    case 2: return box_of<std::uint16_t>(p, raw);
    case 4: return box_of<std::uint32_t>(p, raw);
    default: return box_of<std::uint64_t>(p, raw);
  }
}

// Kind 2: the head (extents and c), then the box's stream unless the box is empty. In bpv mode the
// box gets the whole chunk's budget (bpv counts bits per value of the chunk, docs/hdf5.md).
std::vector<std::uint8_t> encode_trimmed(const ChunkParams& p, std::span<const std::uint8_t> raw,
                                         const Extent& box, api::VolumeOptions options,
                                         const Executor* executor) {
  std::vector<std::uint8_t> payload;
  for (const std::size_t d : p.dims) put_u32(payload, d);
  for (const std::size_t d : box) put_u32(payload, d);
  const std::size_t es = element_size(p.type);
  payload.insert(payload.end(), raw.end() - std::ptrdiff_t(es), raw.end());
  const std::size_t box_count = box[0] * box[1] * box[2];
  if (box_count > 0) {
    if (p.mode == Mode::bpv) options.target = p.bound * double(p.count()) / double(box_count);
    VolumeEncodeResult coded;
    try {
      coded = encode_box(p, raw, box, options, executor);
    } catch (const EncodeError&) {
      return stored_raw(p.type, raw);  // as encode_chunk: data the codec cannot hold stays raw
    }
    payload.insert(payload.end(), coded.bytes.begin(), coded.bytes.end());
  }
  if (payload.size() >= raw.size()) return stored_raw(p.type, raw);  // tiny chunks
  return stored_chunk(ChunkKind::trimmed, p.type, payload);
}

}  // namespace

std::size_t element_size(ChunkType type) {
  switch (type) {
    case ChunkType::u8:
    case ChunkType::i8: return 1;
    case ChunkType::u16:
    case ChunkType::i16: return 2;
    case ChunkType::f32: return 4;
    case ChunkType::f64: return 8;
  }
  return 0;
}

bool is_valid_type(std::uint32_t code) { return code >= 1 && code <= 6; }

std::string check_params(std::uint32_t mode, double bound, ChunkType type) {
  const bool is_float = type == ChunkType::f32 || type == ChunkType::f64;
  switch (Mode(mode)) {
    case Mode::max_error:
      if (!(std::isfinite(bound) && bound > 0.0 && bound < 1e300))
        return "max_error must be a finite positive number, got " + std::to_string(bound);
      return {};
    case Mode::bpv:
      if (!(bound > 0.0 && bound <= double(8 * element_size(type))))
        return "bits per value must be in (0, " + std::to_string(8 * element_size(type)) + "], got " +
               std::to_string(bound);
      return {};
    case Mode::lossless:
      if (is_float) return "lossless mode needs 8- or 16-bit integers; for floats use max_error";
      return {};
  }
  return "unknown mode " + std::to_string(mode) + " (1 = max_error, 2 = bpv, 3 = lossless)";
}

Extent extent_from_shape(std::span<const unsigned long long> c_order_dims) {
  if (c_order_dims.empty()) throw std::invalid_argument("chunk has no dimensions");
  Extent e{1, 1, 1};
  std::size_t kept = 0;
  std::uint64_t count = 1;
  // C order: the last dimension varies fastest, so it becomes x (e[0]).
  for (std::size_t i = c_order_dims.size(); i-- > 0;) {
    const std::uint64_t d = c_order_dims[i];
    if (d == 0) throw std::invalid_argument("chunk dimension of size 0");
    if (d == 1) continue;
    if (kept == 3) throw std::invalid_argument("chunks with more than 3 dimensions larger than 1");
    if (d > kMaxChunkElements / count) throw std::invalid_argument("chunk larger than 2^32 elements");
    count *= d;
    e[kept++] = std::size_t(d);
  }
  return e;
}

std::vector<std::uint8_t> encode_chunk(const ChunkParams& params, std::span<const std::uint8_t> raw) {
  if (raw.size() != params.count() * element_size(params.type))
    throw std::invalid_argument("chunk holds " + std::to_string(raw.size()) + " bytes, expected " +
                                std::to_string(params.count() * element_size(params.type)));
  if (const std::string why = check_params(std::uint32_t(params.mode), params.bound, params.type);
      !why.empty())
    throw std::invalid_argument(why);
  VolumeEncodeResult coded;
  const auto executor = make_pool_executor(params.threads);
  const api::VolumeOptions options = volume_options(params);
  // Trimmed only when its decode stays within the default limit, as a volume chunk's must.
  if (const Extent box = untrimmed_box(params, raw);
      box != params.dims && params.count() <= kDefaultMaxDecodePixels)
    return encode_trimmed(params, raw, box, options, executor.get());
  try {
    coded = encode_box(params, raw, params.dims, options, executor.get());
  } catch (const EncodeError&) {
    // Data the codec cannot hold (a bound below the type's precision): keep it raw.
    return stored_raw(params.type, raw);
  }
  if (coded.bytes.size() >= raw.size()) return stored_raw(params.type, raw);
  return stored_chunk(ChunkKind::volume, params.type, coded.bytes);
}

}  // namespace pupwave::h5
