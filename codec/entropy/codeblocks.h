#pragma once
// Partition of a Mallat decomposition into code-blocks, ordered by resolution so that a
// reduced-resolution decode reads a prefix of the data. Works for 2-D and 3-D extents.

#include <cstdint>
#include <vector>

#include "transforms/subband.h"

namespace pupwave {

// One code-block: a box inside one subband of one component.
struct CodeBlock {
  std::uint32_t component = 0;
  std::uint32_t band = 0;  // index into subbands(dims, levels)
  int resolution = 0;      // 0: coarse band; r: details of level (levels - r + 1)
  unsigned orientation = 0;
  Extent offset{0, 0, 0};  // first sample in the component's in-place array
  Extent size{1, 1, 1};
  std::size_t count() const { return size[0] * size[1] * size[2]; }
};

// Resolution of a subband: 0 for the coarse band, levels - level + 1 for detail bands.
int band_resolution(const Subband& band, int levels);

// Blocks of every component, ordered by resolution, then component, then subband, then
// tile (x fastest). `block_size` is the nominal block extent; blocks at band edges are
// smaller. Throws std::invalid_argument for a zero block extent.
std::vector<CodeBlock> partition_blocks(const std::vector<Subband>& bands, int levels, std::size_t components,
                                        const Extent& block_size);

// Copies a block out of (into) a component array laid out over `dims`, x fastest.
template <class T>
void copy_block_out(const T* plane, const Extent& dims, const CodeBlock& block, T* out) {
  std::size_t k = 0;
  for (std::size_t z = 0; z < block.size[2]; ++z)
    for (std::size_t y = 0; y < block.size[1]; ++y) {
      const T* row =
          plane + block.offset[0] + dims[0] * ((block.offset[1] + y) + dims[1] * (block.offset[2] + z));
      for (std::size_t x = 0; x < block.size[0]; ++x) out[k++] = row[x];
    }
}
template <class T>
void copy_block_in(const T* in, const Extent& dims, const CodeBlock& block, T* plane) {
  std::size_t k = 0;
  for (std::size_t z = 0; z < block.size[2]; ++z)
    for (std::size_t y = 0; y < block.size[1]; ++y) {
      T* row = plane + block.offset[0] + dims[0] * ((block.offset[1] + y) + dims[1] * (block.offset[2] + z));
      for (std::size_t x = 0; x < block.size[0]; ++x) row[x] = in[k++];
    }
}

}  // namespace pupwave
