// encode_image with the lc back end: each component is transformed whole, then its blocks are
// coded in parallel, each reading its parent band from the same transformed component.
#include "codec/image/image_encoder_lc.h"

#include <stdexcept>

#include "codec/entropy/lc_blocks.h"
#include "codec/image/lc_parent.h"

namespace pupwave {

EncodeResult encode_lc(const ImageView& image, ImagePlan& plan) {
  if (!plan.header.reversible) throw std::invalid_argument("the lc coder codes lossless streams only");
  std::vector<BlockEntry> entries(plan.blocks.size());
  std::vector<std::vector<std::uint8_t>> words(plan.blocks.size());
  const Extent& dims = plan.header.dims;
  std::vector<std::int32_t> first;  // the first component, the guide of the others' coarse band
  std::vector<std::int32_t> previous;
  for (std::size_t c = 0; c < plan.header.channels; ++c) {
    std::vector<std::size_t> ids;
    for (std::size_t i = 0; i < plan.blocks.size(); ++i)
      if (plan.blocks[i].component == c) ids.push_back(i);
    transform_component(plan, c);
    const std::int32_t* plane = plan.icoef[c].data();
    plan.executor->run(ids.size(), [&](std::size_t k) {
      const std::size_t i = ids[k];
      const CodeBlock& b = plan.blocks[i];
      std::vector<std::int32_t> values(b.count());
      copy_block_out(plane, dims, b, values.data());
      LcCodeword w =
          lc_encode_block(values, b.size[0], b.size[1], b.orientation == 0,
                          lc_parent(plan.bands, b, plane, dims[0], first.empty() ? nullptr : first.data(),
                                    previous.empty() ? nullptr : previous.data()));
      entries[i] = {w.planes, w.planes > 0 ? 1 : 0, std::uint32_t(w.bytes.size())};
      words[i] = std::move(w.bytes);
    });
    if (c == 0 && plan.header.channels > 1) first = plan.icoef[0];
    if (c + 1 < plan.header.channels) previous = plan.icoef[c];
    release_component(plan, c);
  }
  release_coefficients(plan);
  return make_encode_result(image, plan, assemble(plan, entries, words), 1.0);
}

}  // namespace pupwave
