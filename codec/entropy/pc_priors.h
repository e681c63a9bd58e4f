#pragma once
// Trained start states of the pc coder's models (entropy coder 4, docs/bitstream.md, stream
// version 6): a block is a whole band, yet many of its 738 models code only a few bits, and
// one that starts near its typical probability spends fewer bits learning it. Every model of a
// block starts at its band class's trained probability of a 0, worth kPcPriorCount bits, or
// flat (1/2, count 0) where the training never used it. Band classes: each detail level (1
// finest .. 6, coarser levels as 6) x orientation x luma / chroma, and the coarse band luma /
// chroma. -2.5 points BD-rate against OpenJPEG on the test photographs, -1.1 on held-out ones.
// Tables: pc_priors_table.h (tools/train/train_pc_priors.cpp).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/entropy/codeblocks.h"
#include "codec/entropy/pc_index.h"
#include "transforms/subband.h"

namespace pupwave {

// Detail levels with their own classes (coarser ones share the last), and the class count.
inline constexpr int kPcPriorLevels = 6;
inline constexpr int kPcPriorClasses = kPcPriorLevels * 3 * 2 + 2;
// Models of a block, in the tables' order: unary by activity class, low by activity class, sign.
inline constexpr std::size_t kPcModelCount =
    std::size_t(kCoefClasses) * (kCoefUnaryModels + (2 << kCoefModelledLow)) + 2 * kPcSignContexts;
// How many bits a trained start is worth: PcBit's count (rate 1/16 at first, then 1/32 ...).
inline constexpr std::uint8_t kPcPriorCount = 8;

// The class of a block of band `band` in component `component` of `components`: chroma are
// the second and later components of three or more (pc_has_luma's, and any alpha).
inline int pc_prior_class(const Subband& band, std::size_t component, std::size_t components) {
  const int chroma = component > 0 && components >= 3 ? 1 : 0;
  if (band.orientation == 0) return kPcPriorLevels * 3 * 2 + chroma;
  const int level = std::clamp(band.level, 1, kPcPriorLevels) - 1;
  const int orientation = int(std::min(band.orientation, 3u)) - 1;
  return (level * 3 + orientation) * 2 + chroma;
}

// The models a block of class `cls` (0 .. kPcPriorClasses - 1) starts with.
const PcModels& pc_prior_models(int cls);

// The models block b starts with.
inline const PcModels& pc_block_priors(const std::vector<Subband>& bands, const CodeBlock& b,
                                       std::size_t components) {
  return pc_prior_models(pc_prior_class(bands[b.band], b.component, components));
}

// Calls f(model) for every model of m in the tables' order.
template <class Models, class F>
void pc_each_model(Models& m, const F& f) {
  for (auto& row : m.unary)
    for (auto& b : row) f(b);
  for (auto& row : m.low)
    for (auto& b : row) f(b);
  for (auto& b : m.sign) f(b);
}

}  // namespace pupwave
