// Golden checksums of encoded streams. They pin the bitstream: any change to the container,
// the index, the block coder, the quantizer or the transforms it uses changes them. When a
// format change is deliberate, bump kStreamVersion, update docs/bitstream.md and these values.
// The --bpp stream also pins rate control (which base step and truncation points the encoder
// picks): an encoder-only change there updates its value without a version bump.
// Version 2 (transfer and flags bytes in HEAD, optional META/NFIN chunks) changed all five.
// Version 3 (the block coder's far-neighbour contexts and trained priors) changed all six.
// Version 4 (the priors retrained on other photographs, a weight per context) changed
// all six (the zstd one by its version byte only).
// The size-target encoder (base-step family per band, RDOQ) is effort 2 and has its own value.
// Entropy coder 4 (pc) has its own value: coder, RDOQ and its rate search.
// Version 5 (pc's luma and Cb parents, parent neighbours, faster silent models) changed the
// pc value and the six others by their version byte only.
// Version 6 (pc predicts chroma detail blocks from luma and Cb, and its models start
// from trained states per band class) changed the pc values and the six others by their version
// byte only.
#include <gtest/gtest.h>

#include "codec/format/crc32.h"
#include "codec/image/image_codec.h"
#include "test_images.h"

namespace pupwave {
namespace {

std::uint32_t stream_crc(const Image& img, RateMode mode, double target, const char* spec,
                         EntropyCoder coder = EntropyCoder::ebcot, int effort = 1) {
  EncodeOptions o;
  o.effort = effort;
  o.mode = mode;
  o.target = target;
  o.transform = spec;
  o.entropy = coder;
  return crc32(encode_image(img, o).bytes);
}

TEST(GoldenStream, LosslessStreamsAreUnchanged) {
  EXPECT_EQ(
      stream_crc(testing::synthetic_image(61, 47, 3, SampleType::u8, 21), RateMode::lossless, 0, "cdf53"),
      3512199539u);
  EXPECT_EQ(
      stream_crc(testing::synthetic_image(40, 33, 1, SampleType::u16, 22), RateMode::lossless, 0, "cdf53"),
      2456597352u);
}

TEST(GoldenStream, LossyStreamsAreUnchanged) {
  EXPECT_EQ(stream_crc(testing::synthetic_image(64, 64, 3, SampleType::u8, 24), RateMode::bpp, 1.0, "cdf97"),
            2474911351u);
  EXPECT_EQ(stream_crc(testing::synthetic_image(64, 64, 3, SampleType::u8, 24), RateMode::bpp, 1.0, "cdf97",
                       EntropyCoder::ebcot, 2),
            2585391441u);
  EXPECT_EQ(stream_crc(testing::synthetic_image(50, 30, 1, SampleType::u8, 25), RateMode::step, 4.0, "cdf53"),
            3500861292u);
}

// A --step stream pins the pc coder alone (no search): the same values before and after the
// model-guided search and in-place decoder (changed by version 5's contexts and
// version 6's chroma from luma and trained model starts; the RGB one by the encoder-only
// chroma-from-luma choice from pc_cfl_pays).
TEST(GoldenStream, PcStepStreamsAreUnchanged) {
  EXPECT_EQ(stream_crc(testing::synthetic_image(64, 64, 3, SampleType::u8, 24), RateMode::step, 4.0, "cdf97",
                       EntropyCoder::pc),
            2647769617u);
  EXPECT_EQ(stream_crc(testing::synthetic_image(61, 47, 1, SampleType::u8, 26), RateMode::step, 1.5, "cdf97",
                       EntropyCoder::pc),
            1687506337u);
}

TEST(GoldenStream, PcStreamIsUnchanged) {
  EXPECT_EQ(stream_crc(testing::synthetic_image(64, 64, 3, SampleType::u8, 24), RateMode::bpp, 1.0, "cdf97",
                       EntropyCoder::pc),
            139638909u);  // version 6; the steered search lands with the finest
                          // bands' steps moved from the base step's (the format is unchanged)
}

}  // namespace
}  // namespace pupwave
