// C entry points over the chunk codec, exported by the plugin library so that the numcodecs
// codec (tools/python/pupwave/numcodecs.py) stores exactly the chunks the HDF5 filter stores.
// Return 0 on success; otherwise -1 and a message in err (truncated to err_size). Buffers they
// return are malloc'd and released with pupwave_chunk_free.

#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "tools/hdf5/chunk_codec.h"

namespace {

int fail(const char* what, char* err, std::size_t err_size) {
  if (err != nullptr && err_size > 0) {
    std::strncpy(err, what, err_size - 1);
    err[err_size - 1] = '\0';
  }
  return -1;
}

void* copy_out(const std::vector<std::uint8_t>& bytes, std::size_t* out_size) {
  void* out = std::malloc(bytes.empty() ? 1 : bytes.size());
  if (out == nullptr) throw std::bad_alloc();
  std::memcpy(out, bytes.data(), bytes.size());
  *out_size = bytes.size();
  return out;
}

}  // namespace

extern "C" {

// Compresses `ndims` C-order dimensions `dims` of elements of `type` (1 u8, 2 i8, 3 u16, 4 i16,
// 5 f32, 6 f64) with `mode` (1 max_error, 2 bpv, 3 lossless) and `bound`, on `threads` threads
// (0: all cores, 1: the calling thread; a Dask worker passes 1, so workers do not oversubscribe).
int pupwave_chunk_encode(unsigned mode, double bound, unsigned type, unsigned ndims,
                         const unsigned long long* dims, const void* data, std::size_t nbytes,
                         unsigned threads, void** out, std::size_t* out_size, char* err,
                         std::size_t err_size) {
  using namespace pupwave::h5;
  try {
    if (!is_valid_type(type)) return fail("unknown element type code", err, err_size);
    ChunkParams p;
    p.mode = Mode(mode);
    p.bound = bound;
    p.type = ChunkType(type);
    p.dims = extent_from_shape(std::span<const unsigned long long>(dims, ndims));
    p.threads = threads;
    *out = copy_out(
        encode_chunk(p, std::span<const std::uint8_t>(static_cast<const std::uint8_t*>(data), nbytes)),
        out_size);
    return 0;
  } catch (const std::exception& e) {
    return fail(e.what(), err, err_size);
  }
}

// Decompresses a stored chunk on `threads` threads (as above); *type receives its element type code.
int pupwave_chunk_decode(const void* data, std::size_t nbytes, unsigned threads, void** out,
                         std::size_t* out_size, unsigned* type, char* err, std::size_t err_size) {
  try {
    const pupwave::h5::DecodedChunk d = pupwave::h5::decode_chunk(
        std::span<const std::uint8_t>(static_cast<const std::uint8_t*>(data), nbytes), threads);
    *out = copy_out(d.bytes, out_size);
    *type = unsigned(d.type);
    return 0;
  } catch (const std::exception& e) {
    return fail(e.what(), err, err_size);
  }
}

void pupwave_chunk_free(void* p) { std::free(p); }
}
