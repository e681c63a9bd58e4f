#include "codec/image/transfer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>

#include "codec/error.h"
#include "codec/image/image_metrics.h"

namespace pupwave {
namespace {

// The adaptive transfer's offset exponent at 1 bit per sample, and the largest it takes (the
// lowest rate it was fitted at).
constexpr double kAdaptiveOffsetAtOneBit = -5.2;
constexpr int kAdaptiveOffsetHighest = -4;

std::uint32_t float_bits(float v) {
  std::uint32_t b = 0;
  std::memcpy(&b, &v, 4);
  return b;
}

float bits_float(std::uint32_t b) {
  float v = 0.0f;
  std::memcpy(&v, &b, 4);
  return v;
}

[[noreturn]] void refuse_nonfinite(std::size_t count, std::size_t c, std::size_t x, std::size_t y) {
  throw EncodeError("image has " + std::to_string(count) +
                    " non-finite sample(s) (NaN or infinity), the first in channel " + std::to_string(c) +
                    " at x " + std::to_string(x) + ", y " + std::to_string(y) +
                    "; --keep-nonfinite (EncodeOptions::keep_nonfinite) codes them exactly");
}

}  // namespace

double to_transfer(double x, Transfer t, int offset_log2) {
  if (t == Transfer::linear) return x;
  return std::copysign(std::log2(1.0 + std::ldexp(std::abs(x), -offset_log2)), x);
}

double from_transfer(double v, Transfer t, int offset_log2) {
  if (t == Transfer::linear) return v;
  return std::copysign(std::ldexp(std::exp2(std::abs(v)) - 1.0, offset_log2), v);
}

std::string metric_name(Transfer t) {
  switch (t) {
    case Transfer::linear: return "PSNR";
    case Transfer::log2: return "log-PSNR";
    case Transfer::log2_adaptive: return "adaptive log-PSNR";
  }
  return "PSNR";
}

// Fitted on Blender's eight HDR maps against OpenEXR DWAA/DWAB at Q 45 .. 400 (bench/hdr_vs_dwa.py,
// bench/results/image-lossless-hdr.md): the offset that kept Pupwave ahead in both log-PSNR and
// linear-light PSNR fell by about two stops per doubling of the rate (2^-4 at 0.67 bits per
// sample, 2^-8 at 2.7, 2^-10 at 6), since at high rates the dark pixels' relative precision
// decides log-PSNR and at low rates the highlights decide linear PSNR. The image's own
// statistics (its log-average value) predicted nothing beyond the rate.
int adaptive_offset_log2(double bits_per_sample) {
  const double k = kAdaptiveOffsetAtOneBit - 2.0 * std::log2(bits_per_sample);
  return std::clamp(int(std::lround(k)), kLogOffsetLog2, kAdaptiveOffsetHighest);
}

CodedDomainImage to_coded_domain(const ImageView& image, Transfer t, bool keep_nonfinite, int offset_log2) {
  CodedDomainImage out;
  out.offset_log2 = t == Transfer::log2_adaptive ? offset_log2 : kLogOffsetLog2;
  out.image = Image(image.width, image.height, image.channels, image.type);
  std::size_t bad = 0, first_c = 0, first_x = 0, first_y = 0;
  for (std::size_t c = 0; c < image.channels; ++c)
    for (std::size_t y = 0; y < image.height; ++y) {
      float* row = out.image.plane(c) + y * image.width;
      image.read_row(c, y, row);
      for (std::size_t x = 0; x < image.width; ++x) {
        const float v = row[x];
        if (!std::isfinite(v)) {
          if (bad++ == 0) first_c = c, first_x = x, first_y = y;
          out.nonfinite.push_back({std::uint32_t(c), y * image.width + x, float_bits(v)});
          row[x] = 0.0f;  // a value the coder holds; the side list restores the sample
          continue;
        }
        out.nonnegative = out.nonnegative && v >= 0.0f;
        row[x] = float(to_transfer(v, t, out.offset_log2));
      }
    }
  if (bad > 0 && !keep_nonfinite) refuse_nonfinite(bad, first_c, first_x, first_y);
  return out;
}

void from_coded_domain(Image& image, const StreamHeader& h, bool full_resolution) {
  const double lo = h.nonnegative ? 0.0 : -std::numeric_limits<double>::infinity();
  const double hi = image.type == SampleType::f16 ? 65504.0 : std::numeric_limits<double>::infinity();
  for (float& v : image.samples)
    v = float(std::clamp(from_transfer(v, h.transfer, h.transfer_offset_log2), std::max(lo, -hi), hi));
  if (!full_resolution) return;  // the listed positions are those of the full-size image
  for (const NonFiniteSample& s : h.nonfinite) image.plane(s.channel)[s.index] = bits_float(s.bits);
}

double transfer_psnr(const Image& reference, const Image& test, Transfer t, int offset_log2) {
  if (reference.samples.size() != test.samples.size())
    throw std::invalid_argument("transfer_psnr: images of different shapes");
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < reference.samples.size(); ++i) {
    if (!std::isfinite(reference.samples[i])) continue;
    const double d =
        to_transfer(reference.samples[i], t, offset_log2) - to_transfer(test.samples[i], t, offset_log2);
    sum += d * d;
    ++n;
  }
  return psnr_from_mse(n ? sum / double(n) : 0.0, 1.0);
}

HdrError hdr_error(const Image& reference, const Image& test) {
  if (reference.samples.size() != test.samples.size())
    throw std::invalid_argument("hdr_error: images of different shapes");
  auto luma = [](const Image& img, std::size_t i) {
    if (img.channels < 3) return double(img.plane(0)[i]);
    return 0.2126 * img.plane(0)[i] + 0.7152 * img.plane(1)[i] + 0.0722 * img.plane(2)[i];
  };
  std::map<int, std::vector<double>> rel;
  for (std::size_t i = 0; i < reference.plane_size(); ++i) {
    const double y = luma(reference, i);
    if (!(y > 0.0) || !std::isfinite(y)) continue;
    rel[int(std::floor(std::log10(y)))].push_back(std::abs(luma(test, i) - y) / y);
  }
  HdrError out;
  for (auto& [decade, e] : rel) {
    std::nth_element(e.begin(), e.begin() + std::ptrdiff_t(e.size() / 2), e.end());
    out.decades.push_back({decade, double(e.size()) / double(reference.plane_size()), e[e.size() / 2]});
  }
  for (std::size_t i = 0; i < reference.samples.size(); ++i)
    out.sign_flips += reference.samples[i] >= 0.0f && test.samples[i] < 0.0f;
  return out;
}

}  // namespace pupwave
