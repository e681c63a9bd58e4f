#pragma once
// encode_image with the parent-context coefficient coder (`--entropy pc`, entropy coder 4,
// codec/entropy/pc_blocks.h): lossy only, every band one block, greedy RDOQ while coding.

#include "codec/image/image_plan.h"

namespace pupwave {

// RDOQ slope (squared index-unit error per bit) and reconstruction offset, measured best by a
// rate-distortion estimate of non-embedded coders on the test photographs (coefp + RDOQ).
inline constexpr double kPcLambda = 0.1;
inline constexpr double kPcDelta = 0.05;

// Codes an irreversible plan (planned with kLcBlockSize) with the pc coder: --step in one pass,
// --bpp and --psnr by a search of the base step over whole coding passes.
// The rate search's cost (passes, trims, abandoned share) is added to plan.stats when there is one.
EncodeResult encode_pc(const ImageView& image, ImagePlan& plan, const EncodeOptions& options);

}  // namespace pupwave
