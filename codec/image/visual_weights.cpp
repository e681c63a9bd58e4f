#include "codec/image/visual_weights.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pupwave {
namespace {

// Mannos-Sakrison contrast sensitivity, unnormalised.
double mannos_sakrison(double f) { return 2.6 * (0.0192 + 0.114 * f) * std::exp(-std::pow(0.114 * f, 1.1)); }

// Where mannos_sakrison peaks (cycles per degree) and its value there.
constexpr double kPeakFrequency = 8.0;
const double kPeakSensitivity = mannos_sakrison(kPeakFrequency);

// Colour-difference sensitivity falls off about an octave before luma's (Mullen 1985): the
// luma curve read at this multiple of the frequency.
constexpr double kChromaFrequencyScale = 2.0;

// Squared-error weight of the colour-difference components against luma: their errors are
// less visible at every frequency.
constexpr double kChromaWeight = 0.5;

// The least band weight: a band weighted near zero would code nothing at any rate, and its
// loss shows as blur and colour bleeding the sensitivity curve does not model.
constexpr double kLeastWeight = 0.1;

// Centre frequency (cycles per degree) of a detail band of `level` (1 finest) along an axis
// it is high-pass on: level l covers [1/2^(l+1), 1/2^l] of the sampling rate.
double band_frequency(int level, double pixels_per_degree) {
  return 0.75 * pixels_per_degree / std::ldexp(1.0, level);
}

}  // namespace

const char* to_string(Tune tune) { return tune == Tune::visual ? "visual" : "psnr"; }

std::optional<Tune> tune_from_name(std::string_view name) {
  if (name == "psnr") return Tune::psnr;
  if (name == "visual") return Tune::visual;
  return std::nullopt;
}

double relative_contrast_sensitivity(double f) {
  if (f <= kPeakFrequency) return 1.0;
  return mannos_sakrison(f) / kPeakSensitivity;
}

std::vector<double> visual_band_weights(std::span<const Subband> bands, bool chroma) {
  // Pixels per degree of visual angle at the viewing distance.
  const double ppd = kViewingDistancePixels * std::tan(std::numbers::pi / 180.0);
  std::vector<double> w;
  w.reserve(bands.size());
  for (const Subband& b : bands) {
    const unsigned high = b.orientation & 3u;  // x and y: the image axes
    if (b.orientation == 0 || high == 0) {
      w.push_back(1.0);
      continue;
    }
    double f = band_frequency(b.level, ppd);
    if (high == 3u) f *= std::numbers::sqrt2;  // diagonal detail: radial frequency
    if (chroma) f *= kChromaFrequencyScale;
    w.push_back(std::max(kLeastWeight, relative_contrast_sensitivity(f)));
  }
  return w;
}

std::vector<double> visual_weights(std::span<const Subband> bands, std::size_t channels,
                                   ColourTransform colour) {
  const std::vector<double> luma = visual_band_weights(bands, false);
  const std::vector<double> chroma = visual_band_weights(bands, true);
  std::vector<double> w;
  w.reserve(bands.size() * channels);
  for (std::size_t c = 0; c < channels; ++c) {
    const bool colour_difference = colour == ColourTransform::ict && (c == 1 || c == 2);
    for (std::size_t b = 0; b < bands.size(); ++b)
      w.push_back(colour_difference ? chroma[b] * std::sqrt(kChromaWeight) : luma[b]);
  }
  return w;
}

}  // namespace pupwave
