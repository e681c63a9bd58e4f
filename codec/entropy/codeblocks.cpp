#include "codec/entropy/codeblocks.h"

#include <stdexcept>

namespace pupwave {

int band_resolution(const Subband& band, int levels) {
  return band.orientation == 0 ? 0 : levels - band.level + 1;
}

std::vector<CodeBlock> partition_blocks(const std::vector<Subband>& bands, int levels, std::size_t components,
                                        const Extent& block_size) {
  if (block_size[0] == 0 || block_size[1] == 0 || block_size[2] == 0)
    throw std::invalid_argument("code-block extent must be positive");
  std::vector<CodeBlock> blocks;
  for (int r = 0; r <= levels; ++r)
    for (std::size_t c = 0; c < components; ++c)
      for (std::size_t b = 0; b < bands.size(); ++b) {
        const Subband& band = bands[b];
        if (band_resolution(band, levels) != r || band.count() == 0) continue;
        for (std::size_t z = 0; z < band.size[2]; z += block_size[2])
          for (std::size_t y = 0; y < band.size[1]; y += block_size[1])
            for (std::size_t x = 0; x < band.size[0]; x += block_size[0]) {
              CodeBlock blk;
              blk.component = std::uint32_t(c);
              blk.band = std::uint32_t(b);
              blk.resolution = r;
              blk.orientation = band.orientation;
              const Extent start{x, y, z};
              for (int a = 0; a < 3; ++a) {
                blk.offset[a] = band.offset[a] + start[a];
                blk.size[a] = std::min(block_size[a], band.size[a] - start[a]);
              }
              blocks.push_back(blk);
            }
      }
  return blocks;
}

}  // namespace pupwave
