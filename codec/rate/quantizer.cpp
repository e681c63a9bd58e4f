#include "codec/rate/quantizer.h"

#include <cmath>
#include <stdexcept>

namespace pupwave {

std::vector<float> subband_steps(double base_step, std::span<const double> norms,
                                 std::span<const double> weights, std::span<const double> visual) {
  if (!(base_step > 0.0) || !std::isfinite(base_step))
    throw std::invalid_argument("quantizer base step must be positive and finite");
  std::vector<float> steps;
  steps.reserve(norms.size() * weights.size());
  if (!visual.empty() && visual.size() != norms.size() * weights.size())
    throw std::invalid_argument("visual weights must be one per component and band");
  for (double w : weights)
    for (double n : norms) {
      const double v = visual.empty() ? 1.0 : visual[steps.size()];
      if (!(n > 0.0) || !(w > 0.0) || !(v > 0.0))
        throw std::invalid_argument("subband norms and weights must be positive");
      steps.push_back(float(base_step / (n * std::sqrt(w) * v)));
    }
  return steps;
}

}  // namespace pupwave
