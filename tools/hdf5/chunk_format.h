#pragma once
// The 4-byte header of a stored chunk and the type mapping shared by chunk encoder and decoder.
// Layout (docs/hdf5.md): 'P' 'W' kind type, then the payload.

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/volume/volume.h"
#include "tools/hdf5/chunk_codec.h"

namespace pupwave::h5 {

enum class ChunkKind : std::uint8_t { raw = 0, volume = 1 };

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

}  // namespace pupwave::h5
