#pragma once
// Between an Image and the planes the wavelet transform codes: level shift of integer
// samples to signed, colour transform, per-component error weights, and the way back
// (including the reduced-resolution rescaling and the rounding and clamping of samples).

#include <cstdint>
#include <vector>

#include "codec/image/colour.h"
#include "codec/image/image.h"
#include "codec/image/image_view.h"
#include "transforms/executor.h"
#include "transforms/subband.h"
#include "transforms/transform1d.h"

namespace pupwave {

// Colour transform used for an image of `channels` channels.
ColourTransform colour_for(std::size_t channels, bool reversible);

// Level shift that centres integer samples on zero (2^(bits-1)); 0 for float samples.
double level_shift(SampleType type);

// Component c after level shift and colour transform (forward_ict / forward_rct), one at a
// time so an encoder holds a single transformed component. `out` is resized to the plane size
// (its capacity is reused). Rows are converted in parallel on `ex`.
void float_component(const ImageView& image, ColourTransform colour, std::size_t c, std::vector<float>& out,
                     const Executor& ex = serial_executor());
void integer_component(const ImageView& image, ColourTransform colour, std::size_t c,
                       std::vector<std::int32_t>& out, const Executor& ex = serial_executor());

// Rows [y0, y1) of component c the same way, into `out` ((y1 - y0) rows of image.width): the
// strip-wise encoder's input.
void float_component_rows(const ImageView& image, ColourTransform colour, std::size_t c, std::size_t y0,
                          std::size_t y1, float* out, const Executor& ex = serial_executor());
void integer_component_rows(const ImageView& image, ColourTransform colour, std::size_t c, std::size_t y0,
                            std::size_t y1, std::int32_t* out, const Executor& ex = serial_executor());

// Squared output error per unit error of each component (ICT components weigh more).
std::vector<double> component_weights(std::size_t channels, ColourTransform colour);

// DC gain of the level-`level` coarse band of transform t over dims (1 for level 0), so a
// reduced-resolution band can be brought back to sample units.
double coarse_gain(const Transform1D& t, const Extent& dims, int level);

// Builds the output image from the low-corner `size` region of component planes laid out
// over `dims`: divide by `gain`, undo colour and level shift, round and clamp to the type.
// Consumes `planes` (they are transformed in place and freed as the image is written).
Image image_from_components(std::vector<std::vector<float>>& planes, const Extent& dims, const Extent& size,
                            SampleType type, ColourTransform colour, double gain);
Image image_from_components(std::vector<std::vector<std::int32_t>>& planes, const Extent& dims,
                            const Extent& size, SampleType type, ColourTransform colour);

// The same for full-resolution float planes that already are the image's own planes (decoded
// into image.samples, gain 1): undoes colour and level shift, rounds and clamps in place, as
// tasks of `ex`, so a decoder never holds a second full-size copy.
void finish_image_in_place(Image& image, ColourTransform colour, const Executor& ex);

// PSNR (all channels, as compare_images(reference, decoded).overall) of full-resolution
// component planes laid out over the reference's extent, without building the decoded
// image: undoes colour and level shift, rounds and clamps like image_from_components.
// Consumes `planes` (the colour transform is undone in place).
// clamp_at_zero: decoded values below 0 count as 0 (a float stream of non-negative input,
// StreamHeader::nonnegative; the clamp commutes with the sign-preserving transfer).
double components_psnr(const ImageView& reference, std::vector<std::vector<float>>& planes,
                       ColourTransform colour, bool clamp_at_zero = false);
double components_psnr(const ImageView& reference, std::vector<std::vector<std::int32_t>>& planes,
                       ColourTransform colour);

// The same comparison for rows [y0, y0 + rows) only (planes of `rows` rows of the reference's
// width), as a sum of squared errors, so a caller decoding by strips can add strips up.
double components_squared_error(const ImageView& reference, std::size_t y0, std::size_t rows,
                                std::vector<std::vector<float>>& planes, ColourTransform colour,
                                bool clamp_at_zero = false);
double components_squared_error(const ImageView& reference, std::size_t y0, std::size_t rows,
                                std::vector<std::vector<std::int32_t>>& planes, ColourTransform colour);
// PSNR (as components_psnr) of a sum of squared errors over every sample of the reference.
double psnr_of_squared_error(const ImageView& reference, double sum_sq);

}  // namespace pupwave
