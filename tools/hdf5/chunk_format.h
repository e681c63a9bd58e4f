#pragma once
// The 4-byte header of a stored chunk and the type mapping shared by chunk encoder and decoder.
// Layout (docs/hdf5.md): 'P' 'W' kind type, then the payload.
// A trimmed chunk's payload starts with the head parsed by parse_trimmed_head.

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/error.h"
#include "codec/format/decode_limits.h"
#include "codec/volume/volume.h"
#include "tools/hdf5/chunk_codec.h"

namespace pupwave::h5 {

enum class ChunkKind : std::uint8_t { raw = 0, volume = 1, trimmed = 2 };

// Signed integers are coded as the unsigned type of the same width, shifted by half its range.
constexpr double kSignedOffset8 = 128.0;
constexpr double kSignedOffset16 = 32768.0;

inline VoxelType stored_voxel_type(ChunkType type) {
  switch (type) {
    case ChunkType::u8:
    case ChunkType::i8: return VoxelType::u8;
    case ChunkType::u16:
    case ChunkType::i16: return VoxelType::u16;
    case ChunkType::f32: return VoxelType::f32;
    case ChunkType::f64: return VoxelType::f64;
  }
  return VoxelType::f64;
}

// Header followed by payload, in one allocation.
inline std::vector<std::uint8_t> stored_chunk(ChunkKind kind, ChunkType type,
                                              std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> out(kChunkHeaderBytes + payload.size());
  out[0] = 'P';
  out[1] = 'W';
  out[2] = std::uint8_t(kind);
  out[3] = std::uint8_t(type);
  std::copy(payload.begin(), payload.end(), out.begin() + kChunkHeaderBytes);
  return out;
}

// Kind 2 ("trimmed volume"): the chunk extent and the coded box extent (3 little-endian u32
// each, x fastest), then the constant c of the trimmed planes (one element, native bytes as in a
// raw chunk), then the box's volume stream (absent when the box is empty: an all-c chunk).
constexpr std::size_t kTrimmedExtentBytes = 24;

struct TrimmedHead {
  Extent chunk{0, 0, 0};
  Extent box{0, 0, 0};  // {0, 0, 0}: every element is c
  std::span<const std::uint8_t> c;
  std::span<const std::uint8_t> stream;
  std::size_t count() const { return chunk[0] * chunk[1] * chunk[2]; }
  bool box_empty() const { return box[0] == 0; }
};

inline void put_u32(std::vector<std::uint8_t>& out, std::size_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
}

inline std::size_t get_u32(std::span<const std::uint8_t> in) {
  return std::size_t(in[0]) | std::size_t(in[1]) << 8 | std::size_t(in[2]) << 16 | std::size_t(in[3]) << 24;
}

// The head of a trimmed chunk's payload, checked: a chunk extent of at most `limits` elements, a
// box inside it and smaller (else it would be a volume chunk), either empty on every axis with no
// stream or non-empty on every axis with one. Throws DecodeError otherwise.
inline TrimmedHead parse_trimmed_head(std::span<const std::uint8_t> payload, std::size_t element_bytes,
                                      const DecodeLimits& limits = {}) {
  require_stream(payload.size() >= kTrimmedExtentBytes + element_bytes,
                 "trimmed chunk truncated in its head");
  TrimmedHead h;
  std::uint64_t count = 1;
  for (std::size_t a = 0; a < 3; ++a) {
    h.chunk[a] = get_u32(payload.subspan(4 * a));
    h.box[a] = get_u32(payload.subspan(12 + 4 * a));
    require_stream(h.chunk[a] >= 1, "trimmed chunk has an empty extent");
    require_stream(h.box[a] <= h.chunk[a], "trimmed chunk's box is larger than the chunk");
    count *= h.chunk[a];  // three u32 factors: no overflow before the limit check
    require_stream(count <= limits.max_pixels, "trimmed chunk's extent is over the decode limit");
  }
  const bool empty = h.box[0] == 0 && h.box[1] == 0 && h.box[2] == 0;
  const bool full = h.box[0] >= 1 && h.box[1] >= 1 && h.box[2] >= 1;
  require_stream(empty || full, "trimmed chunk's box is empty on some axes only");
  require_stream(h.box != h.chunk, "trimmed chunk's box is the whole chunk");
  h.c = payload.subspan(kTrimmedExtentBytes, element_bytes);
  h.stream = payload.subspan(kTrimmedExtentBytes + element_bytes);
  require_stream(empty == h.stream.empty(), empty ? "all-constant trimmed chunk carries a stream"
                                                  : "trimmed chunk has no volume stream for its box");
  return h;
}

}  // namespace pupwave::h5
