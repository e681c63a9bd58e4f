#pragma once
// The modern anchors of the rate-distortion harness: AVIF (avifenc, libaom), HEVC intra (ffmpeg
// with libx265) and WebP (cwebp), each driven to the target rate by bisecting its quantiser.

#include <filesystem>

#include "tools/bench/codecs.h"

namespace pupwave::bench {

// AVIF 4:4:4 (4:0:0 for grey), libaom at `speed` (named "avif" at speed 4, else "avif-sN"), one
// quantiser for all planes (--min Q --max Q). ffmpeg converts PPM/PGM to and from the PNG
// avifenc/avifdec read and write.
RdCodecPtr make_avif_anchor(const std::filesystem::path& avifenc, const std::filesystem::path& avifdec,
                            const std::filesystem::path& ffmpeg, int speed);

// HEVC intra: one frame through libx265, preset slow, tune psnr, fixed QP, full-range 4:4:4
// (yuvj444p; gray for grey images), raw Annex B stream.
RdCodecPtr make_hevc_anchor(const std::filesystem::path& ffmpeg);

// WebP (lossy, VP8: always 4:2:0, so grey images are coded as RGB), cwebp -q Q -m 6;
// dwebp writes PPM, which ffmpeg turns to PGM for grey images.
RdCodecPtr make_webp_anchor(const std::filesystem::path& cwebp, const std::filesystem::path& dwebp,
                            const std::filesystem::path& ffmpeg);

}  // namespace pupwave::bench
