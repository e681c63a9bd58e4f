#include "tools/rate_warnings.h"

#include <cstdio>
#include <stdexcept>

#include "codec/api/api_target_miss.h"
#include "tools/cli_stdio.h"

namespace pupwave::cli {
namespace {

pupwave::api::ImageRate api_rate(RateMode mode) {
  switch (mode) {
    case RateMode::psnr: return pupwave::api::ImageRate::psnr;
    case RateMode::bpp: return pupwave::api::ImageRate::bpp;
    case RateMode::step: return pupwave::api::ImageRate::step;
    case RateMode::lossless: break;
  }
  return pupwave::api::ImageRate::lossless;
}

// The encoder's volume modes as the API's: its max_error mode is an absolute bound (a relative
// one was scaled to sample units before encoding).
pupwave::api::VolumeRate api_rate(VolumeRateMode mode) {
  switch (mode) {
    case VolumeRateMode::bpv: return pupwave::api::VolumeRate::bpv;
    case VolumeRateMode::psnr: return pupwave::api::VolumeRate::psnr;
    case VolumeRateMode::step: return pupwave::api::VolumeRate::step;
    case VolumeRateMode::lossless: return pupwave::api::VolumeRate::lossless;
    case VolumeRateMode::max_error: break;
  }
  return pupwave::api::VolumeRate::max_error;
}

}  // namespace

std::string image_target_miss(const EncodeOptions& enc, const EncodeResult& r, const std::string& subject) {
  const pupwave::api::TargetOutcome outcome{r.target_met, enc.mode == RateMode::bpp ? r.bpp : r.psnr};
  return pupwave::api::image_target_miss(api_rate(enc.mode), enc.target, outcome, r.bytes, subject);
}

std::string volume_target_miss(const VolumeEncodeOptions& enc, const VolumeEncodeResult& r,
                               const std::string& subject) {
  const double achieved = enc.mode == VolumeRateMode::bpv    ? r.bpv
                          : enc.mode == VolumeRateMode::psnr ? r.psnr
                                                             : r.max_error;
  return pupwave::api::volume_target_miss(api_rate(enc.mode), enc.target, {r.target_met, achieved}, r.size,
                                          subject);
}

std::string stream_subject(const std::string& output) { return is_stdio(output) ? "the stream" : output; }

void refuse_if_strict(bool strict, const std::string& missed, const std::string& output) {
  if (!strict || missed.empty()) return;
  const std::string what = is_stdio(output) ? "nothing written to stdout" : output + " not written";
  throw std::runtime_error(missed + "; " + what + " (--strict)");
}

void warn_if_missed(const std::string& missed) {
  if (!missed.empty()) std::fprintf(stderr, "warning: %s\n", missed.c_str());
}

}  // namespace pupwave::cli
