// decode_pc_into: the pc coder's group-wise decode (one resolution at a time, its blocks in
// parallel, so every block's parent band is decoded before it) into the output planes, each
// resolution dequantized in place once its children are decoded.
#include "codec/image/pc_decoder.h"

#include <cstring>

#include "codec/entropy/pc_blocks.h"
#include "codec/entropy/pc_cfl.h"
#include "codec/entropy/pc_groups.h"
#include "codec/entropy/pc_priors.h"
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

void pc_add_prediction(const CodeBlock& b, const PcCfl& k, const float* first, const float* second,
                       float* plane, std::size_t stride) {
  for (std::size_t y = 0; y < b.size[1]; ++y) {
    const std::size_t at = b.offset[0] + stride * (b.offset[1] + y);
    for (std::size_t x = 0; x < b.size[0]; ++x)
      plane[at + x] += pc_cfl_predict(k, first[at + x], k.count == 2 ? second[at + x] : 0.0f);
  }
}

namespace {

// Block b of an index plane dequantized where it lies: the plane's storage holds int32 indices
// until then and floats after (the same size), each sample read and written through memcpy.
void dequantize_in_place(const CodeBlock& b, float* plane, std::size_t stride, float step, float delta) {
  static_assert(sizeof(float) == sizeof(std::int32_t));
  for (std::size_t y = 0; y < b.size[1]; ++y) {
    float* row = plane + b.offset[0] + stride * (b.offset[1] + y);
    for (std::size_t x = 0; x < b.size[0]; ++x) {
      std::int32_t q;
      std::memcpy(&q, row + x, sizeof q);
      const float v = pc_dequantize(q, step, delta);
      std::memcpy(row + x, &v, sizeof v);
    }
  }
}

}  // namespace

// The planes hold the indices first (zeroed floats are zero indices), one resolution at a time;
// a resolution is dequantized in place once the next one, whose parents it holds, is decoded,
// so no second set of planes is needed.
void decode_pc_into(const ParsedStream& s, const Extent& region, const Executor& ex,
                    const std::vector<float*>& planes) {
  const float delta = float(s.header.delta);
  std::vector<PcCfl> cfl(s.blocks.size());  // the chroma detail blocks' weights, as decoded
  // Luma's blocks before Cb's before Cr's (pc_group's order): a prediction reads the decoded
  // floats of the components before it.
  const auto dequantize = [&](std::size_t first, std::size_t end) {
    for (int g = 0; g < kPcGroupsPerResolution; ++g) {
      std::vector<std::size_t> ids;
      for (std::size_t i = first; i < end; ++i)
        if (s.index[i].passes != 0 && pc_group(s.blocks[i], planes.size()) % kPcGroupsPerResolution == g)
          ids.push_back(i);  // a block not coded is zero either way (and has no prediction)
      ex.run(ids.size(), [&](std::size_t k) {
        const CodeBlock& b = s.blocks[ids[k]];
        dequantize_in_place(b, planes[b.component], region[0],
                            s.header.steps[b.component * s.bands.size() + b.band], delta);
        if (!pc_cfl_none(cfl[ids[k]]))
          pc_add_prediction(b, cfl[ids[k]], planes[0], planes[1], planes[b.component], region[0]);
      });
    }
  };
  std::size_t previous = 0, first = 0;
  while (first < s.blocks.size()) {
    std::size_t end = first;
    while (end < s.blocks.size() && s.blocks[end].resolution == s.blocks[first].resolution) ++end;
    // The planes' storage as indices until dequantize_in_place (see there).
    const auto index_plane = [&](std::size_t c) { return reinterpret_cast<std::int32_t*>(planes[c]); };
    for (int g = 0; g < kPcGroupsPerResolution; ++g) {  // pc_group's order inside the resolution
      std::vector<std::size_t> ids;
      for (std::size_t i = first; i < end; ++i)
        if (pc_group(s.blocks[i], planes.size()) % kPcGroupsPerResolution == g) ids.push_back(i);
      ex.run(ids.size(), [&](std::size_t k) {
        const std::size_t i = ids[k];
        const CodeBlock& b = s.blocks[i];
        if (s.index[i].passes == 0) return;  // all zero: the planes start zeroed
        require_stream(s.index[i].passes == 1, "pc code-block: pass count");
        std::int32_t* plane = index_plane(b.component);
        const PcLuma luma = pc_has_luma(b, planes.size())
                                ? pc_luma(b, planes.size(), index_plane(0), index_plane(1), region[0])
                                : PcLuma{};
        cfl[i].count = pc_cfl_applies(b, planes.size()) ? pc_cfl_count(b) : 0;
        pc_decode_block(s.codeword(i), s.index[i].planes, b.size[0], b.size[1],
                        lc_parent(s.bands, b, plane, region[0], nullptr),
                        plane + b.offset[0] + region[0] * b.offset[1], region[0], luma,
                        cfl[i].count ? &cfl[i] : nullptr, &pc_block_priors(s.bands, b, planes.size()));
      });
    }
    dequantize(previous, first);  // the parents of this resolution, no longer needed
    previous = first;
    first = end;
  }
  dequantize(previous, first);
}

}  // namespace pupwave
