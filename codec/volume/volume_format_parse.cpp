// parse_volume_stream: the hostile-input side of volume_format.h.
#include <zstd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "codec/error.h"
#include "codec/format/byte_io.h"
#include "codec/format/chunks.h"
#include "codec/format/decode_limits.h"
#include "codec/volume/volume_brick.h"
#include "codec/volume/volume_format.h"

namespace pupwave {
namespace {

constexpr std::size_t kMaxSpec = 4096;
constexpr std::size_t kMaxMetadata = 4096;
constexpr std::size_t kMaxBlocksPerBrick = std::size_t(1) << 20;
// Index coordinates of blocks and tiles stay in OpenVDB's 32-bit signed range.
constexpr std::int64_t kMinCoord = -(std::int64_t(1) << 31);
constexpr std::int64_t kMaxCoord = (std::int64_t(1) << 31) - 1;

std::size_t total_block_voxels(const BlocksChunk& c) {
  std::size_t n = 0;
  for (const VolumeBlock& b : c.blocks) n += b.volume.count();
  return n;
}

std::uint64_t get_u64(ByteReader& r) {
  const std::uint64_t lo = r.u32();
  return lo | (std::uint64_t(r.u32()) << 32);
}
double get_f64(ByteReader& r) { return std::bit_cast<double>(get_u64(r)); }
double get_finite(ByteReader& r, const char* what) {
  const double v = get_f64(r);
  require_stream(std::isfinite(v), [&] { return std::string("volume stream: non-finite ") + what; });
  return v;
}

void read_metadata(ByteReader& r, std::map<std::string, MetaValue>& metadata) {
  const std::size_t count = r.u32();
  require_stream(count <= kMaxMetadata, "volume stream: too many metadata entries");
  for (std::size_t i = 0; i < count; ++i) {
    const std::string key = r.str16(65535);
    MetaValue m;
    const std::uint32_t kind = r.u8();
    require_stream(kind <= std::uint32_t(MetaValue::Kind::vec3d), "volume stream: metadata kind");
    m.kind = MetaValue::Kind(kind);
    m.text = r.str16(65535);
    m.integer = std::int64_t(get_u64(r));
    for (double& v : m.numbers) v = get_f64(r);
    metadata[key] = m;
  }
}

// A grid transform must be affine and invertible (OpenVDB refuses anything else on writing, so
// a decode would otherwise end in an error after all the work). Row-major 4x4, translation in
// the last row (m[12..14]).
void require_affine(const std::array<double, 16>& m) {
  require_stream(m[3] == 0.0 && m[7] == 0.0 && m[11] == 0.0 && m[15] == 1.0,
                 "volume stream: grid transform is not affine (last column must be 0, 0, 0, 1)");
  const double det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
                     m[2] * (m[4] * m[9] - m[5] * m[8]);
  require_stream(std::isfinite(det) && det != 0.0, "volume stream: grid transform is singular");
}

// An index-space coordinate in OpenVDB's int32 range (so level placement and box arithmetic
// never overflow; a fuzzed grid origin of -2^63 once did).
std::array<std::int64_t, 3> get_origin(ByteReader& r) {
  std::array<std::int64_t, 3> o{};
  for (std::int64_t& v : o) {
    v = std::int64_t(get_u64(r));
    require_stream(v >= kMinCoord && v <= kMaxCoord, "volume stream: coordinate out of range");
  }
  return o;
}

VolumeGrid read_grid(ByteReader& r, std::uint8_t version, std::size_t& total_voxels, std::uint8_t& blocked,
                     std::uint8_t& missing) {
  VolumeGrid g;
  g.name = r.str16(65535);
  const std::uint32_t cls = r.u8();
  require_stream(cls <= std::uint32_t(GridClass::fog_volume), "volume stream: grid class");
  g.grid_class = GridClass(cls);
  g.origin = get_origin(r);
  for (double& v : g.index_to_world) v = get_finite(r, "grid transform");
  require_affine(g.index_to_world);
  read_metadata(r, g.metadata);
  std::size_t voxels = 1;
  for (std::size_t& d : g.volume.dims) {
    d = r.u32();
    require_stream(d >= 1 && d <= kMaxVolumeAxis, "volume stream: absurd volume dims");
    voxels *= d;
  }
  const std::uint32_t type = r.u8();
  require_stream(type <= std::uint32_t(VoxelType::f64), "volume stream: voxel type");
  g.volume.type = VoxelType(type);
  g.volume.background = get_finite(r, "background");
  const std::uint32_t sparse = r.u8();
  require_stream(sparse <= (version >= 7 ? 4u : 3u), "volume stream: sparse flag");
  blocked = sparse == 3 ? 2 : sparse == 2 ? 1 : 0;
  missing = sparse == 4 ? 1 : 0;
  if (sparse == 1 || sparse == 4) g.volume.active.assign(1, 1);  // marker; the mask comes from MASK
  // A sparse-native grid's dims are its bounding box only; its blocks are counted in BLKS.
  if (!blocked) total_voxels += voxels;
  require_stream(voxels <= kMaxVolumeVoxels || blocked,
                 "volume stream: volume too large (more than 2^31 voxels)");
  require_stream(total_voxels <= kMaxVolumeVoxels, "volume stream: volume too large (more than 2^31 voxels)");
  return g;
}

// Voxels a decode allocates for the grids' headers alone: dense grids, and sparse boxes whole when
// `count` says so (sparse-native blocks are counted with their BLKS chunk, box content with its mask).
std::size_t header_decoded_voxels(const VolumeStreamHeader& h, SparseBoxCount count) {
  std::size_t n = 0;
  for (std::size_t g = 0; g < h.grids.size(); ++g)
    if (!h.blocked[g] && (!h.grids[g].volume.is_sparse() || h.has_missing(g) || count == SparseBoxCount::box))
      n += h.grids[g].volume.count();
  return n;
}

VolumeStreamHeader read_header(std::span<const std::uint8_t> payload, std::uint8_t version,
                               const DecodeLimits& limits, SparseBoxCount count) {
  ByteReader r(payload, "volume header");
  VolumeStreamHeader h;
  h.version = version;
  const std::uint32_t reversible = r.u8();
  h.levels = int(r.u8());
  h.brick_log2 = int(r.u8());
  h.block_log2 = int(r.u8());
  h.coder = std::uint8_t(r.u8());
  require_stream(reversible <= 1, "volume stream: reversible flag");
  h.reversible = reversible == 1;
  require_stream(h.coder <= 1 && !(h.coder == 1 && h.reversible), "volume stream: coefficient coder");
  require_stream(h.brick_log2 >= 3 && h.brick_log2 <= 8, "volume stream: brick size");
  require_stream(h.block_log2 >= 4 && h.block_log2 <= 6, "volume stream: code-block size");
  require_stream(h.levels <= h.brick_log2, "volume stream: levels");
  h.delta = get_finite(r, "delta");
  require_stream(h.delta >= 0.0 && h.delta < 1.0, "volume stream: reconstruction offset");
  h.max_error = get_finite(r, "error bound");
  require_stream(h.max_error >= 0.0, "volume stream: error bound");
  h.spec = r.str16(kMaxSpec);
  h.brick_chunks = r.u32();
  const std::size_t grids = r.u32();
  require_stream(grids >= 1 && grids <= kMaxVolumeGrids, "volume stream: grid count");
  std::size_t total = 0;
  h.blocked.assign(grids, 0);
  h.missing.assign(grids, 0);
  for (std::size_t i = 0; i < grids; ++i)
    h.grids.push_back(read_grid(r, version, total, h.blocked[i], h.missing[i]));
  require_stream(r.remaining() == 0, "volume stream: trailing bytes in header");
  // Before any mask is read or output allocated.
  check_decode_limit(header_decoded_voxels(h, count), limits, "volume stream: voxels of all grids");
  return h;
}

// The inactive_other values of a mask of `count` voxels: raw f64s (version 6) or a zstd frame of
// them (version 7). Non-finite values belong only to a grid with missing values.
std::vector<double> read_inactive_values(ByteReader& r, std::uint8_t version, std::size_t count,
                                         bool missing) {
  const std::size_t others = r.u32();
  std::vector<double> values;
  if (version < 7) {
    require_stream(others <= r.remaining() / 8, "volume stream: inactive value count");
    values.reserve(others);
    for (std::size_t i = 0; i < others; ++i) values.push_back(get_finite(r, "inactive value"));
    return values;
  }
  const auto packed = r.bytes(r.u32());
  const unsigned long long content = ZSTD_getFrameContentSize(packed.data(), packed.size());
  require_stream(others <= count && content == others * 8, "volume stream: inactive value count");
  std::vector<std::uint8_t> raw(others * 8);
  const std::size_t n = ZSTD_decompress(raw.data(), raw.size(), packed.data(), packed.size());
  require_stream(!ZSTD_isError(n) && n == raw.size(), "volume stream: corrupt inactive values");
  ByteReader v(raw, "volume inactive values");
  values.reserve(others);
  for (std::size_t i = 0; i < others; ++i) {
    values.push_back(get_f64(v));
    require_stream(missing || std::isfinite(values.back()), "volume stream: non-finite inactive value");
  }
  return values;
}

// Voxel states of `count` voxels (zstd) and the inactive_other values.
MaskChunk read_states(ByteReader& r, std::uint8_t version, std::size_t count) {
  const auto packed = r.bytes(r.u32());
  const unsigned long long content = ZSTD_getFrameContentSize(packed.data(), packed.size());
  require_stream(content == count, "volume stream: mask size");
  MaskChunk m;
  m.states.resize(count);
  const std::size_t n = ZSTD_decompress(m.states.data(), count, packed.data(), packed.size());
  require_stream(!ZSTD_isError(n) && n == count, "volume stream: corrupt mask");
  m.other_values = read_inactive_values(r, version, count, false);
  return m;
}

// A sparse box grid's MASK: states kept compressed and summarised per brick (volume_box_mask.h).
// `already`: voxels counted against the limit before it (box mode: the limit was applied to boxes).
BoxMask read_mask(std::span<const std::uint8_t> payload, const VolumeStreamHeader& h, std::uint32_t& grid,
                  const DecodeLimits& limits, std::size_t already) {
  ByteReader r(payload, "volume mask");
  grid = r.u32();
  require_stream(grid < h.grids.size() && h.grids[grid].volume.is_sparse(), "volume stream: mask grid");
  const auto frame = r.bytes(r.u32());
  std::vector<double> values =
      read_inactive_values(r, h.version, h.grids[grid].volume.count(), h.has_missing(grid));
  require_stream(r.remaining() == 0, "volume stream: trailing bytes in mask");
  return scan_box_mask(frame, std::move(values), h.grids[grid].volume.dims, h.brick_log2, limits, already);
}

// Code-blocks of a brick of extent `size`, computed from the geometry so that a count is
// checked before the index is decoded.
std::size_t block_count_of(const VolumeStreamHeader& h, const Extent& size) {
  BrickCoding coding;
  coding.levels = h.levels;
  coding.block = std::size_t(1) << h.block_log2;
  return brick_blocks(coding, size).size();
}

// Code-blocks of brick `brick` of grid `grid` (0 for an index outside the grid). A box grid's
// bricks tile its box; a sparse-native grid's bricks tile each of its blocks in turn
// (`block_bricks`, the brick extents listed when its BLKS chunk was read).
std::size_t brick_block_count(const VolumeStreamHeader& h, std::uint32_t grid, std::uint32_t brick,
                              const std::vector<Extent>& block_bricks) {
  if (h.blocked[grid] == 2) return 0;  // opaque grids have no bricks
  if (h.blocked[grid] == 1) return brick < block_bricks.size() ? block_count_of(h, block_bricks[brick]) : 0;
  const Extent& dims = h.grids[grid].volume.dims;
  const std::size_t edge = std::size_t(1) << h.brick_log2;
  Extent n{}, size{};
  for (std::size_t a = 0; a < 3; ++a) n[a] = (dims[a] + edge - 1) / edge;
  if (brick >= n[0] * n[1] * n[2]) return 0;
  const Extent at{brick % n[0], brick / n[0] % n[1], brick / n[0] / n[1]};
  for (std::size_t a = 0; a < 3; ++a) size[a] = std::min(edge, dims[a] - at[a] * edge);
  return block_count_of(h, size);
}

// Blocks, tiles and block voxel states of a sparse-native grid; block voxels count towards
// total_voxels (the 2^31 cap of all grids).
BlocksChunk read_blocks(std::span<const std::uint8_t> payload, const VolumeStreamHeader& h,
                        std::uint32_t& grid, std::size_t& total_voxels) {
  ByteReader r(payload, "volume blocks");
  grid = r.u32();
  require_stream(grid < h.grids.size() && h.blocked[grid] == 1, "volume stream: blocks grid");
  BlocksChunk c;
  const std::size_t blocks = r.u32();
  require_stream(blocks <= r.remaining() / 36, "volume stream: block count");
  for (std::size_t i = 0; i < blocks; ++i) {
    VolumeBlock b;
    b.origin = get_origin(r);
    std::size_t voxels = 1;
    for (std::size_t& d : b.volume.dims) {
      d = r.u32();
      require_stream(d >= 1 && d <= kMaxVolumeAxis, "volume stream: absurd block dims");
      voxels *= d;
    }
    total_voxels += voxels;
    require_stream(total_voxels <= kMaxVolumeVoxels,
                   "volume stream: volume too large (more than 2^31 voxels)");
    b.volume.type = h.grids[grid].volume.type;
    b.volume.background = h.grids[grid].volume.background;
    c.blocks.push_back(std::move(b));
  }
  const std::size_t tiles = r.u32();
  require_stream(tiles <= r.remaining() / 37, "volume stream: tile count");  // 37 bytes per tile
  for (std::size_t i = 0; i < tiles; ++i) {
    VolumeTile t;
    t.origin = get_origin(r);
    t.edge = r.u32();
    require_stream(t.edge >= 1 && t.edge <= kMaxVolumeAxis, "volume stream: tile edge");
    t.value = get_finite(r, "tile value");
    const std::uint32_t active = r.u8();
    require_stream(active <= 1, "volume stream: tile state");
    t.active = active == 1;
    c.tiles.push_back(t);
  }
  c.mask = read_states(r, h.version, total_block_voxels(c));
  require_stream(r.remaining() == 0, "volume stream: trailing bytes in blocks");
  return c;
}

BrickChunk read_brick(std::span<const std::uint8_t> payload, const VolumeStreamHeader& h,
                      const std::vector<std::vector<Extent>>& block_bricks) {
  ByteReader r(payload, "volume brick");
  BrickChunk b;
  b.grid = r.u32();
  b.brick = r.u32();
  require_stream(b.grid < h.grids.size(), "volume stream: brick grid");
  const std::size_t geometry_blocks = brick_block_count(h, b.grid, b.brick, block_bricks[b.grid]);
  require_stream(geometry_blocks > 0, "volume stream: brick index out of range");
  b.base_step = get_finite(r, "base step");
  require_stream(b.base_step > 0.0, "volume stream: base step");
  const std::size_t blocks = r.u32();
  require_stream(blocks <= kMaxBlocksPerBrick && blocks == geometry_blocks,
                 "volume stream: block count does not match the brick geometry");
  b.entries = decode_index(r.bytes(r.u32()), blocks);
  for (const BlockEntry& e : b.entries) b.codewords.push_back(r.bytes(e.length));
  const auto outliers = r.bytes(r.u32());
  b.outliers.assign(outliers.begin(), outliers.end());
  require_stream(r.remaining() == 0, "volume stream: trailing bytes in brick");
  return b;
}

}  // namespace

ParsedVolumeStream parse_volume_stream(std::span<const std::uint8_t> bytes, const DecodeLimits& limits,
                                       SparseBoxCount count) {
  ChunkReader r(bytes, kVolumeSignature, kVolumeStreamVersion, "volume stream", kOldestVolumeStreamVersion);
  const Chunk head = r.expect("VHDR");
  ParsedVolumeStream s;
  s.header = read_header(head.payload, r.version(), limits, count);
  // Voxels the decode allocates, against the limit; box mode counted whole boxes already.
  std::size_t decoded = header_decoded_voxels(s.header, count);
  const DecodeLimits mask_limits =
      count == SparseBoxCount::box ? DecodeLimits{std::numeric_limits<std::size_t>::max()} : limits;
  s.masks.resize(s.header.grids.size());
  s.layouts.resize(s.header.grids.size());
  s.opaque.resize(s.header.grids.size());
  std::size_t masks = 0, needed = 0, total_voxels = 0;
  for (std::size_t g = 0; g < s.header.grids.size(); ++g) {
    needed += s.header.grids[g].volume.is_sparse() || s.header.blocked[g] ? 1 : 0;
    if (!s.header.blocked[g]) total_voxels += s.header.grids[g].volume.count();
  }
  std::vector<std::uint8_t> seen_layout(s.header.grids.size(), 0);
  std::vector<std::vector<Extent>> block_bricks(s.header.grids.size());  // of sparse-native grids
  const std::size_t brick_edge = std::size_t(1) << s.header.brick_log2;
  s.grid_bytes.assign(s.header.grids.size(), 0);
  constexpr std::size_t kFraming = 12;  // name, length and CRC of a chunk
  while (!r.at_end()) {
    const Chunk c = r.next();
    if (c.is("MASK")) {
      std::uint32_t grid = 0;
      BoxMask m = read_mask(c.payload, s.header, grid, mask_limits, decoded);
      require_stream(s.masks[grid].empty(), "volume stream: repeated mask");
      if (count == SparseBoxCount::content && !s.header.has_missing(grid)) decoded += m.content_voxels;
      s.masks[grid] = std::move(m);
      s.grid_bytes[grid] += c.payload.size() + kFraming;
      ++masks;
    } else if (c.is("BLKS")) {
      std::uint32_t grid = 0;
      const std::size_t before = total_voxels;
      BlocksChunk b = read_blocks(c.payload, s.header, grid, total_voxels);
      // Block voxels are allocated on decode: the decode limit covers them as it covers boxes.
      decoded += total_voxels - before;
      check_decode_limit(decoded, limits, "volume stream: voxels of all grids");
      require_stream(seen_layout[grid] == 0, "volume stream: repeated blocks");
      seen_layout[grid] = 1;
      for (const VolumeBlock& block : b.blocks)
        for (const BrickBox& box : brick_boxes(block.volume.dims, brick_edge))
          block_bricks[grid].push_back(box.size);
      s.layouts[grid] = std::move(b);
      s.grid_bytes[grid] += c.payload.size() + kFraming;
      ++masks;
    } else if (c.is("OPAQ")) {
      ByteReader op(c.payload, "volume opaque grid");
      const std::uint32_t grid = op.u32();
      require_stream(grid < s.header.grids.size() && s.header.blocked[grid] == 2,
                     "volume stream: opaque grid");
      require_stream(seen_layout[grid] == 0 && op.remaining() > 0,
                     "volume stream: repeated or empty opaque grid");
      seen_layout[grid] = 1;
      const auto serialised = op.bytes(op.remaining());
      s.opaque[grid].assign(serialised.begin(), serialised.end());
      s.grid_bytes[grid] += c.payload.size() + kFraming;
      ++masks;
    } else if (c.is("BRIK")) {
      require_stream(s.bricks.size() < s.header.brick_chunks, "volume stream: too many bricks");
      s.bricks.push_back(read_brick(c.payload, s.header, block_bricks));
      s.grid_bytes[s.bricks.back().grid] += c.payload.size() + kFraming;
    } else {
      throw DecodeError("volume stream: unknown chunk " + c.name());
    }
  }
  require_stream(masks == needed, "volume stream truncated (missing mask)");
  require_stream(s.bricks.size() == s.header.brick_chunks, "volume stream truncated (missing bricks)");
  return s;
}

}  // namespace pupwave
