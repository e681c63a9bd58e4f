#pragma once
// Internal to the library and the CLI (not installed): the one place where the public image
// options (api::ImageOptions) become the encoder's, so every front door (C++ and C APIs,
// Python, the OpenImageIO plugin, the CLI) codes the same image and options to the same bytes.

#include "codec/image/image_codec.h"
#include "pupwave/pupwave.hpp"

namespace pupwave::api {

// The encoder's options for `options`: rate mode and target, transform (cdf97; cdf53 for
// lossless), levels, coder and effort. Callers add what only they know (executor, metadata,
// measure_psnr, which is off here). Throws Error for a target or level out of range.
EncodeOptions resolve_image_options(const ImageOptions& options);

// Encodes with `coder`'s choice: Coder::automatic the default one (encode_image_default_coder,
// lc for lossless), any other exactly that coder (options.entropy, as resolve_image_options set
// it). Throws Error when the settings give a stream the decoder would reject.
EncodeResult encode_resolved(const pupwave::ImageView& view, const EncodeOptions& options, Coder coder);

}  // namespace pupwave::api
