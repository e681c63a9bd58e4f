// The text of a missed rate target (api_target_miss.h).
#include "codec/api/api_target_miss.h"

#include <cstdio>

#include "codec/api/api_volume_options.h"
#include "codec/image/image_stream.h"
#include "codec/image/transfer.h"

namespace pupwave::api {
namespace {

// A number as every message prints it (%.6g).
std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

}  // namespace

std::string image_target_miss(ImageRate rate, double target, const TargetOutcome& outcome,
                              std::span<const std::uint8_t> stream, std::string_view subject) {
  if (outcome.met) return "";
  const StreamHeader header = parse_container(stream).header;
  const std::string who(subject);
  if (rate == ImageRate::psnr)
    return "--psnr " + number(target) + " not met: " + who + " reaches " + metric_name(header.transfer) +
           " " + number(outcome.achieved) + " dB";
  const std::size_t width = header.dims[0], height = header.dims[1];
  std::string text = "--bpp " + number(target) + " not met: " + who + " is " + std::to_string(stream.size()) +
                     " bytes (" + number(outcome.achieved) + " bpp) for this " + std::to_string(width) + "x" +
                     std::to_string(height) + " image";
  // What the stream holds before any coded data, said where it alone exceeds the budget: why a
  // tiny image cannot meet it.
  const std::size_t framing = container_size(header, 0, 0);
  if (8.0 * double(framing) > target * double(width * height))
    text += "; its header and chunk framing alone take " + std::to_string(framing) + " bytes";
  return text;
}

std::string volume_target_miss(VolumeRate rate, double target, const TargetOutcome& outcome,
                               std::size_t stream_bytes, std::string_view subject) {
  if (outcome.met) return "";
  const std::string who(subject);
  switch (rate) {
    case VolumeRate::automatic:  // misses only as the relative bound it codes floats to
      return volume_target_miss(VolumeRate::max_error_rel, kDefaultRelativeError, outcome, stream_bytes,
                                subject);
    case VolumeRate::bpv:
      return "--bpv " + number(target) + " not met: " + who + " is " + std::to_string(stream_bytes) +
             " bytes (" + number(outcome.achieved) + " bpv)";
    case VolumeRate::psnr:
      return "--psnr " + number(target) + " not met: " + who + " reaches PSNR " + number(outcome.achieved) +
             " dB";
    default:
      return "error bound " + number(target) + " not met: " + who + " has a largest error of " +
             number(outcome.achieved);
  }
}

}  // namespace pupwave::api
