// parse_volume_stream: the hostile-input side of volume_format.h.
#include <zstd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

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

VolumeGrid read_grid(ByteReader& r, std::size_t& total_voxels) {
  VolumeGrid g;
  g.name = r.str16(65535);
  const std::uint32_t cls = r.u8();
  require_stream(cls <= std::uint32_t(GridClass::fog_volume), "volume stream: grid class");
  g.grid_class = GridClass(cls);
  for (std::int64_t& o : g.origin) o = std::int64_t(get_u64(r));
  for (double& v : g.index_to_world) v = get_finite(r, "grid transform");
  require_affine(g.index_to_world);
  read_metadata(r, g.metadata);
  std::size_t voxels = 1;
  for (std::size_t& d : g.volume.dims) {
    d = r.u32();
    require_stream(d >= 1 && d <= kMaxVolumeAxis, "volume stream: absurd volume dims");
    voxels *= d;
  }
  total_voxels += voxels;
  require_stream(voxels <= kMaxVolumeVoxels && total_voxels <= kMaxVolumeVoxels,
                 "volume stream: volume too large (more than 2^31 voxels)");
  const std::uint32_t type = r.u8();
  require_stream(type <= std::uint32_t(VoxelType::f64), "volume stream: voxel type");
  g.volume.type = VoxelType(type);
  g.volume.background = get_finite(r, "background");
  const std::uint32_t sparse = r.u8();
  require_stream(sparse <= 1, "volume stream: sparse flag");
  if (sparse) g.volume.active.assign(1, 1);  // marker; the mask comes from the MASK chunk
  return g;
}

VolumeStreamHeader read_header(std::span<const std::uint8_t> payload, const DecodeLimits& limits) {
  ByteReader r(payload, "volume header");
  VolumeStreamHeader h;
  const std::uint32_t reversible = r.u8();
  h.levels = int(r.u8());
  h.brick_log2 = int(r.u8());
  h.block_log2 = int(r.u8());
  require_stream(reversible <= 1, "volume stream: reversible flag");
  h.reversible = reversible == 1;
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
  for (std::size_t i = 0; i < grids; ++i) h.grids.push_back(read_grid(r, total));
  require_stream(r.remaining() == 0, "volume stream: trailing bytes in header");
  // Before any mask (one byte per voxel) or output is allocated.
  check_decode_limit(total, limits, "volume stream: voxels of all grids");
  return h;
}

MaskChunk read_mask(std::span<const std::uint8_t> payload, const VolumeStreamHeader& h, std::uint32_t& grid) {
  ByteReader r(payload, "volume mask");
  grid = r.u32();
  require_stream(grid < h.grids.size() && h.grids[grid].volume.is_sparse(), "volume stream: mask grid");
  const Volume& v = h.grids[grid].volume;
  const std::size_t count = v.dims[0] * v.dims[1] * v.dims[2];
  const auto packed = r.bytes(r.u32());
  const unsigned long long content = ZSTD_getFrameContentSize(packed.data(), packed.size());
  require_stream(content == count, "volume stream: mask size");
  MaskChunk m;
  m.states.resize(count);
  const std::size_t n = ZSTD_decompress(m.states.data(), count, packed.data(), packed.size());
  require_stream(!ZSTD_isError(n) && n == count, "volume stream: corrupt mask");
  const std::size_t others = r.u32();
  require_stream(others <= r.remaining() / 8, "volume stream: inactive value count");
  for (std::size_t i = 0; i < others; ++i) m.other_values.push_back(get_finite(r, "inactive value"));
  require_stream(r.remaining() == 0, "volume stream: trailing bytes in mask");
  return m;
}

// Code-blocks of brick `brick` of grid `grid` (0 for an index outside the grid), computed from
// the geometry so that a count is checked before the index is decoded.
std::size_t brick_block_count(const VolumeStreamHeader& h, std::uint32_t grid, std::uint32_t brick) {
  const Extent& dims = h.grids[grid].volume.dims;
  const std::size_t edge = std::size_t(1) << h.brick_log2;
  Extent n{}, size{};
  for (std::size_t a = 0; a < 3; ++a) n[a] = (dims[a] + edge - 1) / edge;
  if (brick >= n[0] * n[1] * n[2]) return 0;
  const Extent at{brick % n[0], brick / n[0] % n[1], brick / n[0] / n[1]};
  for (std::size_t a = 0; a < 3; ++a) size[a] = std::min(edge, dims[a] - at[a] * edge);
  BrickCoding coding;
  coding.levels = h.levels;
  coding.block = std::size_t(1) << h.block_log2;
  return brick_blocks(coding, size).size();
}

BrickChunk read_brick(std::span<const std::uint8_t> payload, const VolumeStreamHeader& h) {
  ByteReader r(payload, "volume brick");
  BrickChunk b;
  b.grid = r.u32();
  b.brick = r.u32();
  require_stream(b.grid < h.grids.size(), "volume stream: brick grid");
  require_stream(brick_block_count(h, b.grid, b.brick) > 0, "volume stream: brick index out of range");
  b.base_step = get_finite(r, "base step");
  require_stream(b.base_step > 0.0, "volume stream: base step");
  const std::size_t blocks = r.u32();
  require_stream(blocks <= kMaxBlocksPerBrick && blocks == brick_block_count(h, b.grid, b.brick),
                 "volume stream: block count does not match the brick geometry");
  b.entries = decode_index(r.bytes(r.u32()), blocks);
  for (const BlockEntry& e : b.entries) b.codewords.push_back(r.bytes(e.length));
  const auto outliers = r.bytes(r.u32());
  b.outliers.assign(outliers.begin(), outliers.end());
  require_stream(r.remaining() == 0, "volume stream: trailing bytes in brick");
  return b;
}

}  // namespace

ParsedVolumeStream parse_volume_stream(std::span<const std::uint8_t> bytes, const DecodeLimits& limits) {
  ChunkReader r(bytes, kVolumeSignature, kVolumeStreamVersion, "volume stream");
  const Chunk head = r.expect("VHDR");
  ParsedVolumeStream s;
  s.header = read_header(head.payload, limits);
  s.masks.resize(s.header.grids.size());
  std::size_t masks = 0, needed = 0;
  for (const VolumeGrid& g : s.header.grids) needed += g.volume.is_sparse() ? 1 : 0;
  while (!r.at_end()) {
    const Chunk c = r.next();
    if (c.is("MASK")) {
      std::uint32_t grid = 0;
      MaskChunk m = read_mask(c.payload, s.header, grid);
      require_stream(s.masks[grid].states.empty(), "volume stream: repeated mask");
      s.masks[grid] = std::move(m);
      ++masks;
    } else if (c.is("BRIK")) {
      require_stream(s.bricks.size() < s.header.brick_chunks, "volume stream: too many bricks");
      s.bricks.push_back(read_brick(c.payload, s.header));
    } else {
      throw DecodeError("volume stream: unknown chunk " + c.name());
    }
  }
  require_stream(masks == needed, "volume stream truncated (missing mask)");
  require_stream(s.bricks.size() == s.header.brick_chunks, "volume stream truncated (missing bricks)");
  return s;
}

}  // namespace pupwave
