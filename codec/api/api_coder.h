#pragma once
// Internal to the library: the public Coder (pupwave/pupwave.hpp) as the codec's
// EntropyCoder, from the one table of coders in api_coder.cpp.

#include <optional>

#include "codec/image/image_stream.h"
#include "pupwave/pupwave.hpp"

namespace pupwave::api {

// The coder a stream is written with; nullopt for Coder::automatic, the default choice
// (encode_image_default_coder). Throws Error for a value that is not a Coder.
std::optional<EntropyCoder> entropy_coder(Coder coder);

}  // namespace pupwave::api
