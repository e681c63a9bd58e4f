#pragma once
// encode_image with the lossless context coder (`--entropy lc`, codec/entropy/lc_blocks.h).

#include "codec/image/image_plan.h"

namespace pupwave {

// Block extent the lc coder is planned with: the largest the format allows, so a band of up to
// 1024 x 1024 is one block and its models learn over the whole band.
inline constexpr Extent kLcBlockSize{1024, 1024, 1};

// Codes every block of a reversible plan (planned with kLcBlockSize) with the lc coder, one
// component transformed at a time.
EncodeResult encode_lc(const ImageView& image, ImagePlan& plan);

}  // namespace pupwave
