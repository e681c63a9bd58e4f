// fuzz_volume: a volume stream decoded at every level it has. Invariants: each grid has the
// level's extent of its header dimensions; a full decode twice gives the same voxels; a sparse
// box decoded as blocks of its non-empty bricks (what .vdb output uses) has the box form's
// active mask and voxels (inactive ones compared at full resolution, where both are exact); a
// box of a dense grid decoded alone (decode_volume_box) is that crop of the whole decode.
#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "codec/error.h"
#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_format.h"
#include "fuzz_check.h"
#include "transforms/separable.h"

using namespace pupwave;

namespace {

bool same_voxels(const std::vector<VolumeGrid>& a, const std::vector<VolumeGrid>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t g = 0; g < a.size(); ++g) {
    const Volume &x = a[g].volume, &y = b[g].volume;
    if (x.dims != y.dims || x.active != y.active || x.samples.size() != y.samples.size() ||
        std::memcmp(x.samples.data(), y.samples.data(), x.samples.size() * sizeof(double)) != 0)
      return false;
  }
  return true;
}

// The blocks form of sparse box grids, made dense again, against the box form (grids with missing
// values come back dense in both).
bool same_as_box_form(const std::vector<VolumeGrid>& box, std::vector<VolumeGrid> blocks,
                      const VolumeStreamHeader& h, int level) {
  if (box.size() != blocks.size()) return false;
  for (std::size_t g = 0; g < box.size(); ++g) {
    if (h.blocked[g] != 0 || !h.grids[g].volume.is_sparse()) continue;
    const Volume& x = box[g].volume;
    if (h.has_missing(g)) {  // a dense grid with missing values: dense in both forms, bit for bit
      const Volume& y = blocks[g].volume;
      if (x.is_sparse() || y.is_sparse() || blocks[g].is_blocked() || y.dims != x.dims ||
          std::memcmp(x.samples.data(), y.samples.data(), x.count() * sizeof(double)) != 0)
        return false;
      continue;
    }
    if (!blocks[g].is_blocked()) {  // nothing but inactive background
      if (blocks[g].volume.count() != 0 || x.active_count() != 0) return false;
      continue;
    }
    make_dense_box(blocks[g], x.count());
    const Volume& y = blocks[g].volume;
    if (y.dims != x.dims || y.active != x.active) return false;
    for (std::size_t i = 0; i < x.count(); ++i)
      if ((level == 0 || x.active[i]) && std::memcmp(&x.samples[i], &y.samples[i], sizeof(double)) != 0)
        return false;
  }
  return true;
}

// The middle third of a dense grid (box form) decoded alone against that crop of the whole decode
// at the level, bit for bit. Grids whose name another grid shares cannot be named alone: skipped.
bool box_is_crop(std::span<const std::uint8_t> bytes, const std::vector<VolumeGrid>& grids,
                 const VolumeStreamHeader& h, int level) {
  for (std::size_t g = 0; g < grids.size(); ++g) {
    const VolumeGrid& whole = h.grids[g];
    if (h.blocked[g] != 0 || whole.volume.count() == 0) continue;
    std::size_t same_name = 0;
    for (const VolumeGrid& other : h.grids) same_name += other.name == whole.name;
    if (same_name != 1) continue;
    VoxelBox box;
    for (int a = 0; a < 3; ++a) {
      box.lo[a] = whole.volume.dims[a] / 3;
      box.hi[a] = std::max(box.lo[a] + 1, 2 * whole.volume.dims[a] / 3);
    }
    const VolumeGrid part =
        decode_volume_box(bytes, whole.name, box, level, serial_executor(), fuzz::kFuzzLimits);
    const Volume& x = grids[g].volume;
    const Volume& y = part.volume;
    Extent first{};
    for (int a = 0; a < 3; ++a) {
      first[a] = box.lo[a] >> level;
      if (y.dims[a] != ((box.hi[a] - 1) >> level) - first[a] + 1) return false;
    }
    for (std::size_t k = 0; k < y.dims[2]; ++k)
      for (std::size_t j = 0; j < y.dims[1]; ++j)
        for (std::size_t i = 0; i < y.dims[0]; ++i) {
          const std::size_t xi = (first[0] + i) + x.dims[0] * ((first[1] + j) + x.dims[1] * (first[2] + k));
          const std::size_t yi = i + y.dims[0] * (j + y.dims[1] * k);
          if (std::memcmp(&x.samples[xi], &y.samples[yi], sizeof(double)) != 0) return false;
          if (x.is_sparse() != y.is_sparse() || (x.is_sparse() && x.active[xi] != y.active[yi])) return false;
        }
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto bytes = fuzz::as_span(data, size);
  std::vector<VolumeGrid> full;
  try {
    full = decode_volumes(bytes, 0, serial_executor(), fuzz::kFuzzLimits);
  } catch (const DecodeError&) {
    return 0;
  }
  const VolumeStreamHeader h = parse_volume_stream(bytes, fuzz::kFuzzLimits).header;
  FUZZ_CHECK(same_voxels(full, decode_volumes(bytes, 0, serial_executor(), fuzz::kFuzzLimits)));
  for (int level = 0; level <= h.levels; ++level) {
    const auto grids = level == 0 ? full : decode_volumes(bytes, level, serial_executor(), fuzz::kFuzzLimits);
    FUZZ_CHECK(grids.size() == h.grids.size());
    for (std::size_t g = 0; g < grids.size(); ++g)
      FUZZ_CHECK(grids[g].volume.dims == level_extent(h.grids[g].volume.dims, level));
    const auto blocks =
        decode_volumes(bytes, level, serial_executor(), fuzz::kFuzzLimits, SparseBoxForm::blocks);
    FUZZ_CHECK(same_as_box_form(grids, blocks, h, level));
    FUZZ_CHECK(box_is_crop(bytes, grids, h, level));
  }
  return 0;
}
