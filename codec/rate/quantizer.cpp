#include "codec/rate/quantizer.h"

#include <cmath>
#include <stdexcept>

namespace pupwave {

std::vector<float> subband_steps(double base_step, std::span<const double> norms,
                                 std::span<const double> weights) {
  if (!(base_step > 0.0) || !std::isfinite(base_step))
    throw std::invalid_argument("quantizer base step must be positive and finite");
  std::vector<float> steps;
  steps.reserve(norms.size() * weights.size());
  for (double w : weights)
    for (double n : norms) {
      if (!(n > 0.0) || !(w > 0.0)) throw std::invalid_argument("subband norms and weights must be positive");
      steps.push_back(float(base_step / (n * std::sqrt(w))));
    }
  return steps;
}

}  // namespace pupwave
