#include "codec/volume/volume_format.h"

#include <zstd.h>

#include <bit>
#include <cmath>
#include <stdexcept>

#include "codec/error.h"
#include "codec/format/byte_io.h"
#include "codec/format/chunks.h"

namespace pupwave {
namespace {

constexpr std::size_t kMaxText = 65535;
constexpr std::size_t kMaxMetadata = 4096;
constexpr int kMaskZstdLevel = 9;

void put_u64(ByteWriter& w, std::uint64_t v) {
  w.u32(std::uint32_t(v));
  w.u32(std::uint32_t(v >> 32));
}
void put_f64(ByteWriter& w, double v) { put_u64(w, std::bit_cast<std::uint64_t>(v)); }

void put_text(ByteWriter& w, const std::string& s) {
  if (s.size() > kMaxText) throw EncodeError("grid name or metadata text longer than 65535 bytes");
  w.str16(s);
}

void write_metadata(ByteWriter& w, const std::map<std::string, MetaValue>& metadata) {
  if (metadata.size() > kMaxMetadata) throw EncodeError("more than 4096 metadata entries in a grid");
  w.u32(std::uint32_t(metadata.size()));
  for (const auto& [key, m] : metadata) {
    put_text(w, key);
    w.u8(std::uint8_t(m.kind));
    put_text(w, m.text);
    put_u64(w, std::uint64_t(m.integer));
    for (double v : m.numbers) put_f64(w, v);
  }
}

void write_grid(ByteWriter& w, const VolumeGrid& g, std::uint8_t blocked, bool missing) {
  put_text(w, g.name);
  w.u8(std::uint8_t(g.grid_class));
  for (std::int64_t o : g.origin) put_u64(w, std::uint64_t(o));
  for (double v : g.index_to_world) put_f64(w, v);
  write_metadata(w, g.metadata);
  for (std::size_t d : g.volume.dims) w.u32(std::uint32_t(d));
  w.u8(std::uint8_t(g.volume.type));
  put_f64(w, g.volume.background);
  w.u8(missing ? 4 : blocked == 2 ? 3 : blocked == 1 ? 2 : g.volume.is_sparse() ? 1 : 0);
}

// Bytes as a zstd frame (u32 length, then the frame).
void put_zstd(ByteWriter& w, std::span<const std::uint8_t> bytes) {
  std::vector<std::uint8_t> packed(ZSTD_compressBound(bytes.size()));
  const std::size_t n =
      ZSTD_compress(packed.data(), packed.size(), bytes.data(), bytes.size(), kMaskZstdLevel);
  if (ZSTD_isError(n)) throw EncodeError(std::string("zstd: ") + ZSTD_getErrorName(n));
  packed.resize(n);
  w.u32(std::uint32_t(packed.size()));
  w.bytes(packed);
}

// Voxel states (zstd) and inactive values, shared by MASK and BLKS.
// The inactive values are a zstd frame of their little-endian f64 bits: a land mask's thousands
// of NaNs or fill values cost a few bytes, not eight each.
void write_states(ByteWriter& w, const MaskChunk& mask) {
  put_zstd(w, mask.states);
  w.u32(std::uint32_t(mask.other_values.size()));
  std::vector<std::uint8_t> values;
  ByteWriter v(values);
  for (double x : mask.other_values) put_f64(v, x);
  put_zstd(w, values);
}

}  // namespace

void write_volume_signature(std::vector<std::uint8_t>& out) {
  write_signature(out, kVolumeSignature, kVolumeStreamVersion);
}

void write_header_chunk(std::vector<std::uint8_t>& out, const VolumeStreamHeader& h) {
  std::vector<std::uint8_t> p;
  ByteWriter w(p);
  w.u8(h.reversible ? 1 : 0);
  w.u8(std::uint32_t(h.levels));
  w.u8(std::uint32_t(h.brick_log2));
  w.u8(std::uint32_t(h.block_log2));
  w.u8(h.coder);
  put_f64(w, h.delta);
  put_f64(w, h.max_error);
  put_text(w, h.spec);
  w.u32(h.brick_chunks);
  w.u32(std::uint32_t(h.grids.size()));
  for (std::size_t g = 0; g < h.grids.size(); ++g)
    write_grid(w, h.grids[g], g < h.blocked.size() ? h.blocked[g] : 0, h.has_missing(g));
  write_chunk(out, "VHDR", p);
}

void write_mask_chunk(std::vector<std::uint8_t>& out, std::uint32_t grid, const MaskChunk& mask) {
  std::vector<std::uint8_t> p;
  ByteWriter w(p);
  w.u32(grid);
  write_states(w, mask);
  write_chunk(out, "MASK", p);
}

void write_opaque_chunk(std::vector<std::uint8_t>& out, std::uint32_t grid,
                        const std::vector<std::uint8_t>& bytes) {
  std::vector<std::uint8_t> p;
  ByteWriter w(p);
  w.u32(grid);
  w.bytes(bytes);
  write_chunk(out, "OPAQ", p);
}

void write_blocks_chunk(std::vector<std::uint8_t>& out, std::uint32_t grid, const BlocksChunk& c) {
  std::vector<std::uint8_t> p;
  ByteWriter w(p);
  w.u32(grid);
  w.u32(std::uint32_t(c.blocks.size()));
  for (const VolumeBlock& b : c.blocks) {
    for (std::int64_t o : b.origin) put_u64(w, std::uint64_t(o));
    for (std::size_t d : b.volume.dims) w.u32(std::uint32_t(d));
  }
  w.u32(std::uint32_t(c.tiles.size()));
  for (const VolumeTile& t : c.tiles) {
    for (std::int64_t o : t.origin) put_u64(w, std::uint64_t(o));
    w.u32(t.edge);
    put_f64(w, t.value);
    w.u8(t.active ? 1 : 0);
  }
  write_states(w, c.mask);
  write_chunk(out, "BLKS", p);
}

void write_brick_chunk(std::vector<std::uint8_t>& out, const BrickChunk& b) {
  std::vector<std::uint8_t> p;
  ByteWriter w(p);
  w.u32(b.grid);
  w.u32(b.brick);
  put_f64(w, b.base_step);
  w.u32(std::uint32_t(b.entries.size()));
  const auto index = encode_index(b.entries);
  w.u32(std::uint32_t(index.size()));
  w.bytes(index);
  std::size_t lengths = 0, pieces = 0;
  for (const BlockEntry& e : b.entries) lengths += e.length;
  for (const auto& cw : b.codewords) pieces += cw.size();
  if (lengths != pieces) throw std::logic_error("write_brick_chunk: codeword bytes differ from the entries'");
  for (const auto& cw : b.codewords) w.bytes(cw);
  w.u32(std::uint32_t(b.outliers.size()));
  w.bytes(b.outliers);
  write_chunk(out, "BRIK", p);
}

}  // namespace pupwave
