#pragma once
// Colour transforms of JPEG 2000 Part 1 Annex G: the irreversible YCbCr transform (ICT) for
// lossy RGB and the reversible integer transform (RCT) for lossless RGB. They act on the
// first three planes in place; extra planes (alpha) are left alone and coded as they are.

#include <array>
#include <cstddef>
#include <cstdint>

namespace pupwave {

enum class ColourTransform : std::uint8_t { none = 0, ict = 1, rct = 2 };

const char* to_string(ColourTransform colour);

// R, G, B -> Y, Cb, Cr (real-valued, orthogonal-ish) and back, n samples per plane.
void forward_ict(float* r, float* g, float* b, std::size_t n);
void inverse_ict(float* y, float* cb, float* cr, std::size_t n);
// Component c (0: Y, 1: Cb, 2: Cr) of the ICT of one pixel, exactly as forward_ict gives it.
void forward_ict(const float rgb[3], std::size_t c, float* out);
// Component c of the ICT of n pixels whose samples are rgb[k][i] - shift, exactly as above,
// in one loop the compiler vectorizes (the encoder's colour conversion, row by row).
void forward_ict_row(const float* const rgb[3], float shift, std::size_t c, float* out, std::size_t n);
// The weights of R, G and B in component c of the ICT, as forward_ict_row multiplies them.
std::array<double, 3> forward_ict_weights(std::size_t c);

// R, G, B -> Yr, Ur, Vr (integer, bit-exactly invertible) and back.
void forward_rct(std::int32_t* r, std::int32_t* g, std::int32_t* b, std::size_t n);
void inverse_rct(std::int32_t* y, std::int32_t* u, std::int32_t* v, std::size_t n);
// Component c (0: Yr, 1: Ur, 2: Vr) of the RCT of one pixel, exactly as forward_rct gives it.
void forward_rct(const std::int32_t rgb[3], std::size_t c, std::int32_t* out);

// Squared error in R+G+B caused by a unit error in each ICT component (squared column norms
// of the inverse ICT), so rate allocation minimizes the error of the colours, not of YCbCr.
std::array<double, 3> ict_error_weights();

}  // namespace pupwave
