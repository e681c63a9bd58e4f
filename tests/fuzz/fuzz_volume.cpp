// fuzz_volume: a volume stream decoded at every level it has. Invariants: each grid has the
// level's extent of its header dimensions; a full decode twice gives the same voxels.
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
  }
  return 0;
}
