// decode_volumes: parse and validate the stream, decode every brick in parallel (stopping the
// inverse transform at the requested level), apply outlier corrections, restore the sparse
// topology and inactive values exactly.
#include <algorithm>
#include <atomic>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include "codec/error.h"
#include "codec/format/chunks.h"
#include "codec/volume/volume_box_mask.h"
#include "codec/volume/volume_brick.h"
#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_format.h"
#include "codec/volume/volume_outliers.h"
#include "codec/volume/volume_tasks.h"
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

// The bricks of one grid: of its box (computed, never listed: a sparse box may have millions),
// or of each of its blocks in turn (listed; block: which one).
struct GridBricks {
  BoxBricks box;
  std::vector<BrickBox> listed;
  std::vector<std::uint32_t> block;
  bool is_listed = true;
  std::size_t count() const { return is_listed ? listed.size() : box.count(); }
  BrickBox at(std::size_t i) const { return is_listed ? listed[i] : box.box(i); }
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
    for (std::uint8_t bits : s.masks[g].bricks) expected.push_back((bits & kBrickHasActive) != 0 ? 1 : 0);
  } else {
    expected.assign(BoxBricks(v.dims, s.header.brick_log2).count(), 1);
  }
  return expected;
}

// Checks that the BRIK chunks code exactly the bricks every grid needs, once each.
void check_brick_set(const ParsedVolumeStream& s, const std::vector<GridBricks>& bricks) {
  std::vector<std::vector<std::uint8_t>> seen(bricks.size());
  for (std::size_t g = 0; g < bricks.size(); ++g) seen[g].assign(bricks[g].count(), 0);
  for (const BrickChunk& b : s.bricks) {
    require_stream(b.brick < bricks[b.grid].count(), "volume stream: brick index out of range");
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

// Exact states of `n` voxels of `out` from voxel index `at`: active mask and inactive values
// (`other` indexes `others` and advances past those used).
void restore_run(Volume& out, std::size_t at, const std::uint8_t* states, std::size_t n,
                 const std::vector<double>& others, std::size_t& other) {
  for (std::size_t i = at; i < at + n; ++i) {
    switch (VoxelState(states[i - at])) {
      case VoxelState::active: out.active[i] = 1; break;
      case VoxelState::inactive_background: out.samples[i] = out.background; break;
      case VoxelState::inactive_negative: out.samples[i] = -out.background; break;
      case VoxelState::inactive_other:
        require_stream(other < others.size(), "volume stream: missing inactive values");
        out.samples[i] = others[other++];
        break;
      default: throw DecodeError("volume stream: bad voxel state");
    }
  }
}

// Full-resolution sparse restore of a block's states (BLKS).
void restore_states(Volume& out, const std::uint8_t* states, const MaskChunk& mask, std::size_t& other) {
  out.active.assign(out.count(), 0);
  restore_run(out, 0, states, out.count(), mask.other_values, other);
}

// Full-resolution sparse restore of a box, its states streamed from the MASK frame.
void restore_mask(Volume& out, const BoxMask& mask) {
  out.active.assign(out.count(), 0);
  std::size_t other = 0, first = 0;
  const std::uint8_t* states = nullptr;
  MaskRows rows(mask.frame, out.dims);
  while (const std::size_t n = rows.next(first, states))
    restore_run(out, first * out.dims[0], states, n * out.dims[0], mask.other_values, other);
  require_stream(other == mask.other_values.size(), "volume stream: extra inactive values");
}

// Value of an inactive voxel of state `s` (advancing `other` past an inactive_other one); 0 for
// an active voxel.
double inactive_value(std::uint8_t s, double background, const std::vector<double>& others,
                      std::size_t& other) {
  switch (VoxelState(s)) {
    case VoxelState::active: return 0.0;
    case VoxelState::inactive_background: return background;
    case VoxelState::inactive_negative: return -background;
    case VoxelState::inactive_other:
      require_stream(other < others.size(), "volume stream: missing inactive values");
      return others[other++];
    default: throw DecodeError("volume stream: bad voxel state");
  }
}

// Reduced-resolution restore of a box (`fine` its full-resolution dims), streamed: a coarse voxel
// is active when any of its children is; an inactive one takes the mean of its children's exact
// values (summed in voxel order, as the full-resolution restore would).
void restore_coarse_box(Volume& out, const Extent& fine, const BoxMask& mask, int level) {
  out.active.assign(out.count(), 0);
  std::vector<double> sum(out.count(), 0.0);
  std::vector<std::uint32_t> n(out.count(), 0);
  std::size_t other = 0, first = 0;
  const std::uint8_t* states = nullptr;
  MaskRows rows(mask.frame, fine);
  while (const std::size_t count = rows.next(first, states))
    for (std::size_t r = 0; r < count; ++r) {
      const std::size_t y = (first + r) % fine[1], z = (first + r) / fine[1];
      const std::uint8_t* row = states + r * fine[0];
      for (std::size_t x = 0; x < fine[0]; ++x) {
        const std::size_t c = out.index(x >> level, y >> level, z >> level);
        if (row[x] == std::uint8_t(VoxelState::active)) out.active[c] = 1;
        sum[c] += inactive_value(row[x], out.background, mask.other_values, other);
        ++n[c];
      }
    }
  for (std::size_t c = 0; c < out.count(); ++c)
    if (!out.active[c]) out.samples[c] = sum[c] / double(n[c]);
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
          bricks[g].listed.push_back(box);
          bricks[g].block.push_back(k);
        }
      continue;
    }
    bricks[g].box = BoxBricks(v.dims, s.header.brick_log2);
    bricks[g].is_listed = false;
    require_stream(v.is_sparse() || bricks[g].count() <= s.bricks.size(),
                   "volume stream truncated (missing bricks)");
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
// Origin of block `b` of grid `g` at 1/2^level resolution.
std::array<std::int64_t, 3> level_origin(const VolumeGrid& g, const VolumeBlock& b, int level) {
  const std::int64_t f = std::int64_t(1) << level;
  std::array<std::int64_t, 3> origin{};
  for (std::size_t a = 0; a < 3; ++a) {
    if (b.origin[a] % f != 0)
      throw std::invalid_argument("level " + std::to_string(level) + " of grid '" + g.name +
                                  "': a block does not start on a multiple of 2^level (sparse grids decode "
                                  "at levels up to 3)");
    origin[a] = b.origin[a] / f;
  }
  return origin;
}

// Block `b` of grid `g` at 1/2^level resolution, filled with background.
VolumeBlock level_block(const VolumeGrid& g, const VolumeBlock& b, int level) {
  VolumeBlock out;
  out.origin = level_origin(g, b, level);
  out.volume = Volume(level_extent(b.volume.dims, level), g.volume.type);
  out.volume.background = g.volume.background;
  std::fill(out.volume.samples.begin(), out.volume.samples.end(), g.volume.background);
  return out;
}

// Tile `t` at 1/2^level resolution (origin floor-divided, edge rounded up).
VolumeTile level_tile(VolumeTile t, int level) {
  const std::int64_t f = std::int64_t(1) << level;
  for (std::int64_t& o : t.origin) o = coarse(o, level);
  t.edge = std::uint32_t((std::int64_t(t.edge) + f - 1) / f);
  return t;
}

void allocate_blocks(VolumeGrid& g, const BlocksChunk& layout, int level) {
  for (const VolumeBlock& b : layout.blocks) g.blocks.push_back(level_block(g, b, level));
  for (const VolumeTile& t : layout.tiles) g.tiles.push_back(level_tile(t, level));
}

// Active masks and exact inactive values of each block (coarsened at level > 0).
// Active mask and exact inactive values of one block (`out`, at `level`) from its full-resolution
// states (`fine_dims` voxels; `other` indexes the layout's inactive_other values).
void restore_block(Volume& out, const Extent& fine_dims, const std::uint8_t* states, const MaskChunk& mask,
                   int level, std::size_t& other) {
  if (level == 0) return restore_states(out, states, mask, other);
  Volume fine(fine_dims, out.type);
  fine.background = out.background;
  restore_states(fine, states, mask, other);
  restore_coarse_mask(out, fine, level);
}

void restore_blocks(VolumeGrid& g, const BlocksChunk& layout, int level) {
  std::size_t at = 0, other = 0;
  for (std::size_t k = 0; k < layout.blocks.size(); ++k) {
    restore_block(g.blocks[k].volume, layout.blocks[k].volume.dims, layout.mask.states.data() + at,
                  layout.mask, level, other);
    at += layout.blocks[k].volume.count();
  }
  require_stream(other == layout.mask.other_values.size(), "volume stream: extra inactive values");
}

// Active masks and exact inactive values of the sparse grids (coarsened at level > 0); sparse
// boxes turned into blocks get theirs in box_to_blocks.
void restore_sparse(std::vector<VolumeGrid>& grids, const ParsedVolumeStream& s, int level, bool to_blocks) {
  for (std::size_t g = 0; g < grids.size(); ++g) {
    if (s.header.blocked[g] == 1) restore_blocks(grids[g], s.layouts[g], level);
    if (!s.header.grids[g].volume.is_sparse() || (to_blocks && !s.header.has_missing(g))) continue;
    if (level == 0)
      restore_mask(grids[g].volume, s.masks[g]);
    else
      restore_coarse_box(grids[g].volume, s.header.grids[g].volume.dims, s.masks[g], level);
  }
}

// Children of coarse voxel c (level-`level` index within a brick of fine extent `size`).
double children(const Extent& size, const Extent& c, int level) {
  double n = 1.0;
  for (std::size_t a = 0; a < 3; ++a)
    n *= double(std::min(std::size_t(1) << level, size[a] - (c[a] << level)));
  return n;
}

// One row of a sparse box's states into the blocks of its bricks (box_to_blocks): active mask,
// exact inactive values at level 0, sums of the children's inactive values above.
void scatter_row(std::vector<VolumeBlock>& blocks, std::size_t k, const BoxMask& mask,
                 const BoxBricks& geometry, const std::uint8_t* row, std::size_t y, std::size_t z, int level,
                 std::size_t& other) {
  const std::size_t base = geometry.at(0, y, z), edge = std::size_t(1) << geometry.log2;
  for (std::size_t bx = 0; bx < geometry.n[0]; ++bx) {
    if (mask.bricks[base + bx] == 0) continue;
    Volume& v = blocks[k++].volume;
    const std::size_t x0 = bx * edge, x1 = std::min(x0 + edge, geometry.dims[0]);
    const std::size_t at = v.index(0, (y & (edge - 1)) >> level, (z & (edge - 1)) >> level);
    for (std::size_t x = x0; x < x1; ++x) {
      const std::size_t c = at + ((x - x0) >> level);
      if (row[x] == std::uint8_t(VoxelState::active)) v.active[c] = 1;
      const double value = inactive_value(row[x], v.background, mask.other_values, other);
      if (level == 0)
        v.samples[c] = value;
      else
        v.samples[c] += value;
    }
  }
}

// A sparse box grid in the sparse-native form (SparseBoxForm::blocks): one block per brick whose
// states are not all inactive background, at 1/2^level, placed from the grid's (scaled) origin,
// with its active mask and inactive values (coarse ones: the mean of their children). Nothing is
// allocated for empty bricks, and the states are streamed only up to the last non-empty brick.
// `content` receives the indices of those bricks (block k holds brick content[k]).
void box_to_blocks(VolumeGrid& g, const BoxMask& mask, const BoxBricks& geometry, int level,
                   std::vector<std::uint32_t>& content) {
  for (std::size_t i = 0; i < mask.bricks.size(); ++i) {
    if (mask.bricks[i] == 0) continue;
    const BrickBox box = geometry.box(i);
    VolumeBlock b;
    for (std::size_t a = 0; a < 3; ++a) b.origin[a] = g.origin[a] + std::int64_t(box.offset[a] >> level);
    b.volume = Volume(level_extent(box.size, level), g.volume.type);  // zero: sums at level > 0
    b.volume.background = g.volume.background;
    b.volume.active.assign(b.volume.count(), 0);
    g.blocks.push_back(std::move(b));
    content.push_back(std::uint32_t(i));
  }
  std::size_t other = 0, first = 0;
  const std::uint8_t* states = nullptr;
  MaskRows rows(mask.frame, geometry.dims);
  for (std::size_t n = 0; first + n < mask.last_row && (n = rows.next(first, states)) > 0;)
    for (std::size_t r = 0; r < n && first + r < mask.last_row; ++r) {
      const std::size_t y = (first + r) % geometry.dims[1], z = (first + r) / geometry.dims[1];
      const auto k = std::lower_bound(content.begin(), content.end(), geometry.at(0, y, z)) - content.begin();
      scatter_row(g.blocks, std::size_t(k), mask, geometry, states + r * geometry.dims[0], y, z, level,
                  other);
    }
  for (std::size_t k = 0; level > 0 && k < content.size(); ++k) {
    Volume& v = g.blocks[k].volume;
    const Extent size = geometry.box(content[k]).size;
    for (std::size_t z = 0; z < v.dims[2]; ++z)
      for (std::size_t y = 0; y < v.dims[1]; ++y)
        for (std::size_t x = 0; x < v.dims[0]; ++x)
          if (!v.active[v.index(x, y, z)]) v.samples[v.index(x, y, z)] /= children(size, {x, y, z}, level);
  }
  g.volume.samples.clear();
  if (g.blocks.empty()) g.volume.dims = {0, 0, 0};  // nothing but background: an empty grid
}

// Writes the active voxels of a decoded brick (extent `part`) into a block of its own extent.
void place_active(Volume& out, const Extent& part, const std::vector<double>& values) {
  for (std::size_t i = 0; i < part[0] * part[1] * part[2]; ++i)
    if (out.active[i]) out.samples[i] = values[i];
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

// restore_mask for a typed output: inactive voxels get their exact values, `out.active` (if set)
// the mask. Every voxel is active (in a coded brick) or set here, so nothing is filled before.
void restore_output_states(const VolumeOutput& out, double background, VoxelType type, const BoxMask& mask) {
  std::size_t other = 0, first = 0;
  const std::uint8_t* states = nullptr;
  MaskRows rows(mask.frame, out.dims);
  while (const std::size_t n = rows.next(first, states))
    for (std::size_t r = 0; r < n; ++r) {
      const std::size_t y = (first + r) % out.dims[1], z = (first + r) / out.dims[1];
      for (std::size_t x = 0; x < out.dims[0]; ++x) {
        const std::uint8_t s = states[r * out.dims[0] + x];
        if (out.active != nullptr) out.active[(first + r) * out.dims[0] + x] = s == 1 ? 1 : 0;
        if (s != std::uint8_t(VoxelState::active))
          out.set(x, y, z, to_stored(inactive_value(s, background, mask.other_values, other), type));
      }
    }
  require_stream(other == mask.other_values.size(), "volume stream: extra inactive values");
}

// Per-thread buffers of decode_volume_into, reused from brick to brick.
struct IntoScratch {
  std::vector<std::int32_t> exact;  // reversible reconstruction
  std::vector<float> approximate;   // irreversible reconstruction
  std::vector<double> row;
  // Drops buffers larger than a 64^3 brick needs (a 256^3 brick's would stay with the thread).
  void trim() {
    constexpr std::size_t kKeptVoxels = std::size_t(1) << 18;
    if (exact.capacity() > kKeptVoxels || approximate.capacity() > kKeptVoxels) *this = IntoScratch{};
  }
};

// Level voxels [first, first + dims) of a grid: what a VolumeOutput holds (its voxel 0 is first).
struct LevelBox {
  Extent first{0, 0, 0};
  Extent dims{0, 0, 0};
};

// The level-`level` voxels whose full-resolution footprint meets `box`.
LevelBox level_box(const VoxelBox& box, int level) {
  LevelBox out;
  for (std::size_t a = 0; a < 3; ++a) {
    out.first[a] = box.lo[a] >> level;
    out.dims[a] = ((box.hi[a] - 1) >> level) + 1 - out.first[a];
  }
  return out;
}

// Stores row (y, z) of a brick (level offset `at`; n values from x = at[0]) into `out`, which
// holds the voxels of `window`; the part outside the window is dropped.
void set_window_row(const VolumeOutput& out, const LevelBox& window, const Extent& at, std::size_t y,
                    std::size_t z, const double* row, std::size_t n) {
  const std::size_t gy = at[1] + y, gz = at[2] + z;
  if (gy < window.first[1] || gy >= window.first[1] + window.dims[1] || gz < window.first[2] ||
      gz >= window.first[2] + window.dims[2])
    return;
  const std::size_t x0 = std::max(at[0], window.first[0]);
  const std::size_t x1 = std::min(at[0] + n, window.first[0] + window.dims[0]);
  if (x0 < x1)
    out.set_row(x0 - window.first[0], gy - window.first[1], gz - window.first[2], row + (x0 - at[0]),
                x1 - x0);
}

// Writes a brick decoded at full resolution (`values`, the decoder's own element type, x fastest)
// into `out` (holding `window`) row by row: each value widened, its outlier correction applied
// (`outliers` in index order), rounded to the stored type; as brick_values computes it, without a
// double brick.
template <class T>
void write_full_brick(const VolumeOutput& out, const LevelBox& window, const BrickBox& box,
                      const std::vector<T>& values, std::span<const Outlier> outliers, double bound,
                      VoxelType type, std::vector<double>& row) {
  row.resize(box.size[0]);
  std::size_t k = 0, next = 0;
  for (std::size_t z = 0; z < box.size[2]; ++z)
    for (std::size_t y = 0; y < box.size[1]; ++y) {
      for (std::size_t x = 0; x < box.size[0]; ++x, ++k) {
        double v = double(values[k]);
        if (next < outliers.size() && outliers[next].index == k)
          v = to_stored(v + double(outliers[next++].k) * bound, type);
        row[x] = to_stored(v, type);
      }
      set_window_row(out, window, box.offset, y, z, row.data(), box.size[0]);
    }
}

// One brick at full resolution into `out` (holding `window`), through per-thread buffers.
void decode_full_brick(const ParsedVolumeStream& s, const BrickCoding& coding, const BrickChunk& b,
                       const BrickBox& box, const VolumeOutput& out, const LevelBox& window) {
  thread_local IntoScratch scratch;
  const VoxelType type = s.header.grids[b.grid].volume.type;
  const double bound = s.header.max_error;
  const std::vector<Outlier> outliers =
      bound > 0.0 ? decode_outliers(b.outliers, box.count()) : std::vector<Outlier>{};
  if (coding.reversible) {
    decode_brick_into(coding, box.size, b.base_step, b.entries, b.codewords, scratch.exact);
    write_full_brick(out, window, box, scratch.exact, outliers, bound, type, scratch.row);
  } else {
    decode_brick_into(coding, box.size, b.base_step, b.entries, b.codewords, scratch.approximate);
    write_full_brick(out, window, box, scratch.approximate, outliers, bound, type, scratch.row);
  }
  scratch.trim();
}

// One brick at `level` into `out` (holding `window`): at full resolution without a double brick.
void decode_brick_window(const ParsedVolumeStream& s, const BrickCoding& coding, const BrickChunk& b,
                         const BrickBox& box, int level, const VolumeOutput& out, const LevelBox& window) {
  if (level == 0) return decode_full_brick(s, coding, b, box, out, window);
  const auto values = brick_values(s, coding, b, box, level);
  const Extent at{box.offset[0] >> level, box.offset[1] >> level, box.offset[2] >> level};
  const Extent part = level_extent(box.size, level);
  for (std::size_t z = 0, k = 0; z < part[2]; ++z)
    for (std::size_t y = 0; y < part[1]; ++y, k += part[0])
      set_window_row(out, window, at, y, z, values.data() + k, part[0]);
}

// Counts the bricks of each z-slab of a dense output still to write, and reports a slab to
// VolumeOutput::done_slabs once its last brick is written (bricks finish in any order).
class OutputSlabs {
 public:
  OutputSlabs(const VolumeOutput& out, const BoxBricks& bricks) : out_(out), log2_(bricks.log2) {
    if (out.done_slabs == nullptr) return;
    left_ = std::make_unique<std::atomic<std::size_t>[]>(bricks.n[2]);
    for (std::size_t z = 0; z < bricks.n[2]; ++z)
      left_[z].store(bricks.n[0] * bricks.n[1], std::memory_order_relaxed);
  }
  void done(const BrickBox& box) {
    if (!left_) return;
    const std::size_t z = box.offset[2] >> log2_;
    // acq_rel: the last brick of a slab sees every other brick's writes finished before it reports.
    if (left_[z].fetch_sub(1, std::memory_order_acq_rel) == 1)
      out_.done_slabs(out_.done_context, out_, box.offset[2], box.offset[2] + box.size[2]);
  }

 private:
  VolumeOutput out_;
  int log2_;
  std::unique_ptr<std::atomic<std::size_t>[]> left_;  // per slab; null: nothing to report
};

// Throws std::invalid_argument unless `box` is non-empty and inside the grid.
void check_box(const VoxelBox& box, const VolumeGrid& grid) {
  const Extent& d = grid.volume.dims;
  for (std::size_t a = 0; a < 3; ++a)
    if (box.lo[a] >= box.hi[a] || box.hi[a] > d[a])
      throw std::invalid_argument("box " + to_string(box) + " is empty, inverted or outside grid '" +
                                  grid.name + "' of dims " + std::to_string(d[0]) + "x" +
                                  std::to_string(d[1]) + "x" + std::to_string(d[2]));
}

// The grid decode_volume_box decodes: the one named, or the only one.
std::size_t box_grid(const VolumeStreamHeader& h, std::string_view name) {
  if (name.empty()) {
    if (h.grids.size() != 1)
      throw std::invalid_argument("the stream holds " + std::to_string(h.grids.size()) +
                                  " grids; name the one to decode a box of");
    return 0;
  }
  for (std::size_t g = 0; g < h.grids.size(); ++g)
    if (h.grids[g].name == name) return g;
  throw std::invalid_argument("the stream has no grid named '" + std::string(name) + "'");
}

// Whether a brick decoded at a level (level offset `at`, extent `part`) meets `crop`.
bool meets(const LevelBox& crop, const Extent& at, const Extent& part) {
  for (std::size_t a = 0; a < 3; ++a)
    if (at[a] >= crop.first[a] + crop.dims[a] || at[a] + part[a] <= crop.first[a]) return false;
  return true;
}

// The sparse restore of decode_volumes (restore_mask at level 0, restore_coarse_box above) for
// the voxels of `crop` only, into `out` (holding `crop`; its `active`, if set, gets the mask):
// the states are streamed up to the last row of the crop's footprint, and inactive_other values
// before it are skipped to find those inside. Sums run in voxel order over the same children as
// the whole restore, so the means are the same bits.
void restore_box_crop(const VolumeOutput& out, double background, const Extent& fine, const BoxMask& mask,
                      int level, const LevelBox& crop) {
  Extent lo, hi;  // full-resolution footprint of the crop
  for (std::size_t a = 0; a < 3; ++a) {
    lo[a] = crop.first[a] << level;
    hi[a] = std::min((crop.first[a] + crop.dims[a]) << level, fine[a]);
  }
  const Extent& d = crop.dims;
  std::vector<std::uint8_t> active(d[0] * d[1] * d[2], 0);
  std::vector<double> sum(level > 0 ? active.size() : 0, 0.0);
  std::vector<std::uint32_t> n(sum.size(), 0);
  const std::size_t end_row = (hi[1] - 1) + fine[1] * (hi[2] - 1) + 1;
  std::size_t other = 0, first = 0;
  const std::uint8_t* states = nullptr;
  MaskRows rows(mask.frame, fine);
  for (std::size_t count = 0; (count = rows.next(first, states)) > 0 && first < end_row;)
    for (std::size_t r = 0; r < count; ++r) {
      const std::size_t y = (first + r) % fine[1], z = (first + r) / fine[1];
      const std::uint8_t* row = states + r * fine[0];
      const bool inside = y >= lo[1] && y < hi[1] && z >= lo[2] && z < hi[2];
      for (std::size_t x = 0; x < fine[0]; ++x) {
        if (!inside || x < lo[0] || x >= hi[0]) {
          other += row[x] == std::uint8_t(VoxelState::inactive_other) ? 1 : 0;
          continue;
        }
        const Extent c{(x >> level) - crop.first[0], (y >> level) - crop.first[1],
                       (z >> level) - crop.first[2]};
        const std::size_t i = c[0] + d[0] * (c[1] + d[1] * c[2]);
        const bool is_active = row[x] == std::uint8_t(VoxelState::active);
        const double value = inactive_value(row[x], background, mask.other_values, other);
        if (is_active) active[i] = 1;
        if (level > 0) {
          sum[i] += value;
          ++n[i];
        } else if (!is_active) {
          out.set(c[0], c[1], c[2], value);
        }
      }
    }
  for (std::size_t i = 0; i < sum.size(); ++i)
    if (!active[i]) out.set(i % d[0], (i / d[0]) % d[1], i / (d[0] * d[1]), sum[i] / double(n[i]));
  if (out.active != nullptr) std::copy(active.begin(), active.end(), out.active);
}

// The level index-space box [lo, hi) of a grid described for decode_volume_box_into.
struct IndexBox {
  std::array<std::int64_t, 3> lo{}, hi{};
  bool meets(const std::array<std::int64_t, 3>& at, const Extent& size) const {
    for (std::size_t a = 0; a < 3; ++a)
      if (at[a] >= hi[a] || at[a] + std::int64_t(size[a]) <= lo[a]) return false;
    return true;
  }
};

// A sparse-native grid's part of decode_volume_box: `grid` arrives described (placement at the
// level, the crop's dims) and leaves as the crop of its dense bounding box, what decode_volumes
// and make_dense_box give, from the blocks meeting the crop and only their bricks meeting it
// (the inactive_other values of the blocks before each are skipped to find its own).
void decode_blocked_box(VolumeGrid& grid, const ParsedVolumeStream& s, std::size_t g,
                        const BrickCoding& coding, const GridBricks& bricks, int level, const Executor& ex) {
  const BlocksChunk& layout = s.layouts[g];
  IndexBox region;
  for (std::size_t a = 0; a < 3; ++a) {
    region.lo[a] = grid.origin[a];
    region.hi[a] = grid.origin[a] + std::int64_t(grid.volume.dims[a]);
  }
  std::vector<std::ptrdiff_t> slot(layout.blocks.size(), -1);  // block k's place in grid.blocks
  for (std::size_t k = 0; k < layout.blocks.size(); ++k)
    if (region.meets(level_origin(grid, layout.blocks[k], level),
                     level_extent(layout.blocks[k].volume.dims, level))) {
      slot[k] = std::ptrdiff_t(grid.blocks.size());
      grid.blocks.push_back(level_block(grid, layout.blocks[k], level));
    }
  for (const VolumeTile& t : layout.tiles) grid.tiles.push_back(level_tile(t, level));
  const auto block_of = [&](const BrickChunk& b) -> VolumeBlock* {
    const std::ptrdiff_t k = slot[bricks.block[b.brick]];
    return k < 0 ? nullptr : &grid.blocks[std::size_t(k)];
  };
  std::vector<std::size_t> touched;  // BRIK chunks of those blocks' bricks that meet the crop
  for (std::size_t i = 0; i < s.bricks.size(); ++i) {
    const VolumeBlock* block = s.bricks[i].grid == g ? block_of(s.bricks[i]) : nullptr;
    if (block == nullptr) continue;
    const BrickBox box = bricks.at(s.bricks[i].brick);
    std::array<std::int64_t, 3> at{};
    for (std::size_t a = 0; a < 3; ++a) at[a] = block->origin[a] + std::int64_t(box.offset[a] >> level);
    if (region.meets(at, level_extent(box.size, level))) touched.push_back(i);
  }
  ex.run(touched.size(), [&](std::size_t k) {
    const BrickChunk& b = s.bricks[touched[k]];
    const BrickBox box = bricks.at(b.brick);
    place(block_of(b)->volume, {box.offset[0] >> level, box.offset[1] >> level, box.offset[2] >> level},
          level_extent(box.size, level), brick_values(s, coding, b, box, level));
  });
  std::size_t at = 0, other = 0;
  for (std::size_t k = 0; k < layout.blocks.size(); ++k) {
    const std::uint8_t* states = layout.mask.states.data() + at;
    const std::size_t n = layout.blocks[k].volume.count();
    if (slot[k] >= 0)
      restore_block(grid.blocks[std::size_t(slot[k])].volume, layout.blocks[k].volume.dims, states,
                    layout.mask, level, other);
    else
      other += std::size_t(std::count(states, states + n, std::uint8_t(VoxelState::inactive_other)));
    at += n;
  }
  if (grid.is_blocked()) return make_dense_box(grid, std::numeric_limits<std::size_t>::max());
  grid.volume = Volume(grid.volume.dims, grid.volume.type);  // nothing but background in the crop
  grid.volume.background = s.header.grids[g].volume.background;
  std::fill(grid.volume.samples.begin(), grid.volume.samples.end(), grid.volume.background);
  grid.volume.active.assign(grid.volume.count(), 0);
}

// decode_blocked_box into the caller's output: `grid` (described) is returned as a sparse box.
VolumeGrid blocked_box_into(VolumeGrid grid, const ParsedVolumeStream& s, std::size_t g,
                            const BrickCoding& coding, const GridBricks& bricks, int level,
                            const Executor& ex,
                            const std::function<VolumeOutput(const VolumeGrid&)>& allocate) {
  VolumeGrid dense = grid;
  decode_blocked_box(dense, s, g, coding, bricks, level, ex);
  grid.volume.active.assign(1, 1);  // the marker of a sparse box
  const VolumeOutput out = allocate(grid);
  if (out.data == nullptr || out.dims != grid.volume.dims)
    throw std::invalid_argument("decode_volume_box_into: the output does not match the box's dims");
  const Volume& v = dense.volume;
  for (std::size_t z = 0; z < v.dims[2]; ++z)
    for (std::size_t y = 0; y < v.dims[1]; ++y) out.set_row(0, y, z, &v.samples[v.index(0, y, z)], v.dims[0]);
  if (out.active != nullptr) std::copy(v.active.begin(), v.active.end(), out.active);
  return grid;
}

}  // namespace

bool is_volume_stream(std::span<const std::uint8_t> bytes) { return has_signature(bytes, kVolumeSignature); }

std::vector<VolumeGrid> decode_volumes(std::span<const std::uint8_t> bytes, int level, const Executor& ex) {
  return decode_volumes(bytes, level, ex, DecodeLimits{});
}

std::vector<VolumeGrid> decode_volumes(std::span<const std::uint8_t> bytes, int level, const Executor& ex,
                                       const DecodeLimits& limits) {
  return decode_volumes(bytes, level, ex, limits, SparseBoxForm::box);
}

std::vector<VolumeGrid> decode_volumes(std::span<const std::uint8_t> bytes, int level, const Executor& ex,
                                       const DecodeLimits& limits, SparseBoxForm form) {
  const bool to_blocks = form == SparseBoxForm::blocks;
  const ParsedVolumeStream s =
      parse_volume_stream(bytes, limits, to_blocks ? SparseBoxCount::content : SparseBoxCount::box);
  const VolumeStreamHeader& h = s.header;
  if (level < 0 || level > h.levels)
    throw std::invalid_argument("level " + std::to_string(level) + " exceeds the stream's " +
                                std::to_string(h.levels) + " levels");
  const auto t = stream_transform(h);
  const BrickCoding coding{t.get(), h.levels,     std::size_t(1) << h.block_log2,
                           h.delta, h.reversible, h.coder == 1};
  const auto bricks = grid_bricks(s);
  check_brick_set(s, bricks);
  std::vector<VolumeGrid> grids = h.grids;
  std::vector<std::vector<std::uint32_t>> content(grids.size());  // box_to_blocks: brick of each block
  for (std::size_t i = 0; i < grids.size(); ++i) {
    VolumeGrid& g = grids[i];
    if (level > 0) scale_placement(g, level);
    g.volume.dims = level_extent(g.volume.dims, level);
    g.volume.active.clear();
    if (h.blocked[i] == 2)
      g.opaque = s.opaque[i];  // carried verbatim, at every level
    else if (h.blocked[i] == 1)
      allocate_blocks(g, s.layouts[i], level);
    else if (to_blocks && h.grids[i].volume.is_sparse() && !h.has_missing(i))
      box_to_blocks(g, s.masks[i], bricks[i].box, level, content[i]);
    else
      g.volume.samples.assign(g.volume.count(), g.volume.background);
  }
  // Bricks are the parallel tasks; each brick's inverse transform runs serially inside its task.
  ex.run(s.bricks.size(), [&](std::size_t i) {
    const BrickChunk& b = s.bricks[i];
    const BrickBox box = bricks[b.grid].at(b.brick);
    const auto values = brick_values(s, coding, b, box, level);
    const Extent at{box.offset[0] >> level, box.offset[1] >> level, box.offset[2] >> level};
    VolumeGrid& g = grids[b.grid];
    const Extent part = level_extent(box.size, level);
    if (!content[b.grid].empty()) {  // a sparse box as blocks: its active voxels (restored already)
      const auto& c = content[b.grid];
      place_active(g.blocks[std::size_t(std::lower_bound(c.begin(), c.end(), b.brick) - c.begin())].volume,
                   part, values);
      return;
    }
    Volume& target = h.blocked[b.grid] == 1 ? g.blocks[bricks[b.grid].block[b.brick]].volume : g.volume;
    place(target, at, part, values);  // bricks never overlap
  });
  restore_sparse(grids, s, level, to_blocks);
  for (std::size_t i = 0; i < grids.size(); ++i)
    if (h.has_missing(i)) grids[i].volume.active.clear();  // dense, its missing voxels restored exactly
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
  const BrickCoding coding{t.get(), h.levels,     std::size_t(1) << h.block_log2,
                           h.delta, h.reversible, h.coder == 1};
  const auto bricks = grid_bricks(s);
  check_brick_set(s, bricks);
  VolumeGrid grid = h.grids[g];
  if (level > 0) scale_placement(grid, level);
  grid.volume.dims = level_extent(grid.volume.dims, level);  // volume.active: the header's sparse marker
  if (h.has_missing(g)) grid.volume.active.clear();          // returned dense
  const VolumeOutput out = allocate(grid);
  if (out.data == nullptr || out.dims != grid.volume.dims)
    throw std::invalid_argument("decode_volume_into: the output does not match the grid's dims");
  // Slabs are reported only for a dense grid at full resolution, every brick of which is coded.
  const bool report = !sparse && level == 0;
  OutputSlabs slabs(report ? out : VolumeOutput{}, bricks[g].box);
  const LevelBox whole{{0, 0, 0}, grid.volume.dims};
  run_in_index_order(ex, s.bricks.size(), [&](std::size_t i) {
    const BrickChunk& b = s.bricks[i];
    if (b.grid != g) return;
    const BrickBox box = bricks[g].at(b.brick);
    decode_brick_window(s, coding, b, box, level, out, whole);
    if (level == 0) slabs.done(box);
  });
  if (sparse) restore_output_states(out, grid.volume.background, grid.volume.type, s.masks[g]);
  return grid;
}

std::string to_string(const VoxelBox& box) {
  std::string out;
  for (std::size_t a = 0; a < 3; ++a)
    out += (a ? " x [" : "[") + std::to_string(box.lo[a]) + "," + std::to_string(box.hi[a]) + ")";
  return out;
}

VolumeGrid decode_volume_box_into(std::span<const std::uint8_t> bytes, std::string_view name,
                                  const VoxelBox& box, int level, const Executor& ex,
                                  const DecodeLimits& limits,
                                  const std::function<VolumeOutput(const VolumeGrid&)>& allocate) {
  // The limit is the box's (checked below); the whole stream is only bounded by the format's caps.
  const ParsedVolumeStream s =
      parse_volume_stream(bytes, DecodeLimits{std::numeric_limits<std::size_t>::max()});
  const VolumeStreamHeader& h = s.header;
  if (level < 0 || level > h.levels)
    throw std::invalid_argument("level " + std::to_string(level) + " exceeds the stream's " +
                                std::to_string(h.levels) + " levels");
  const std::size_t g = box_grid(h, name);
  if (h.blocked[g] == 2)
    throw std::invalid_argument("grid '" + h.grids[g].name +
                                "' is carried as OpenVDB bytes only: it has no voxels to decode a box of");
  const Volume& whole = h.grids[g].volume;
  check_box(box, h.grids[g]);
  check_decode_limit((box.hi[0] - box.lo[0]) * (box.hi[1] - box.lo[1]) * (box.hi[2] - box.lo[2]), limits,
                     "volume box: voxels");
  const auto t = stream_transform(h);
  const BrickCoding coding{t.get(), h.levels,     std::size_t(1) << h.block_log2,
                           h.delta, h.reversible, h.coder == 1};
  const auto bricks = grid_bricks(s);
  check_brick_set(s, bricks);
  const LevelBox crop = level_box(box, level);
  VolumeGrid grid = h.grids[g];
  if (level > 0) scale_placement(grid, level);
  for (std::size_t a = 0; a < 3; ++a) grid.origin[a] += std::int64_t(crop.first[a]);
  grid.volume.dims = crop.dims;                      // volume.active: the header's sparse marker
  if (h.has_missing(g)) grid.volume.active.clear();  // returned dense
  if (h.blocked[g] == 1) return blocked_box_into(grid, s, g, coding, bricks[g], level, ex, allocate);
  const VolumeOutput out = allocate(grid);
  if (out.data == nullptr || out.dims != grid.volume.dims)
    throw std::invalid_argument("decode_volume_box_into: the output does not match the box's dims");
  std::vector<std::size_t> touched;  // BRIK chunks of the grid's bricks that meet the box
  for (std::size_t i = 0; i < s.bricks.size(); ++i) {
    if (s.bricks[i].grid != g) continue;
    const BrickBox b = bricks[g].at(s.bricks[i].brick);
    const Extent at{b.offset[0] >> level, b.offset[1] >> level, b.offset[2] >> level};
    if (meets(crop, at, level_extent(b.size, level))) touched.push_back(i);
  }
  ex.run(touched.size(), [&](std::size_t k) {
    const BrickChunk& b = s.bricks[touched[k]];
    decode_brick_window(s, coding, b, bricks[g].at(b.brick), level, out, crop);
  });
  if (whole.is_sparse()) restore_box_crop(out, whole.background, whole.dims, s.masks[g], level, crop);
  return grid;
}

VolumeGrid decode_volume_box(std::span<const std::uint8_t> bytes, std::string_view name, const VoxelBox& box,
                             int level, const Executor& ex, const DecodeLimits& limits) {
  Volume volume;
  VolumeGrid grid = decode_volume_box_into(bytes, name, box, level, ex, limits, [&](const VolumeGrid& g) {
    volume = Volume(g.volume.dims, g.volume.type);
    volume.background = g.volume.background;
    VolumeOutput out = contiguous_output(volume.samples.data(), volume.dims, VoxelType::f64);
    if (g.volume.is_sparse()) {
      volume.active.assign(volume.count(), 0);
      out.active = volume.active.data();
    }
    return out;
  });
  grid.volume = std::move(volume);
  return grid;
}

}  // namespace pupwave
