#pragma once
// Dead-zone uniform scalar quantizer. Subband b of component c gets the step
//   step = base / (norm_b * sqrt(weight_c)),
// where norm_b is the L2 norm of the subband's synthesis basis functions and weight_c the
// squared error a unit error of component c causes in the output channels. Then a unit
// error in index units costs base^2 of output squared error in every subband and
// component, so bits go where they reduce the MSE most for any transform.

#include <cstdint>
#include <span>
#include <vector>

namespace pupwave {

// Default reconstruction offset inside a quantization bin [q, q+1) (index units): below the
// middle because detail coefficients are peaked (Laplacian) around zero.
inline constexpr double kDefaultReconstructionDelta = 0.4375;

// Steps for every (component, band): result[c * norms.size() + b]. A non-empty `visual` (one
// per (component, band), same order: visual_weights.h) scales each gain, so a unit index
// error costs base^2 of visually weighted squared error instead.
std::vector<float> subband_steps(double base_step, std::span<const double> norms,
                                 std::span<const double> weights, std::span<const double> visual = {});

// Index-unit magnitudes |x| / step and signs of a run of coefficients: the integer part of
// magnitude is the dead-zone quantization index (bin [q, q+1) * step, q = 0 twice as wide).
template <class T>
void quantize(std::span<const T> coefficients, float step, std::span<float> magnitude,
              std::span<std::uint8_t> negative) {
  const float inv = 1.0f / step;
  for (std::size_t i = 0; i < coefficients.size(); ++i) {
    const float v = float(coefficients[i]);
    negative[i] = v < 0.0f;
    magnitude[i] = (v < 0.0f ? -v : v) * inv;
  }
}

}  // namespace pupwave
