#pragma once
// The perceptual domain float images are coded in (docs/bitstream.md, "Transfer"): a
// logarithmic transfer, so that a coding error is an error in stops (a relative error) at
// every luminance rather than an absolute one, which would wipe out the dark pixels of an
// HDR image (values 0..1000 with most pixels below 1).
//   T(x) = sign(x) * log2(1 + |x| / a),   a = 2^-14 (the smallest normal half float)
// T is in stops above a; PSNR in this domain ("log-PSNR") uses peak 1 stop, so 40 dB is an
// RMS error of 1/100 stop (0.7 %), below the ~1 % Weber threshold of luminance.
// log2_adaptive is the same curve with a larger offset a = 2^k chosen per image from its rate
// (adaptive_offset_log2) and signalled: samples far above a are coded in stops as by log2,
// samples far below it nearly linearly, so fewer bits go to the darkest pixels and more to the
// highlights that dominate PSNR in linear light.

#include <string>
#include <vector>

#include "codec/image/image.h"
#include "codec/image/image_stream.h"
#include "codec/image/image_view.h"

namespace pupwave {

// offset_log2: log2 of the offset a of the log transfers (the header's transfer_offset_log2).
double to_transfer(double x, Transfer t, int offset_log2 = kLogOffsetLog2);
double from_transfer(double v, Transfer t, int offset_log2 = kLogOffsetLog2);

// Name of the PSNR a stream's rate target and report use ("PSNR", "log-PSNR", "adaptive
// log-PSNR": peak 1 over log2(1 + |x| / a) with the image's own a).
std::string metric_name(Transfer t);

// The offset exponent log2_adaptive codes an image with at `bits_per_sample` (bits per pixel
// over the channel count): lower at higher rates, in [kLogOffsetLog2, -4] (transfer.cpp).
int adaptive_offset_log2(double bits_per_sample);
// The exponent for targets that fix no rate (--psnr, --step): that of 2.7 bits per sample.
inline constexpr int kAdaptiveOffsetNoRate = -8;

// A float image ready for the coder: samples in the transfer domain, non-finite samples (if
// kept) replaced by 0 and listed, and whether every finite input sample was >= 0.
struct CodedDomainImage {
  Image image;
  int offset_log2 = kLogOffsetLog2;  // the offset exponent the log transfers used
  bool nonnegative = true;
  std::vector<NonFiniteSample> nonfinite;
};

// Throws EncodeError for non-finite samples unless keep_nonfinite (the message says how many,
// where the first is, and how to keep them). offset_log2: that of log2_adaptive.
CodedDomainImage to_coded_domain(const ImageView& image, Transfer t, bool keep_nonfinite,
                                 int offset_log2 = kLogOffsetLog2);

// Undoes to_coded_domain on a decoded image: inverse transfer, clamp at 0 for non-negative
// inputs, clamp to the half range for half images, and (at full resolution) the non-finite samples.
void from_coded_domain(Image& image, const StreamHeader& h, bool full_resolution);

// PSNR of `test` against `reference` in the transfer domain (peak 1), over the finite samples
// of the reference.
double transfer_psnr(const Image& reference, const Image& test, Transfer t, int offset_log2 = kLogOffsetLog2);

// Relative error of an HDR image by decade of luminance (Rec. 709 Y of channels 0..2, or
// channel 0 for grey), for `pupwave psnr` and bench/hdr_compare.sh.
struct DecadeError {
  int decade = 0;           // luminance in [10^decade, 10^(decade+1))
  double share = 0.0;       // fraction of the pixels
  double median_rel = 0.0;  // median |Y' - Y| / Y
};
struct HdrError {
  std::vector<DecadeError> decades;  // ascending, pixels with Y > 0 only
  std::size_t sign_flips = 0;        // samples >= 0 in the reference, < 0 in the test
};
HdrError hdr_error(const Image& reference, const Image& test);

}  // namespace pupwave
