#pragma once
// encode_image with the high-throughput block coder (`--entropy ht`, codec/entropy/ht_blocks.h).

#include <cstddef>
#include <limits>

#include "codec/image/image_plan.h"

namespace pupwave {

// Encodes with the ht coder: one codeword per block, rate control by the quantizer steps
// (image_encoder_ht.cpp). A lossless encode whose codewords exceed `byte_limit`, or whose
// first blocks project twice that, stops early and returns an empty result (bytes empty).
EncodeResult encode_ht(const ImageView& image, ImagePlan& plan, const EncodeOptions& options,
                       std::size_t byte_limit = std::numeric_limits<std::size_t>::max());

}  // namespace pupwave
