#include <cstring>

#include "codec/error.h"
#include "codec/volume/volume_codec.h"
#include "tools/hdf5/chunk_codec.h"
#include "tools/hdf5/chunk_format.h"

namespace pupwave::h5 {
namespace {

template <typename T>
void narrow(const std::vector<double>& samples, std::vector<std::uint8_t>& out, double offset) {
  out.resize(samples.size() * sizeof(T));
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const T v = T(samples[i] - offset);
    std::memcpy(out.data() + i * sizeof(T), &v, sizeof(T));
  }
}

std::vector<std::uint8_t> from_volume(const Volume& v, ChunkType type) {
  std::vector<std::uint8_t> out;
  switch (type) {
    case ChunkType::u8: narrow<std::uint8_t>(v.samples, out, 0.0); break;
    case ChunkType::i8: narrow<std::int8_t>(v.samples, out, kSignedOffset8); break;
    case ChunkType::u16: narrow<std::uint16_t>(v.samples, out, 0.0); break;
    case ChunkType::i16: narrow<std::int16_t>(v.samples, out, kSignedOffset16); break;
    case ChunkType::f32: narrow<float>(v.samples, out, 0.0); break;
    case ChunkType::f64: narrow<double>(v.samples, out, 0.0); break;
  }
  return out;
}

}  // namespace

DecodedChunk decode_chunk(std::span<const std::uint8_t> stored, unsigned threads) {
  require_stream(stored.size() >= kChunkHeaderBytes, "chunk shorter than its header");
  require_stream(stored[0] == 'P' && stored[1] == 'W', "not a pupwave chunk (bad signature)");
  require_stream(is_valid_type(stored[3]), "unknown chunk element type");
  DecodedChunk out;
  out.type = ChunkType(stored[3]);
  const std::span<const std::uint8_t> payload = stored.subspan(kChunkHeaderBytes);
  if (stored[2] == std::uint8_t(ChunkKind::raw)) {
    require_stream(payload.size() % element_size(out.type) == 0,
                   "raw chunk size is not a whole element count");
    out.bytes.assign(payload.begin(), payload.end());
    return out;
  }
  require_stream(stored[2] == std::uint8_t(ChunkKind::volume), "unknown chunk kind");
  const std::vector<VolumeGrid> grids = decode_volumes(payload, 0, *make_pool_executor(threads));
  require_stream(grids.size() == 1, "chunk stream must hold one grid");
  require_stream(grids[0].volume.type == stored_voxel_type(out.type),
                 "chunk stream type differs from header");
  out.bytes = from_volume(grids[0].volume, out.type);
  return out;
}

}  // namespace pupwave::h5
