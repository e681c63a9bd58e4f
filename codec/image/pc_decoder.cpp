// decode_pc_into: the pc coder's group-wise decode (one resolution at a time, its blocks in
// parallel, so every block's parent band is decoded before it), then dequantisation.
#include "codec/image/pc_decoder.h"

#include "codec/entropy/pc_blocks.h"
#include "codec/entropy/pc_groups.h"
#include "codec/error.h"
#include "codec/image/lc_parent.h"

namespace pupwave {

void pc_dequantize_block(const CodeBlock& b, const std::int32_t* index, float* plane, std::size_t stride,
                         float step, float delta) {
  const std::size_t at = b.offset[0] + stride * b.offset[1];
  for (std::size_t y = 0; y < b.size[1]; ++y)
    for (std::size_t x = 0; x < b.size[0]; ++x)
      plane[at + y * stride + x] = pc_dequantize(index[at + y * stride + x], step, delta);
}

void decode_pc_into(const ParsedStream& s, const Extent& region, const Executor& ex,
                    const std::vector<float*>& planes) {
  const std::size_t samples = region[0] * region[1];
  // The parents are the decoded integer indices, not the dequantized floats.
  std::vector<std::vector<std::int32_t>> index(planes.size(), std::vector<std::int32_t>(samples, 0));
  std::size_t first = 0;
  while (first < s.blocks.size()) {
    std::size_t end = first;
    while (end < s.blocks.size() && s.blocks[end].resolution == s.blocks[first].resolution) ++end;
    for (int g = 0; g < kPcGroupsPerResolution; ++g) {  // pc_group's order inside the resolution
      std::vector<std::size_t> ids;
      for (std::size_t i = first; i < end; ++i)
        if (pc_group(s.blocks[i], index.size()) % kPcGroupsPerResolution == g) ids.push_back(i);
      ex.run(ids.size(), [&](std::size_t k) {
        const std::size_t i = ids[k];
        const CodeBlock& b = s.blocks[i];
        if (s.index[i].passes == 0) return;  // all zero: the planes start zeroed
        require_stream(s.index[i].passes == 1, "pc code-block: pass count");
        std::int32_t* plane = index[b.component].data();
        pc_decode_block(s.codeword(i), s.index[i].planes, b.size[0], b.size[1],
                        lc_parent(s.bands, b, plane, region[0], nullptr),
                        plane + b.offset[0] + region[0] * b.offset[1], region[0],
                        pc_luma(b, index, region[0]));
      });
    }
    first = end;
  }
  const float delta = float(s.header.delta);
  ex.run(s.blocks.size(), [&](std::size_t i) {
    const CodeBlock& b = s.blocks[i];
    if (s.index[i].passes == 0) return;
    pc_dequantize_block(b, index[b.component].data(), planes[b.component], region[0],
                        s.header.steps[b.component * s.bands.size() + b.band], delta);
  });
}

}  // namespace pupwave
