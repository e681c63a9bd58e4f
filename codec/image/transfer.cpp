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

double to_transfer(double x, Transfer t) {
  if (t == Transfer::linear) return x;
  return std::copysign(std::log2(1.0 + std::abs(x) / kLogTransferOffset), x);
}

double from_transfer(double v, Transfer t) {
  if (t == Transfer::linear) return v;
  return std::copysign(kLogTransferOffset * (std::exp2(std::abs(v)) - 1.0), v);
}

std::string metric_name(Transfer t) { return t == Transfer::log2 ? "log-PSNR" : "PSNR"; }

CodedDomainImage to_coded_domain(const ImageView& image, Transfer t, bool keep_nonfinite) {
  CodedDomainImage out;
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
        row[x] = float(to_transfer(v, t));
      }
    }
  if (bad > 0 && !keep_nonfinite) refuse_nonfinite(bad, first_c, first_x, first_y);
  return out;
}

void from_coded_domain(Image& image, const StreamHeader& h, bool full_resolution) {
  const double lo = h.nonnegative ? 0.0 : -std::numeric_limits<double>::infinity();
  const double hi = image.type == SampleType::f16 ? 65504.0 : std::numeric_limits<double>::infinity();
  for (float& v : image.samples) v = float(std::clamp(from_transfer(v, h.transfer), std::max(lo, -hi), hi));
  if (!full_resolution) return;  // the listed positions are those of the full-size image
  for (const NonFiniteSample& s : h.nonfinite) image.plane(s.channel)[s.index] = bits_float(s.bits);
}

double transfer_psnr(const Image& reference, const Image& test, Transfer t) {
  if (reference.samples.size() != test.samples.size())
    throw std::invalid_argument("transfer_psnr: images of different shapes");
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < reference.samples.size(); ++i) {
    if (!std::isfinite(reference.samples[i])) continue;
    const double d = to_transfer(reference.samples[i], t) - to_transfer(test.samples[i], t);
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
