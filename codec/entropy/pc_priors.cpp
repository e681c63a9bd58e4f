#include "codec/entropy/pc_priors.h"

#include <array>
#include <stdexcept>

#include "codec/entropy/pc_priors_table.h"

namespace pupwave {

static_assert(kPcPriorTable.size() == std::size_t(kPcPriorClasses));
static_assert(kPcPriorTable[0].size() == kPcModelCount);

const PcModels& pc_prior_models(int cls) {
  static const auto models = [] {
    std::array<PcModels, kPcPriorClasses> all{};
    for (std::size_t c = 0; c < all.size(); ++c) {
      std::size_t k = 0;
      pc_each_model(all[c], [&](PcBit& b) {
        const std::uint8_t p = kPcPriorTable[c][k++];
        if (p == 0) return;  // never trained: flat
        b.p0 = std::uint16_t(p << (kProbabilityBits - 8));
        b.count = kPcPriorCount;
      });
    }
    return all;
  }();
  if (cls < 0 || cls >= kPcPriorClasses) throw std::out_of_range("pc_prior_models: no such class");
  return models[std::size_t(cls)];
}

}  // namespace pupwave
