#pragma once
// A rate and distortion model of the pc coder's passes (codec/image/image_encoder_pc.cpp) from
// per-band histograms of coefficient magnitudes, built once after the transform: at any base
// step it gives the zero-order entropy of the indices the quantizer would choose and their
// squared error, in microseconds. The rate search calibrates it by the real passes (their
// bytes or PSNR against the model's) and solves for the target, so a budget is met in about
// two coding passes instead of a secant's three to five.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/image/image_plan.h"

namespace pupwave {

class PcRateModel {
 public:
  // From plan.coef (every component transformed), magnitudes in output units (magnitude_scale),
  // so one base step quantizes every band; `delta` is the reconstruction offset.
  PcRateModel(const ImagePlan& plan, double delta);

  // Estimated coded bits of every block at `base_step` (zero-order entropy of the indices plus
  // a sign bit per nonzero index), band k's (component c, band b: k = c x bands + b, as the
  // header's steps) multiplied by scale[k] when given (a calibration by a coded pass).
  double bits(double base_step, const std::vector<double>* scale = nullptr) const;
  double bits_of_band(std::size_t k, double base_step) const { return band_bits(bands_[k], base_step); }
  // bits_of_band times the pc coder's typical ratio of real to zero-order bits at the band's
  // density (its modelled bits per sample; contexts gain most in sparse bands), so a calibration
  // by one pass carries to other steps: a prior before any pass, the shape of the ratio after.
  double coded_bits_of_band(std::size_t k, double base_step) const;
  std::size_t band_count() const { return bands_.size(); }
  // Estimated squared error of all samples at `base_step`, in output units (the PSNR's).
  double squared_error(double base_step) const;

 private:
  // One band of one component: cumulative counts of its magnitudes in 1/32-octave bins.
  struct Band {
    std::size_t count = 0;
    std::vector<std::uint32_t> below;  // below[k]: magnitudes in bins under k (kBins + 1 entries)
    bool coarse = false;               // the coarse (LL) band
    bool chroma = false;               // a detail band of a colour-transformed chroma component
    // Its squared error in the PSNR's units per unit of band_error's (visually weighted) ones.
    double error_scale = 1.0;
  };
  double count_below(const Band& band, double magnitude) const;  // interpolated inside a bin
  double band_bits(const Band& band, double base_step) const;
  double band_error(const Band& band, double base_step) const;

  std::vector<Band> bands_;
  int low_exponent_ = 0;  // log2 of the lowest bin's lower edge
  double delta_ = 0.0;
};

}  // namespace pupwave
