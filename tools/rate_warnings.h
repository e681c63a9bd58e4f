#pragma once
// What `pupwave compress` says when the stream misses the rate target the user gave (a tiny
// image's header alone can exceed a --bpp budget): one `warning:` line on stderr
// giving the target and what the stream reached, or with --strict an error before anything is
// written. A met target says nothing.

#include <string>

#include "codec/image/image_codec.h"
#include "codec/volume/volume_codec.h"

namespace pupwave::cli {

// How an image stream misses its target, in the library's words (api::image_target_miss:
// "--bpp 1 not met: SUBJECT is 110 bytes (220 bpp) for this 2x2 image; ..."), with `subject`
// naming the stream; "" when the target is met.
std::string image_target_miss(const EncodeOptions& enc, const EncodeResult& r, const std::string& subject);

// The same for a volume stream ("--bpv 1 not met: SUBJECT is 70 bytes (70 bpv)"); an error
// bound is said in sample units, as the encoder holds it.
std::string volume_target_miss(const VolumeEncodeOptions& enc, const VolumeEncodeResult& r,
                               const std::string& subject);

// How a message names the stream written to `output`: the path, or "the stream" for stdout.
std::string stream_subject(const std::string& output);

// With `strict`, a miss (`missed` not empty, subject "the stream") throws
// std::runtime_error("MISSED; OUTPUT not written (--strict)"). Called before the output is put
// in place (or any byte goes to stdout), so an existing file stays as it was.
void refuse_if_strict(bool strict, const std::string& missed, const std::string& output);

// Prints "warning: MISSED" on stderr when `missed` is not empty (--quiet too: a missed target
// is never silent).
void warn_if_missed(const std::string& missed);

}  // namespace pupwave::cli
