#include "tools/rate_warnings.h"

#include <cstdio>
#include <stdexcept>

#include "codec/image/image_stream.h"
#include "tools/cli_numbers.h"
#include "tools/cli_stdio.h"

namespace pupwave::cli {
std::string image_target_miss(const EncodeOptions& enc, const EncodeResult& r, std::size_t width,
                              std::size_t height, const std::string& subject) {
  if (r.target_met) return "";
  if (enc.mode == RateMode::psnr)
    return "--psnr " + shortest(enc.target) + " not met: " + subject + " reaches " + r.metric + " " +
           shortest(r.psnr) + " dB";
  std::string text = "--bpp " + shortest(enc.target) + " not met: " + subject + " is " +
                     std::to_string(r.bytes.size()) + " bytes (" + shortest(r.bpp) + " bpp) for this " +
                     std::to_string(width) + "x" + std::to_string(height) + " image";
  // What the stream holds before any coded data, said where it alone exceeds the budget: why a
  // tiny image cannot meet it.
  const std::size_t framing = container_size(parse_container(r.bytes).header, 0, 0);
  if (8.0 * double(framing) > enc.target * double(width * height))
    text += "; its header and chunk framing alone take " + std::to_string(framing) + " bytes";
  return text;
}

std::string volume_target_miss(const VolumeEncodeOptions& enc, const VolumeEncodeResult& r,
                               const std::string& subject) {
  if (r.target_met) return "";
  switch (enc.mode) {
    case VolumeRateMode::bpv:
      return "--bpv " + shortest(enc.target) + " not met: " + subject + " is " + std::to_string(r.size) +
             " bytes (" + shortest(r.bpv) + " bpv)";
    case VolumeRateMode::psnr:
      return "--psnr " + shortest(enc.target) + " not met: " + subject + " reaches PSNR " + shortest(r.psnr) +
             " dB";
    default:  // max_error: the bound in sample units, as --max-error or --max-error-rel set it
      return "error bound " + shortest(enc.target) + " not met: " + subject + " has a largest error of " +
             shortest(r.max_error);
  }
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
