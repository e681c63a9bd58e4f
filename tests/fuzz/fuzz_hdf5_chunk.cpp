// fuzz_hdf5_chunk: the HDF5 filter's (and numcodecs codec's) decode path, h5::decode_chunk
// (tools/hdf5/chunk_decode.cpp; the filter callback adds only HDF5's buffer handling): a 4-byte
// chunk header ('P' 'W' kind type) then a raw payload or a volume stream. Volume payloads
// whose header is over the fuzzers' decode limit are skipped (decode_chunk applies the default
// limit). Invariants: a decoded chunk holds whole elements of its header's type, and a volume
// chunk as many as its grid's box has voxels; decoding twice gives the same bytes.
#include <stdexcept>

#include "codec/error.h"
#include "codec/volume/volume_format.h"
#include "fuzz_check.h"
#include "tools/hdf5/chunk_codec.h"

using namespace pupwave;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto stored = fuzz::as_span(data, size);
  std::size_t voxels = 0;                              // of a volume chunk's grid
  if (size > h5::kChunkHeaderBytes && data[2] == 1) {  // a volume chunk: its stream within the limit
    try {
      const auto h = parse_volume_stream(stored.subspan(h5::kChunkHeaderBytes), fuzz::kFuzzLimits).header;
      voxels = h.grids[0].volume.count();
    } catch (const DecodeError&) {
      return 0;
    }
  }
  h5::DecodedChunk chunk;
  try {
    chunk = h5::decode_chunk(stored);
  } catch (const DecodeError&) {
    return 0;
  }
  FUZZ_CHECK(h5::is_valid_type(std::uint32_t(chunk.type)));
  FUZZ_CHECK(chunk.bytes.size() % h5::element_size(chunk.type) == 0);
  FUZZ_CHECK(data[2] != 1 || chunk.bytes.size() == voxels * h5::element_size(chunk.type));
  FUZZ_CHECK(h5::decode_chunk(stored).bytes == chunk.bytes);
  return 0;
}
