// decode_volumes: parse and validate the stream, decode every brick in parallel (stopping the
// inverse transform at the requested level), apply outlier corrections, restore the sparse
// topology and inactive values exactly.
#include <algorithm>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "codec/error.h"
#include "codec/format/chunks.h"
#include "codec/volume/volume_brick.h"
#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_format.h"
#include "codec/volume/volume_outliers.h"
#include "transforms/separable.h"
#include "transforms/spec.h"

namespace pupwave {
namespace {

Transform1DPtr stream_transform(const VolumeStreamHeader& h) {
  try {
    check_stream_spec(h.spec);  // bounded design work before anything is designed
    auto t = make_transform(h.spec);
    require_stream(t->is_reversible() || !h.reversible,
                   "volume stream: lossless with an irreversible transform");
    return t;
  } catch (const std::invalid_argument& e) {
    throw DecodeError(std::string("volume stream: bad transform spec: ") + e.what());
  }
}

// The bricks of one grid: of its box, or of each of its blocks in turn (block: which one).
struct GridBricks {
  std::vector<BrickBox> boxes;
  std::vector<std::uint32_t> block;
};

// Whether each brick of `boxes` holds an active voxel by `states` (voxels of a `dims` box).
void mark_active_bricks(const Extent& dims, const std::uint8_t* states, const std::vector<BrickBox>& boxes,
                        std::vector<std::uint8_t>& expected) {
  for (const BrickBox& box : boxes) {
    bool any = false;
    for (std::size_t z = 0; z < box.size[2] && !any; ++z)
      for (std::size_t y = 0; y < box.size[1] && !any; ++y) {
        const std::size_t row =
            box.offset[0] + dims[0] * ((box.offset[1] + y) + dims[1] * (box.offset[2] + z));
        for (std::size_t x = 0; x < box.size[0]; ++x)
          any = any || states[row + x] == std::uint8_t(VoxelState::active);
      }
    expected.push_back(any ? 1 : 0);
  }
}

// Bricks of each grid a valid stream codes: all for dense grids, those with an active voxel
// for sparse grids (from the mask states).
std::vector<std::uint8_t> expected_bricks(const ParsedVolumeStream& s, std::size_t g, std::size_t edge) {
  const Volume& v = s.header.grids[g].volume;
  std::vector<std::uint8_t> expected;
  if (s.header.blocked[g] == 2) return expected;  // opaque: no bricks
  if (s.header.blocked[g] == 1) {
    std::size_t at = 0;
    for (const VolumeBlock& b : s.layouts[g].blocks) {
      mark_active_bricks(b.volume.dims, s.layouts[g].mask.states.data() + at,
                         brick_boxes(b.volume.dims, edge), expected);
      at += b.volume.count();
    }
  } else if (v.is_sparse()) {
    mark_active_bricks(v.dims, s.masks[g].states.data(), brick_boxes(v.dims, edge), expected);
  } else {
    expected.assign(brick_boxes(v.dims, edge).size(), 1);
  }
  return expected;
}

// Checks that the BRIK chunks code exactly the bricks every grid needs, once each.
void check_brick_set(const ParsedVolumeStream& s, const std::vector<GridBricks>& bricks) {
  std::vector<std::vector<std::uint8_t>> seen(bricks.size());
  for (std::size_t g = 0; g < bricks.size(); ++g) seen[g].assign(bricks[g].boxes.size(), 0);
  for (const BrickChunk& b : s.bricks) {
    require_stream(b.brick < bricks[b.grid].boxes.size(), "volume stream: brick index out of range");
    require_stream(seen[b.grid][b.brick] == 0, "volume stream: repeated brick");
    seen[b.grid][b.brick] = 1;
  }
  const std::size_t edge = std::size_t(1) << s.header.brick_log2;
  for (std::size_t g = 0; g < bricks.size(); ++g)
    require_stream(expected_bricks(s, g, edge) == seen[g],
                   "volume stream: bricks do not match the active topology");
}

// Writes a decoded brick (extent `part`) into the output volume at `offset`.
void place(Volume& out, const Extent& offset, const Extent& part, const std::vector<double>& values) {
  std::size_t k = 0;
  for (std::size_t z = 0; z < part[2]; ++z)
    for (std::size_t y = 0; y < part[1]; ++y)
      for (std::size_t x = 0; x < part[0]; ++x)
        out.samples[out.index(offset[0] + x, offset[1] + y, offset[2] + z)] = values[k++];
}

// Full-resolution sparse restore: active mask from the states, inactive values exact
// (`other` indexes mask.other_values and advances past those used).
void restore_states(Volume& out, const std::uint8_t* states, const MaskChunk& mask, std::size_t& other) {
  out.active.assign(out.count(), 0);
  for (std::size_t i = 0; i < out.count(); ++i) {
    switch (VoxelState(states[i])) {
      case VoxelState::active: out.active[i] = 1; break;
      case VoxelState::inactive_background: out.samples[i] = out.background; break;
      case VoxelState::inactive_negative: out.samples[i] = -out.background; break;
      case VoxelState::inactive_other:
        require_stream(other < mask.other_values.size(), "volume stream: missing inactive values");
        out.samples[i] = mask.other_values[other++];
        break;
      default: throw DecodeError("volume stream: bad voxel state");
    }
  }
}

void restore_mask(Volume& out, const MaskChunk& mask) {
  std::size_t other = 0;
  restore_states(out, mask.states.data(), mask, other);
  require_stream(other == mask.other_values.size(), "volume stream: extra inactive values");
}

// Reduced-resolution sparse restore: a coarse voxel is active when any of its children is;
// an inactive one takes the mean of its children's (exact) values.
void restore_coarse_mask(Volume& out, const Volume& fine, int level) {
  const std::size_t f = std::size_t(1) << level;
  out.active.assign(out.count(), 0);
  std::vector<double> sum(out.count(), 0.0);
  std::vector<std::size_t> n(out.count(), 0);
  for (std::size_t z = 0; z < fine.dims[2]; ++z)
    for (std::size_t y = 0; y < fine.dims[1]; ++y)
      for (std::size_t x = 0; x < fine.dims[0]; ++x) {
        const std::size_t c = out.index(x / f, fine.dims[1] > 1 ? y / f : y, fine.dims[2] > 1 ? z / f : z);
        const std::size_t i = fine.index(x, y, z);
        if (fine.active[i]) out.active[c] = 1;
        sum[c] += fine.samples[i];
        ++n[c];
      }
  for (std::size_t c = 0; c < out.count(); ++c)
    if (!out.active[c]) out.samples[c] = sum[c] / double(n[c]);
}

// Level-k placement (the lod convention of docs/volumes.md): voxel size x 2^k, coarse voxel c
// where fine index origin + 2^k c lies; the part of the origin that 2^k does not divide goes
// into the translation.
void scale_placement(VolumeGrid& g, int level) {
  const std::int64_t f = std::int64_t(1) << level;
  auto& m = g.index_to_world;
  for (std::size_t a = 0; a < 3; ++a) {
    const std::int64_t o = g.origin[a];
    const std::int64_t c = o >= 0 ? o / f : -((-o + f - 1) / f);
    g.origin[a] = c;
    for (std::size_t j = 0; j < 3; ++j) m[12 + j] += double(o - c * f) * m[4 * a + j];
  }
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t j = 0; j < 3; ++j) m[4 * a + j] *= double(f);
}

// Bricks of every grid. A dense grid needs a BRIK per brick, so its brick count is bounded by
// the chunks present; checked before the brick list is allocated.
std::vector<GridBricks> grid_bricks(const ParsedVolumeStream& s) {
  const std::size_t edge = std::size_t(1) << s.header.brick_log2;
  std::vector<GridBricks> bricks(s.header.grids.size());
  for (std::size_t g = 0; g < s.header.grids.size(); ++g) {
    const Volume& v = s.header.grids[g].volume;
    if (s.header.blocked[g] == 2) continue;  // opaque: no bricks
    if (s.header.blocked[g] == 1) {
      for (std::uint32_t k = 0; k < s.layouts[g].blocks.size(); ++k)
        for (const BrickBox& box : brick_boxes(s.layouts[g].blocks[k].volume.dims, edge)) {
          bricks[g].boxes.push_back(box);
          bricks[g].block.push_back(k);
        }
      continue;
    }
    std::size_t count = 1;
    for (std::size_t d : v.dims) count *= (d + edge - 1) / edge;
    require_stream(v.is_sparse() || count <= s.bricks.size(), "volume stream truncated (missing bricks)");
    bricks[g].boxes = brick_boxes(v.dims, edge);
    bricks[g].block.assign(bricks[g].boxes.size(), 0);
  }
  return bricks;
}

// Floor of o / 2^level.
std::int64_t coarse(std::int64_t o, int level) {
  const std::int64_t f = std::int64_t(1) << level;
  return o >= 0 ? o / f : -((-o + f - 1) / f);
}

// Blocks (at 1/2^level resolution, filled with background) and tiles of a sparse-native grid.
// Blocks start on OpenVDB leaves (multiples of 8), so levels above 3 would misplace them.
void allocate_blocks(VolumeGrid& g, const BlocksChunk& layout, int level) {
  const std::int64_t f = std::int64_t(1) << level;
  for (const VolumeBlock& b : layout.blocks) {
    VolumeBlock out;
    for (std::size_t a = 0; a < 3; ++a) {
      if (b.origin[a] % f != 0)
        throw std::invalid_argument("level " + std::to_string(level) + " of grid '" + g.name +
                                    "': a block does not start on a multiple of 2^level (sparse grids decode "
                                    "at levels up to 3)");
      out.origin[a] = b.origin[a] / f;
    }
    out.volume = Volume(level_extent(b.volume.dims, level), g.volume.type);
    out.volume.background = g.volume.background;
    std::fill(out.volume.samples.begin(), out.volume.samples.end(), g.volume.background);
    g.blocks.push_back(std::move(out));
  }
  for (VolumeTile t : layout.tiles) {
    for (std::int64_t& o : t.origin) o = coarse(o, level);
    t.edge = std::uint32_t((std::int64_t(t.edge) + f - 1) / f);
    g.tiles.push_back(t);
  }
}

// Active masks and exact inactive values of each block (coarsened at level > 0).
void restore_blocks(VolumeGrid& g, const BlocksChunk& layout, int level) {
  std::size_t at = 0, other = 0;
  for (std::size_t k = 0; k < layout.blocks.size(); ++k) {
    const std::uint8_t* states = layout.mask.states.data() + at;
    at += layout.blocks[k].volume.count();
    if (level == 0) {
      restore_states(g.blocks[k].volume, states, layout.mask, other);
      continue;
    }
    Volume fine(layout.blocks[k].volume.dims, g.volume.type);
    fine.background = g.volume.background;
    restore_states(fine, states, layout.mask, other);
    restore_coarse_mask(g.blocks[k].volume, fine, level);
  }
  require_stream(other == layout.mask.other_values.size(), "volume stream: extra inactive values");
}

// Active masks and exact inactive values of the sparse grids (coarsened at level > 0).
void restore_sparse(std::vector<VolumeGrid>& grids, const ParsedVolumeStream& s, int level) {
  for (std::size_t g = 0; g < grids.size(); ++g) {
    if (s.header.blocked[g] == 1) restore_blocks(grids[g], s.layouts[g], level);
    if (!s.header.grids[g].volume.is_sparse()) continue;
    if (level == 0) {
      restore_mask(grids[g].volume, s.masks[g]);
      continue;
    }
    Volume fine = s.header.grids[g].volume;  // full-resolution topology and inactive values
    fine.samples.assign(fine.count(), 0.0);
    restore_mask(fine, s.masks[g]);
    restore_coarse_mask(grids[g].volume, fine, level);
  }
}

// A brick's decoded values at `level` (outliers applied at full resolution), rounded to the
// grid's stored type, x fastest.
std::vector<double> brick_values(const ParsedVolumeStream& s, const BrickCoding& coding, const BrickChunk& b,
                                 const BrickBox& box, int level) {
  const VoxelType type = s.header.grids[b.grid].volume.type;
  auto values = decode_brick(coding, box.size, b.base_step, b.entries, b.codewords, level);
  if (level == 0 && s.header.max_error > 0.0)
    apply_outliers(values, decode_outliers(b.outliers, box.count()), s.header.max_error, type);
  for (double& v : values) v = to_stored(v, type);
  return values;
}

void fill_output(const VolumeOutput& out, double value, VoxelType type) {
  value = to_stored(value, type);
  for (std::size_t z = 0; z < out.dims[2]; ++z)
    for (std::size_t y = 0; y < out.dims[1]; ++y)
      for (std::size_t x = 0; x < out.dims[0]; ++x) out.set(x, y, z, value);
}

// restore_states for a typed output: inactive voxels get their exact values, `out.active` (if
// set) the mask.
void restore_output_states(const VolumeOutput& out, double background, VoxelType type,
                           const MaskChunk& mask) {
  std::size_t i = 0, other = 0;
  for (std::size_t z = 0; z < out.dims[2]; ++z)
    for (std::size_t y = 0; y < out.dims[1]; ++y)
      for (std::size_t x = 0; x < out.dims[0]; ++x, ++i) {
        const auto state = VoxelState(mask.states[i]);
        if (out.active != nullptr) out.active[i] = state == VoxelState::active ? 1 : 0;
        switch (state) {
          case VoxelState::active: break;
          case VoxelState::inactive_background: out.set(x, y, z, to_stored(background, type)); break;
          case VoxelState::inactive_negative: out.set(x, y, z, to_stored(-background, type)); break;
          case VoxelState::inactive_other:
            require_stream(other < mask.other_values.size(), "volume stream: missing inactive values");
            out.set(x, y, z, to_stored(mask.other_values[other++], type));
            break;
          default: throw DecodeError("volume stream: bad voxel state");
        }
      }
  require_stream(other == mask.other_values.size(), "volume stream: extra inactive values");
}

}  // namespace

bool is_volume_stream(std::span<const std::uint8_t> bytes) { return has_signature(bytes, kVolumeSignature); }

std::vector<VolumeGrid> decode_volumes(std::span<const std::uint8_t> bytes, int level, const Executor& ex) {
  return decode_volumes(bytes, level, ex, DecodeLimits{});
}

std::vector<VolumeGrid> decode_volumes(std::span<const std::uint8_t> bytes, int level, const Executor& ex,
                                       const DecodeLimits& limits) {
  const ParsedVolumeStream s = parse_volume_stream(bytes, limits);
  const VolumeStreamHeader& h = s.header;
  if (level < 0 || level > h.levels)
    throw std::invalid_argument("level " + std::to_string(level) + " exceeds the stream's " +
                                std::to_string(h.levels) + " levels");
  const auto t = stream_transform(h);
  const BrickCoding coding{t.get(), h.levels, std::size_t(1) << h.block_log2, h.delta, h.reversible};
  const auto bricks = grid_bricks(s);
  check_brick_set(s, bricks);
  std::vector<VolumeGrid> grids = h.grids;
  for (std::size_t i = 0; i < grids.size(); ++i) {
    VolumeGrid& g = grids[i];
    if (level > 0) scale_placement(g, level);
    g.volume.dims = level_extent(g.volume.dims, level);
    g.volume.active.clear();
    if (h.blocked[i] == 2)
      g.opaque = s.opaque[i];  // carried verbatim, at every level
    else if (h.blocked[i] == 1)
      allocate_blocks(g, s.layouts[i], level);
    else
      g.volume.samples.assign(g.volume.count(), g.volume.background);
  }
  // Bricks are the parallel tasks; each brick's inverse transform runs serially inside its task.
  ex.run(s.bricks.size(), [&](std::size_t i) {
    const BrickChunk& b = s.bricks[i];
    const BrickBox& box = bricks[b.grid].boxes[b.brick];
    const auto values = brick_values(s, coding, b, box, level);
    const Extent at{box.offset[0] >> level, box.offset[1] >> level, box.offset[2] >> level};
    VolumeGrid& g = grids[b.grid];
    Volume& target = h.blocked[b.grid] == 1 ? g.blocks[bricks[b.grid].block[b.brick]].volume : g.volume;
    place(target, at, level_extent(box.size, level), values);  // bricks never overlap
  });
  restore_sparse(grids, s, level);
  return grids;
}

std::optional<VolumeGrid> decode_volume_into(std::span<const std::uint8_t> bytes, std::string_view name,
                                             int level, const Executor& ex, const DecodeLimits& limits,
                                             const std::function<VolumeOutput(const VolumeGrid&)>& allocate) {
  const ParsedVolumeStream s = parse_volume_stream(bytes, limits);
  const VolumeStreamHeader& h = s.header;
  if (level < 0 || level > h.levels)
    throw std::invalid_argument("level " + std::to_string(level) + " exceeds the stream's " +
                                std::to_string(h.levels) + " levels");
  std::size_t g = 0;
  while (g < h.grids.size() && !name.empty() && h.grids[g].name != name) ++g;
  if (g == h.grids.size() || (name.empty() && h.grids.size() != 1)) return std::nullopt;
  const bool sparse = h.grids[g].volume.is_sparse();
  if (h.blocked[g] != 0 || (sparse && level > 0)) return std::nullopt;  // decode_volumes' forms
  const auto t = stream_transform(h);
  const BrickCoding coding{t.get(), h.levels, std::size_t(1) << h.block_log2, h.delta, h.reversible};
  const auto bricks = grid_bricks(s);
  check_brick_set(s, bricks);
  VolumeGrid grid = h.grids[g];
  if (level > 0) scale_placement(grid, level);
  grid.volume.dims = level_extent(grid.volume.dims, level);  // volume.active: the header's sparse marker
  const VolumeOutput out = allocate(grid);
  if (out.data == nullptr || out.dims != grid.volume.dims)
    throw std::invalid_argument("decode_volume_into: the output does not match the grid's dims");
  if (sparse) fill_output(out, grid.volume.background, grid.volume.type);  // voxels of bricks not coded
  ex.run(s.bricks.size(), [&](std::size_t i) {
    const BrickChunk& b = s.bricks[i];
    if (b.grid != g) return;
    const BrickBox& box = bricks[g].boxes[b.brick];
    const auto values = brick_values(s, coding, b, box, level);
    const Extent part = level_extent(box.size, level);
    std::size_t k = 0;
    for (std::size_t z = 0; z < part[2]; ++z)
      for (std::size_t y = 0; y < part[1]; ++y)
        for (std::size_t x = 0; x < part[0]; ++x)
          out.set((box.offset[0] >> level) + x, (box.offset[1] >> level) + y, (box.offset[2] >> level) + z,
                  values[k++]);
  });
  if (sparse) restore_output_states(out, grid.volume.background, grid.volume.type, s.masks[g]);
  return grid;
}

}  // namespace pupwave
