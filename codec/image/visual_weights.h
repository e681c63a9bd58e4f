#pragma once
// What `--tune visual` means: the one place that decides it. The quantizer's steps
// (quantizer.h) make a unit index error cost the same output squared error in every band, so
// rate allocation minimises the MSE. Visual tuning scales each band's and component's
// synthesis gain by how visible its error is, so the same allocation minimises a
// contrast-sensitivity-weighted squared error instead (JPEG 2000 Part 1 Annex J.12's visual
// frequency weighting). Only the steps change, and the stream carries them: no new signalling.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "codec/image/colour.h"
#include "transforms/subband.h"

namespace pupwave {

enum class Tune : std::uint8_t {
  psnr,    // minimise the squared error (the default: PSNR targets and benchmarks)
  visual,  // minimise a contrast-sensitivity-weighted squared error
};

const char* to_string(Tune tune);                           // "psnr", "visual"
std::optional<Tune> tune_from_name(std::string_view name);  // exact lower-case names

// The viewing distance the weights are for, in pixels: about 58 pixels per degree of visual
// angle (a 27-inch 2560 x 1440 screen seen from 77 cm). Chosen on a crop of one photograph
// (butteraugli, MS-SSIM, SSIM at 0.25-1 bpp; 2600 and 4000 scored lower there, 6000 and more
// much lower: the finest bands then sit at kLeastWeight).
inline constexpr double kViewingDistancePixels = 3300.0;

// Contrast sensitivity (Mannos and Sakrison 1974) at f cycles per degree, relative to its peak
// (1 at and below the peak frequency: the coarse bands keep their full weight).
double relative_contrast_sensitivity(double cycles_per_degree);

// Amplitude weight of each band of a 2-D decomposition for luma (a unit error of band b is
// seen as weight[b] of one in the coarse band) or, with `chroma`, for a colour-difference
// component, whose sensitivity falls off at lower frequencies.
std::vector<double> visual_band_weights(std::span<const Subband> bands, bool chroma);

// The amplitude weight of every (component, band), result[c * bands.size() + b], for an image
// of `channels` components under colour transform `colour`: the luma weights for luma and for
// components without a luma/chroma transform, the chroma weights times a lower component weight
// for Cb and Cr (quantizer.h's subband_steps takes them).
std::vector<double> visual_weights(std::span<const Subband> bands, std::size_t channels,
                                   ColourTransform colour);

}  // namespace pupwave
