#pragma once
// A first quantizer base step for a byte budget, from the magnitudes of one transformed
// component, so the bit-plane coder need not code planes that rate allocation will drop.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "codec/image/image_plan.h"

namespace pupwave {

// Base step at which component c alone (plan.coef[c], transformed) would cost about
// `budget_bytes` under a simple bit-plane rate model (log2 of each significant index plus a
// fixed overhead), divided by `margin` so PCRD keeps a choice of truncation points below the
// final rate. Coding the other components too only needs a coarser step, so with the first
// (luma) component this errs on the fine side.
double guess_base_step(const ImagePlan& plan, std::size_t c, double budget_bytes, double margin);

// The statistics that model reads: counts of coefficient magnitudes in output units, log2 in
// 1/8 octave bins. Counts add, so the strip-wise encoder fills one block at a time (in any
// order, on any thread) and gets the step guess_base_step(plan, c, ...) gives.
struct MagnitudeHistogram {
  using Counts = std::array<std::uint64_t, std::size_t(1) << 12>;
  Counts counts{};
  void add(std::span<const float> values, float scale);  // scale: magnitude_scale
  void merge(const MagnitudeHistogram& other);
};
// The factor from coefficients of component c, band `band` to output units.
float magnitude_scale(const ImagePlan& plan, std::size_t c, std::size_t band);
double guess_base_step(const MagnitudeHistogram& h, double budget_bytes, double margin);

}  // namespace pupwave
