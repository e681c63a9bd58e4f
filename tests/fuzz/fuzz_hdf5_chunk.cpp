// fuzz_hdf5_chunk: the HDF5 filter's (and numcodecs codec's) decode path, h5::decode_chunk
// (tools/hdf5/chunk_decode.cpp; the filter callback adds only HDF5's buffer handling): a 4-byte
// chunk header ('P' 'W' kind type) then a raw payload, a volume stream, or a trimmed chunk (its
// extents and constant, then the box's volume stream). Volume streams whose header is over the
// fuzzers' decode limit, and trimmed chunks whose extent is, are skipped (decode_chunk applies
// the default limit). Invariants: a decoded chunk holds whole elements of its header's type, a
// volume chunk as many as its grid's box has voxels, a trimmed chunk as many as its extent, with
// the constant at the last element; decoding twice gives the same bytes.
#include <algorithm>
#include <stdexcept>

#include "codec/error.h"
#include "codec/volume/volume_format.h"
#include "fuzz_check.h"
#include "tools/hdf5/chunk_codec.h"
#include "tools/hdf5/chunk_format.h"

using namespace pupwave;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto stored = fuzz::as_span(data, size);
  std::size_t voxels = 0;  // of a volume chunk's grid or a trimmed chunk's extent
  const auto payload = stored.subspan(std::min(size, h5::kChunkHeaderBytes));
  const bool trimmed = size > h5::kChunkHeaderBytes && data[2] == 2 && h5::is_valid_type(data[3]);
  h5::TrimmedHead head;
  try {
    if (trimmed) {  // extent and box's stream within the limit
      head = h5::parse_trimmed_head(payload, h5::element_size(h5::ChunkType(data[3])), fuzz::kFuzzLimits);
      voxels = head.count();
      if (!head.box_empty()) parse_volume_stream(head.stream, fuzz::kFuzzLimits);
    } else if (size > h5::kChunkHeaderBytes && data[2] == 1) {  // a volume chunk: its stream within the limit
      voxels = parse_volume_stream(payload, fuzz::kFuzzLimits).header.grids[0].volume.count();
    }
  } catch (const DecodeError&) {
    return 0;
  }
  h5::DecodedChunk chunk;
  try {
    chunk = h5::decode_chunk(stored);
  } catch (const DecodeError&) {
    return 0;
  }
  FUZZ_CHECK(h5::is_valid_type(std::uint32_t(chunk.type)));
  FUZZ_CHECK(chunk.bytes.size() % h5::element_size(chunk.type) == 0);
  const std::size_t es = h5::element_size(chunk.type);
  FUZZ_CHECK((data[2] != 1 && !trimmed) || chunk.bytes.size() == voxels * es);
  FUZZ_CHECK(!trimmed || std::equal(head.c.begin(), head.c.end(), chunk.bytes.end() - std::ptrdiff_t(es)));
  FUZZ_CHECK(h5::decode_chunk(stored).bytes == chunk.bytes);
  return 0;
}
