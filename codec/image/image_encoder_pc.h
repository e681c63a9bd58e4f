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
EncodeResult encode_pc(const ImageView& image, ImagePlan& plan, const EncodeOptions& options);

// Coding passes (whole-image ones) of the last encode_pc on the calling thread: the rate
// search's cost, for tests and bench/pc_cpu_bench.
int pc_passes_of_last_encode();
// Trims (codings of a few finest bands, about a quarter of a pass each) of the last encode_pc.
int pc_trims_of_last_encode();
// Samples coded by the passes of the last encode_pc abandoned before their end (not counted by
// pc_passes_of_last_encode), in whole passes.
double pc_abandoned_share_of_last_encode();

}  // namespace pupwave
