// fuzz_volume: a volume stream decoded at every level it has. Invariants: each grid has the
// level's extent of its header dimensions; a full decode twice gives the same voxels; a sparse
// box decoded as blocks of its non-empty bricks (what .vdb output uses) has the box form's
// active mask and voxels (inactive ones compared at full resolution, where both are exact).
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

// The blocks form of sparse box grids, made dense again, against the box form.
bool same_as_box_form(const std::vector<VolumeGrid>& box, std::vector<VolumeGrid> blocks,
                      const VolumeStreamHeader& h, int level) {
  if (box.size() != blocks.size()) return false;
  for (std::size_t g = 0; g < box.size(); ++g) {
    if (h.blocked[g] != 0 || !h.grids[g].volume.is_sparse()) continue;
    const Volume& x = box[g].volume;
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
  }
  return 0;
}
