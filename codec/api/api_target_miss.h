#pragma once
// Internal to the library, the CLI and the Python module (not installed): the one wording of a
// missed rate target, which the CLI prints as its `warning:` line (or, with --strict, its error)
// and the Python module raises as PupwaveTargetWarning or PupwaveTargetError.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "pupwave/pupwave.hpp"

namespace pupwave::api {

// How an image stream misses its target: "--bpp 1 not met: SUBJECT is 110 bytes (220 bpp) for
// this 2x2 image; its header and chunk framing alone take 93 bytes" (that last part where the
// framing alone exceeds the budget) or "--psnr 50 not met: SUBJECT reaches PSNR 41.2 dB" (the
// stream's metric: log-PSNR for half/float images); "" when outcome.met. `rate` and `target` are
// what compress_image was given, `stream` what it returned; `subject` names the stream.
std::string image_target_miss(ImageRate rate, double target, const TargetOutcome& outcome,
                              std::span<const std::uint8_t> stream, std::string_view subject);

// The same for a volume stream of `stream_bytes` bytes: "--bpv 1 not met: SUBJECT is 70 bytes
// (70 bpv)", "--psnr 60 not met: SUBJECT reaches PSNR 52.1 dB", or for an error bound (every
// other rate) "error bound TARGET not met: SUBJECT has a largest error of ACHIEVED", in the unit
// the caller gives `target` and outcome.achieved in (automatic: the relative bound it codes
// floats to, kDefaultRelativeError, whatever `target`); "" when outcome.met.
std::string volume_target_miss(VolumeRate rate, double target, const TargetOutcome& outcome,
                               std::size_t stream_bytes, std::string_view subject);

}  // namespace pupwave::api
