#pragma once
// One chunk of an HDF5 dataset or a Zarr array, compressed on its own (docs/hdf5.md, "Chunk
// format"). Shared by the HDF5 filter (h5z_pupwave.cpp) and the C entry points the numcodecs
// codec calls through ctypes (chunk_c_api.cpp), so both storage layers hold identical chunks.
// Nothing here knows HDF5.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "transforms/subband.h"

namespace pupwave::h5 {

// What the user asks for (cd_values[0]).
enum class Mode : std::uint32_t { max_error = 1, bpv = 2, lossless = 3 };

// Element type of a chunk (cd_values[3], and byte 3 of every stored chunk).
enum class ChunkType : std::uint32_t { u8 = 1, i8 = 2, u16 = 3, i16 = 4, f32 = 5, f64 = 6 };

std::size_t element_size(ChunkType type);
bool is_valid_type(std::uint32_t code);

struct ChunkParams {
  Mode mode = Mode::max_error;
  double bound = 0.0;  // absolute error (max_error) or bits per value (bpv); unused when lossless
  ChunkType type = ChunkType::f32;
  Extent dims{1, 1, 1};  // x fastest: dims[0] is the last (fastest) C-order dimension
  // Threads coding this chunk's bricks (0: all cores, 1: the calling thread); never in the stream.
  unsigned threads = 0;
  std::size_t count() const { return dims[0] * dims[1] * dims[2]; }
};

// Empty when mode and bound make sense for the type, else the reason (for error messages).
std::string check_params(std::uint32_t mode, double bound, ChunkType type);

// Volume extent of a C-order chunk shape: dimensions of size 1 are dropped, at most 3 remain.
// Throws std::invalid_argument for an empty shape, a zero dimension or more than 3 non-unit ones.
Extent extent_from_shape(std::span<const unsigned long long> c_order_dims);

// Stored chunk: 4-byte header then a Pupwave volume stream, or the raw bytes when coding would
// not make the chunk smaller (or the data cannot be coded: a bound below the type's precision):
// never more than raw + 4. NaN and infinities are coded as missing values, kept exactly.
// `raw` holds params.count() elements of params.type, C order, native byte order.
std::vector<std::uint8_t> encode_chunk(const ChunkParams& params, std::span<const std::uint8_t> raw);

struct DecodedChunk {
  ChunkType type = ChunkType::f32;
  std::vector<std::uint8_t> bytes;  // elements of `type`, C order
};

// Inverse of encode_chunk. Throws pupwave::DecodeError for a corrupt or truncated chunk.
// threads as in ChunkParams.
DecodedChunk decode_chunk(std::span<const std::uint8_t> stored, unsigned threads = 0);

constexpr std::size_t kChunkHeaderBytes = 4;

}  // namespace pupwave::h5
