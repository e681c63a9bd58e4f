// --tune visual (codec/image/visual_weights.h) on the test photographs: it changes the coding
// (other bytes), scores higher by the harness's own perceptual measure (MS-SSIM, tools/bench/
// ssim.h) than --tune psnr at no larger size, and every rate target (--bpp budgets, --psnr
// targets in real PSNR) holds with every lossy coder in both modes.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "codec/image/image_codec.h"
#include "codec/image/image_metrics.h"
#include "codec/image/visual_weights.h"
#include "codec/rate/byte_budget.h"
#include "photo_crops.h"
#include "tools/bench/ssim.h"
#include "transforms/separable.h"

namespace pupwave {
namespace {

using test::photo;

EncodeOptions options(RateMode mode, double target, EntropyCoder coder, Tune tune) {
  EncodeOptions o;
  o.mode = mode;
  o.target = target;
  o.entropy = coder;
  o.tune = tune;
  return o;
}

TEST(VisualTune, WeightsFallWithFrequencyAndAreLowerForChroma) {
  const std::vector<Subband> bands = subbands({2560, 1600, 1}, 6);
  const std::vector<double> w = visual_weights(bands, 3, ColourTransform::ict);
  ASSERT_EQ(w.size(), 3 * bands.size());
  for (std::size_t b = 0; b < bands.size(); ++b) {
    EXPECT_GT(w[b], 0.0);
    EXPECT_LE(w[b], 1.0);
    EXPECT_LE(w[bands.size() + b], w[b]) << "Cb band " << b;
    if (bands[b].orientation == 0) EXPECT_EQ(w[b], 1.0);
  }
  // The finest luma details weigh least, and diagonal ones less than horizontal ones.
  double finest_hl = 0.0, finest_hh = 0.0, coarser_hl = 0.0;
  for (std::size_t b = 0; b < bands.size(); ++b) {
    if (bands[b].level == 1 && bands[b].orientation == 1) finest_hl = w[b];
    if (bands[b].level == 1 && bands[b].orientation == 3) finest_hh = w[b];
    if (bands[b].level == 3 && bands[b].orientation == 1) coarser_hl = w[b];
  }
  EXPECT_LT(finest_hl, 1.0);
  EXPECT_LT(finest_hh, finest_hl);
  EXPECT_LT(finest_hl, coarser_hl);
  // Without a luma/chroma transform every component is weighted as luma.
  const std::vector<double> grey = visual_weights(bands, 2, ColourTransform::none);
  for (std::size_t b = 0; b < bands.size(); ++b) EXPECT_EQ(grey[bands.size() + b], w[b]);
}

TEST(VisualTune, BeatsPsnrTuningInMsSsimAtTheSameSize) {
  for (const char* name : {"astronaut.png"}) {
    const Image img = photo(name);
    for (double bpp : {0.25, 1.0}) {
      const EncodeResult p =
          encode_image_default_coder(view_of(img), options(RateMode::bpp, bpp, {}, Tune::psnr));
      const EncodeResult v =
          encode_image_default_coder(view_of(img), options(RateMode::bpp, bpp, {}, Tune::visual));
      EXPECT_NE(p.bytes, v.bytes) << name << " at " << bpp;
      EXPECT_LE(double(v.bytes.size()), byte_budget(bpp, img.plane_size())) << name << " at " << bpp;
      EXPECT_LE(double(v.bytes.size()), double(p.bytes.size()) * 1.005) << name << " at " << bpp;
      const double ms_p = bench::ms_ssim(img, decode_image(p.bytes));
      const double ms_v = bench::ms_ssim(img, decode_image(v.bytes));
      EXPECT_GT(ms_v, ms_p) << name << " at " << bpp;
      // The squared error is what psnr tuning minimises: visual tuning gives some of it up.
      EXPECT_LT(v.psnr, p.psnr) << name << " at " << bpp;
    }
  }
}

TEST(VisualTune, RateTargetsHoldWithEveryLossyCoder) {
  const Image img = photo("chelsea.png");
  for (EntropyCoder coder : {EntropyCoder::pc, EntropyCoder::ebcot, EntropyCoder::ht})
    for (Tune tune : {Tune::psnr, Tune::visual}) {
      const std::string what = std::string(to_string(tune)) + " coder " + std::to_string(int(coder));
      const EncodeResult b = encode_image(img, options(RateMode::bpp, 0.5, coder, tune));
      EXPECT_TRUE(b.target_met) << what;
      EXPECT_LE(double(b.bytes.size()), byte_budget(0.5, img.plane_size())) << what;
      EXPECT_GE(double(b.bytes.size()), 0.97 * byte_budget(0.5, img.plane_size())) << what;
      const EncodeResult q = encode_image(img, options(RateMode::psnr, 34.0, coder, tune));
      const double real = compare_images(img, decode_image(q.bytes)).overall.psnr;
      EXPECT_GE(real, 34.0) << what;
      EXPECT_LE(real, 34.0 + 0.15) << what;  // kPsnrWithin
    }
}

}  // namespace
}  // namespace pupwave
