#pragma once
// A first quantizer base step for a byte budget, from the magnitudes of one transformed
// component, so the bit-plane coder need not code planes that rate allocation will drop.

#include <cstddef>

#include "codec/image/image_plan.h"

namespace pupwave {

// Base step at which component c alone (plan.coef[c], transformed) would cost about
// `budget_bytes` under a simple bit-plane rate model (log2 of each significant index plus a
// fixed overhead), divided by `margin` so PCRD keeps a choice of truncation points below the
// final rate. Coding the other components too only needs a coarser step, so with the first
// (luma) component this errs on the fine side.
double guess_base_step(const ImagePlan& plan, std::size_t c, double budget_bytes, double margin);

}  // namespace pupwave
