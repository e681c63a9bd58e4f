#pragma once
// The perceptual domain float images are coded in (docs/bitstream.md, "Transfer"): a
// logarithmic transfer, so that a coding error is an error in stops (a relative error) at
// every luminance rather than an absolute one, which would wipe out the dark pixels of an
// HDR image (values 0..1000 with most pixels below 1).
//   T(x) = sign(x) * log2(1 + |x| / a),   a = 2^-14 (the smallest normal half float)
// T is in stops above a; PSNR in this domain ("log-PSNR") uses peak 1 stop, so 40 dB is an
// RMS error of 1/100 stop (0.7 %), below the ~1 % Weber threshold of luminance.

#include <string>
#include <vector>

#include "codec/image/image.h"
#include "codec/image/image_stream.h"
#include "codec/image/image_view.h"

namespace pupwave {

inline constexpr double kLogTransferOffset = 1.0 / 16384.0;

double to_transfer(double x, Transfer t);
double from_transfer(double v, Transfer t);

// Name of the PSNR a stream's rate target and report use ("PSNR", "log-PSNR").
std::string metric_name(Transfer t);

// A float image ready for the coder: samples in the transfer domain, non-finite samples (if
// kept) replaced by 0 and listed, and whether every finite input sample was >= 0.
struct CodedDomainImage {
  Image image;
  bool nonnegative = true;
  std::vector<NonFiniteSample> nonfinite;
};

// Throws EncodeError for non-finite samples unless keep_nonfinite (the message says how many,
// where the first is, and how to keep them).
CodedDomainImage to_coded_domain(const ImageView& image, Transfer t, bool keep_nonfinite);

// Undoes to_coded_domain on a decoded image: inverse transfer, clamp at 0 for non-negative
// inputs, clamp to the half range for half images, and (at full resolution) the non-finite samples.
void from_coded_domain(Image& image, const StreamHeader& h, bool full_resolution);

// PSNR of `test` against `reference` in the transfer domain (peak 1), over the finite samples
// of the reference.
double transfer_psnr(const Image& reference, const Image& test, Transfer t);

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
