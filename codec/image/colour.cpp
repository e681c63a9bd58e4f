#include "codec/image/colour.h"

namespace pupwave {
namespace {

// ITU-T T.800 Eq. G-5 / G-6.
constexpr double kCrToR = 1.402;
constexpr double kCbToG = -0.344136;
constexpr double kCrToG = -0.714136;
constexpr double kCbToB = 1.772;

// Floor division by 4 that rounds towards minus infinity for negative sums too.
std::int32_t floor_div4(std::int32_t v) { return v >> 2; }

}  // namespace

const char* to_string(ColourTransform colour) {
  switch (colour) {
    case ColourTransform::none: return "none";
    case ColourTransform::ict: return "ICT (YCbCr)";
    case ColourTransform::rct: return "RCT (reversible)";
  }
  return "unknown";
}

void forward_ict(float* r, float* g, float* b, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const double R = r[i], G = g[i], B = b[i];
    r[i] = float(0.299 * R + 0.587 * G + 0.114 * B);
    g[i] = float(-0.168736 * R - 0.331264 * G + 0.5 * B);
    b[i] = float(0.5 * R - 0.418688 * G - 0.081312 * B);
  }
}

void forward_ict(const float rgb[3], std::size_t c, float* out) {
  const double R = rgb[0], G = rgb[1], B = rgb[2];
  if (c == 0)
    *out = float(0.299 * R + 0.587 * G + 0.114 * B);
  else if (c == 1)
    *out = float(-0.168736 * R - 0.331264 * G + 0.5 * B);
  else
    *out = float(0.5 * R - 0.418688 * G - 0.081312 * B);
}

std::array<double, 3> forward_ict_weights(std::size_t c) {
  // x - y is x + (-y) exactly, so sums with these are forward_ict's expressions term by term.
  static constexpr double kRows[3][3] = {
      {0.299, 0.587, 0.114}, {-0.168736, -0.331264, 0.5}, {0.5, -0.418688, -0.081312}};
  return {kRows[c][0], kRows[c][1], kRows[c][2]};
}

void forward_ict_row(const float* const rgb[3], float shift, std::size_t c, float* out, std::size_t n) {
  const auto [a, b, d] = forward_ict_weights(c);
  const float *r = rgb[0], *g = rgb[1], *bl = rgb[2];
  for (std::size_t i = 0; i < n; ++i) {
    const double R = r[i] - shift, G = g[i] - shift, B = bl[i] - shift;
    out[i] = float(a * R + b * G + d * B);
  }
}

void inverse_ict(float* y, float* cb, float* cr, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const double Y = y[i], Cb = cb[i], Cr = cr[i];
    y[i] = float(Y + kCrToR * Cr);
    cb[i] = float(Y + kCbToG * Cb + kCrToG * Cr);
    cr[i] = float(Y + kCbToB * Cb);
  }
}

void forward_rct(std::int32_t* r, std::int32_t* g, std::int32_t* b, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t R = r[i], G = g[i], B = b[i];
    r[i] = floor_div4(R + 2 * G + B);
    g[i] = B - G;
    b[i] = R - G;
  }
}

void forward_rct(const std::int32_t rgb[3], std::size_t c, std::int32_t* out) {
  const std::int32_t R = rgb[0], G = rgb[1], B = rgb[2];
  if (c == 0)
    *out = floor_div4(R + 2 * G + B);
  else if (c == 1)
    *out = B - G;
  else
    *out = R - G;
}

void inverse_rct(std::int32_t* y, std::int32_t* u, std::int32_t* v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t Y = y[i], U = u[i], V = v[i];
    const std::int32_t G = Y - floor_div4(U + V);
    y[i] = V + G;
    u[i] = G;
    v[i] = U + G;
  }
}

std::array<double, 3> ict_error_weights() {
  return {3.0, kCbToG * kCbToG + kCbToB * kCbToB, kCrToR * kCrToR + kCrToG * kCrToG};
}

}  // namespace pupwave
