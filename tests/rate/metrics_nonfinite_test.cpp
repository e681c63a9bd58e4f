// PSNR of images holding NaN and infinite samples (coded exactly with --keep-nonfinite): the
// same non-finite value back is exact, so the finite samples still get a PSNR against the
// range of the finite samples; a non-finite sample not given back is an infinite error.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "codec/image/image_codec.h"
#include "codec/image/image_metrics.h"
#include "tools/image_io.h"

namespace pupwave {
namespace {

TEST(MetricsNonFinite, KeptNonFiniteSamplesLeaveTheFinitePsnr) {
  const Image original = cli::read_image(std::string(PUPWAVE_TESTIMAGES_DIR) + "/forest_hdr.exr");
  ASSERT_EQ(original.type, SampleType::f16);
  const double finite_peak = psnr_peak(original);
  Image image = original;
  const std::size_t plane = image.plane_size();
  image.samples[17] = std::numeric_limits<float>::quiet_NaN();
  image.samples[plane + 4000] = std::numeric_limits<float>::infinity();
  image.samples[2 * plane + 9000] = -std::numeric_limits<float>::infinity();
  EXPECT_DOUBLE_EQ(psnr_peak(image), finite_peak);  // none of the three was the min or max

  EncodeOptions o;
  o.keep_nonfinite = true;
  const Image decoded = decode_image(encode_image(image, o).bytes);
  ASSERT_TRUE(std::isnan(decoded.samples[17]));
  const ImageError kept = compare_images(image, decoded);
  EXPECT_TRUE(std::isfinite(kept.overall.psnr)) << kept.overall.psnr;
  EXPECT_GT(kept.overall.psnr, 60.0);
  EXPECT_TRUE(std::isfinite(kept.luma.psnr)) << kept.luma.psnr;
  for (const ChannelError& c : kept.channels) EXPECT_TRUE(std::isfinite(c.max_abs));

  Image lost = decoded;  // a decoder that dropped the side list would give a finite value
  lost.samples[2 * plane + 9000] = 0.0f;
  const ImageError e = compare_images(image, lost);
  EXPECT_TRUE(std::isinf(e.channels[2].mse));
  EXPECT_EQ(e.overall.psnr, -std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isinf(e.channels[2].max_abs));
  EXPECT_DOUBLE_EQ(e.channels[0].psnr, kept.channels[0].psnr);  // other channels unchanged
}

}  // namespace
}  // namespace pupwave
