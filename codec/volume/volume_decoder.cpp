// decode_volumes: parse and validate the stream, decode every brick in parallel (stopping the
// inverse transform at the requested level), apply outlier corrections, restore the sparse
// topology and inactive values exactly.
#include <algorithm>
#include <cstring>
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

// Bricks of each grid a valid stream codes: all for dense grids, those with an active voxel
// for sparse grids (from the mask states).
std::vector<std::uint8_t> expected_bricks(const Volume& v, const MaskChunk& mask,
                                          const std::vector<BrickBox>& boxes) {
  std::vector<std::uint8_t> expected(boxes.size(), 1);
  if (!v.is_sparse()) return expected;
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    const BrickBox& box = boxes[b];
    bool any = false;
    for (std::size_t z = 0; z < box.size[2] && !any; ++z)
      for (std::size_t y = 0; y < box.size[1] && !any; ++y) {
        const std::size_t row =
            box.offset[0] + v.dims[0] * ((box.offset[1] + y) + v.dims[1] * (box.offset[2] + z));
        for (std::size_t x = 0; x < box.size[0]; ++x)
          any = any || mask.states[row + x] == std::uint8_t(VoxelState::active);
      }
    expected[b] = any ? 1 : 0;
  }
  return expected;
}

// Checks that the BRIK chunks code exactly the bricks every grid needs, once each.
void check_brick_set(const ParsedVolumeStream& s, const std::vector<std::vector<BrickBox>>& boxes) {
  std::vector<std::vector<std::uint8_t>> seen(boxes.size());
  for (std::size_t g = 0; g < boxes.size(); ++g) seen[g].assign(boxes[g].size(), 0);
  for (const BrickChunk& b : s.bricks) {
    require_stream(b.brick < boxes[b.grid].size(), "volume stream: brick index out of range");
    require_stream(seen[b.grid][b.brick] == 0, "volume stream: repeated brick");
    seen[b.grid][b.brick] = 1;
  }
  for (std::size_t g = 0; g < boxes.size(); ++g) {
    const auto want = expected_bricks(s.header.grids[g].volume, s.masks[g], boxes[g]);
    require_stream(want == seen[g], "volume stream: bricks do not match the active topology");
  }
}

// Writes a decoded brick (extent `part`) into the output volume at `offset`.
void place(Volume& out, const Extent& offset, const Extent& part, const std::vector<double>& values) {
  std::size_t k = 0;
  for (std::size_t z = 0; z < part[2]; ++z)
    for (std::size_t y = 0; y < part[1]; ++y)
      for (std::size_t x = 0; x < part[0]; ++x)
        out.samples[out.index(offset[0] + x, offset[1] + y, offset[2] + z)] = values[k++];
}

// Full-resolution sparse restore: active mask from the states, inactive values exact.
void restore_mask(Volume& out, const MaskChunk& mask) {
  out.active.assign(out.count(), 0);
  std::size_t other = 0;
  for (std::size_t i = 0; i < out.count(); ++i) {
    switch (VoxelState(mask.states[i])) {
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
std::vector<std::vector<BrickBox>> grid_bricks(const ParsedVolumeStream& s) {
  const std::size_t edge = std::size_t(1) << s.header.brick_log2;
  std::vector<std::vector<BrickBox>> boxes;
  for (const VolumeGrid& g : s.header.grids) {
    std::size_t count = 1;
    for (std::size_t d : g.volume.dims) count *= (d + edge - 1) / edge;
    require_stream(g.volume.is_sparse() || count <= s.bricks.size(),
                   "volume stream truncated (missing bricks)");
    boxes.push_back(brick_boxes(g.volume.dims, edge));
  }
  return boxes;
}

// Active masks and exact inactive values of the sparse grids (coarsened at level > 0).
void restore_sparse(std::vector<VolumeGrid>& grids, const ParsedVolumeStream& s, int level) {
  for (std::size_t g = 0; g < grids.size(); ++g) {
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
  const auto boxes = grid_bricks(s);
  check_brick_set(s, boxes);
  std::vector<VolumeGrid> grids = h.grids;
  for (VolumeGrid& g : grids) {
    if (level > 0) scale_placement(g, level);
    g.volume.dims = level_extent(g.volume.dims, level);
    g.volume.active.clear();
    g.volume.samples.assign(g.volume.count(), g.volume.background);
  }
  // Bricks are the parallel tasks; each brick's inverse transform runs serially inside its task.
  ex.run(s.bricks.size(), [&](std::size_t i) {
    const BrickChunk& b = s.bricks[i];
    const BrickBox& box = boxes[b.grid][b.brick];
    const VoxelType type = h.grids[b.grid].volume.type;
    auto values = decode_brick(coding, box.size, b.base_step, b.entries, b.codewords, level);
    if (level == 0 && h.max_error > 0.0)
      apply_outliers(values, decode_outliers(b.outliers, box.count()), h.max_error, type);
    for (double& v : values) v = to_stored(v, type);
    const Extent at{box.offset[0] >> level, box.offset[1] >> level, box.offset[2] >> level};
    place(grids[b.grid].volume, at, level_extent(box.size, level), values);  // bricks never overlap
  });
  restore_sparse(grids, s, level);
  return grids;
}

}  // namespace pupwave
