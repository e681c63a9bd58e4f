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

// The box's grid, checked against the head and the chunk's type, as elements of `type`.
std::vector<std::uint8_t> decode_grid(std::span<const std::uint8_t> stream, ChunkType type, const Extent* box,
                                      unsigned threads) {
  const std::vector<VolumeGrid> grids = decode_volumes(stream, 0, *make_pool_executor(threads));
  require_stream(grids.size() == 1, "chunk stream must hold one grid");
  require_stream(grids[0].volume.type == stored_voxel_type(type), "chunk stream type differs from header");
  require_stream(box == nullptr || (grids[0].volume.dims == *box && !grids[0].volume.is_sparse()),
                 "trimmed chunk's stream is not a dense grid of its box");
  return from_volume(grids[0].volume, type);
}

// Kind 2: every element c, then the decoded box written over the corner [0, box).
std::vector<std::uint8_t> decode_trimmed(std::span<const std::uint8_t> payload, ChunkType type,
                                         unsigned threads) {
  const std::size_t es = element_size(type);
  const TrimmedHead h = parse_trimmed_head(payload, es);
  std::vector<std::uint8_t> out(h.count() * es);
  for (std::size_t i = 0; i < out.size(); i += es) std::memcpy(out.data() + i, h.c.data(), es);
  if (h.box_empty()) return out;
  const std::vector<std::uint8_t> box = decode_grid(h.stream, type, &h.box, threads);
  const std::size_t row = h.box[0] * es;
  for (std::size_t z = 0; z < h.box[2]; ++z)
    for (std::size_t y = 0; y < h.box[1]; ++y)
      std::memcpy(out.data() + (z * h.chunk[1] + y) * h.chunk[0] * es, box.data() + (z * h.box[1] + y) * row,
                  row);
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
  if (stored[2] == std::uint8_t(ChunkKind::trimmed)) {
    out.bytes = decode_trimmed(payload, out.type, threads);
    return out;
  }
  require_stream(stored[2] == std::uint8_t(ChunkKind::volume), "unknown chunk kind");
  out.bytes = decode_grid(payload, out.type, nullptr, threads);
  return out;
}

}  // namespace pupwave::h5
