// The pc coder's rate search (codec/image/image_encoder_pc.cpp with codec/image/pc_rate_model.h)
// and its in-place decoder on the test photographs: byte budgets met from below within half a
// percent in a few passes, trimmed streams decoding to the encoder's planes, the model near the
// real coder, and decode_pc_into equal, bit for bit, to decoding into separate index planes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "codec/entropy/pc_blocks.h"
#include "codec/entropy/pc_cfl.h"
#include "codec/entropy/pc_groups.h"
#include "codec/entropy/pc_priors.h"
#include "codec/image/encode_stats.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_metrics.h"
#include "codec/image/image_plan.h"
#include "codec/image/image_stream.h"
#include "codec/image/image_view.h"
#include "codec/image/lc_parent.h"
#include "codec/image/pc_decoder.h"
#include "codec/image/pc_rate_model.h"
#include "photo_crops.h"
#include "transforms/executor.h"
#include "transforms/separable.h"

namespace pupwave {
namespace {

using test::crop;
using test::photo;

const char* const kPhotos[] = {"astronaut.png", "camera.png", "chelsea.png", "coffee.png"};

// A pc encode's options (photo_crops.h).
EncodeOptions pc(RateMode mode, double target) { return test::pc_options(mode, target); }

// The same, adding the encode's statistics to `stats`.
EncodeOptions pc(RateMode mode, double target, EncodeStats& stats) {
  EncodeOptions o = pc(mode, target);
  o.stats = &stats;
  return o;
}

TEST(PcRate, BudgetsAreMetWithinHalfAPercentInAFewPasses) {
  int passes = 0, searches = 0, trimmed = 0;
  for (const char* name : kPhotos) {
    const Image img = photo(name);
    for (double bpp : {0.125, 0.25, 0.5, 1.0, 2.0}) {
      EncodeStats stats;
      const EncodeResult r = encode_image(img, pc(RateMode::bpp, bpp, stats));
      const double budget = std::floor(bpp * double(img.plane_size()) / 8.0);
      EXPECT_LE(double(r.bytes.size()), budget) << name << " at " << bpp;
      EXPECT_GE(double(r.bytes.size()), 0.995 * budget) << name << " at " << bpp;
      // The encoder's PSNR comes from its planes (a trimmed pass's too): the decoder's image.
      EXPECT_NEAR(compare_images(img, decode_image(r.bytes)).overall.psnr, r.psnr, 1e-9)
          << name << " at " << bpp;
      // At 0.125 bpp the bytes jump by up to 1% between steps 0.1% apart (RDOQ choices flipping), so
      // landing in the window can take a search 6 passes (camera with RDOQ's neighbour term).
      EXPECT_LE(stats.pc_passes, 6) << name << " at " << bpp;
      passes += stats.pc_passes;
      trimmed += stats.pc_trims > 0;
      ++searches;
    }
  }
  // The secant alone takes 3.9 passes a search here; the calibrated model about 2.1.
  EXPECT_LE(double(passes) / searches, 2.6);
  EXPECT_GT(trimmed, 0);  // the trim path is exercised
}

// The search's cost on the test photographs, in coding passes: whole passes, the share of the
// samples coded by passes abandoned before their finest groups, and trims (a quarter of the
// samples each). A run measured 1.75 passes + 0.21 abandoned + 0.50 trims a search (2.08
// passes' worth) where the per-level prior scales without abandoning take 2.25 + 0.40 trims (2.35).
// The steered search (codec/image/image_encoder_pc.cpp) lands most budgets with one whole pass:
// 1.41 pass-equivalents on these photographs, a trim counted as the third of the samples it codes
// at most (the search without the steering takes 2.1).
TEST(PcRate, SearchesCostUnderOneAndSixTenthsPasses) {
  int passes = 0, trims = 0, searches = 0;
  double abandoned = 0.0;
  for (const char* name : kPhotos) {
    const Image img = photo(name);
    for (double bpp : {0.125, 0.25, 0.5, 1.0, 2.0}) {
      EncodeStats stats;
      encode_image(img, pc(RateMode::bpp, bpp, stats));
      passes += stats.pc_passes;
      trims += stats.pc_trims;
      abandoned += stats.pc_abandoned_share;
      EXPECT_LT(stats.pc_abandoned_share, 0.5)
          << name << " at " << bpp;  // at most two, each before a quarter of the samples
      ++searches;
    }
  }
  EXPECT_GT(abandoned, 0.0);  // the abandoning path is exercised
  EXPECT_GT(trims, 0);        // and the trims
  EXPECT_LE(double(passes) / searches, 1.25);
  EXPECT_LE((double(passes) + abandoned + double(trims) / 3.0) / searches, 1.6);
}

TEST(PcRate, PsnrTargetsTakeAboutTwoPasses) {
  int passes = 0;
  for (const char* name : {"astronaut.png", "coffee.png"})
    for (double target : {32.0, 38.0}) {
      const Image img = photo(name);
      EncodeStats stats;
      const EncodeResult r = encode_image(img, pc(RateMode::psnr, target, stats));
      EXPECT_GE(r.psnr, target) << name;
      EXPECT_LE(r.psnr, target + 0.05) << name;
      passes += stats.pc_passes;
    }
  EXPECT_LE(passes, 10);
}

// A photograph's plan with every component transformed (the view and the image outlive it).
struct Planned {
  ImageView view;
  ImagePlan plan;
  explicit Planned(const Image& img) : view(view_of(img)), plan(plan_image(view, pc(RateMode::step, 1.0))) {
    transform_all_components(plan);
  }
};

TEST(PcRate, ModelFallsWithTheStepAndSitsNearTheCoder) {
  for (const char* name : {"camera.png", "coffee.png"}) {
    const Image img = photo(name);
    Planned p(img);
    const PcRateModel model(p.plan, 0.05);
    double last_bits = INFINITY, last_error = 0.0;
    for (double step = 2.0; step <= 64.0; step *= 2.0) {  // finer rounds back to the 8-bit image
      const double bits = model.bits(step), error = model.squared_error(step);
      EXPECT_LT(bits, last_bits) << name << " step " << step;
      EXPECT_GT(error, last_error) << name << " step " << step;
      last_bits = bits;
      last_error = error;
      // The real coder (contexts, RDOQ) spends 0.6-1.1 of the zero-order estimate.
      const EncodeResult r = encode_image(img, pc(RateMode::step, step));
      const double ratio = double(r.bytes.size()) / (bits / 8.0);
      EXPECT_GT(ratio, 0.6) << name << " step " << step;
      EXPECT_LT(ratio, 1.1) << name << " step " << step;
      const double psnr = 10.0 * std::log10(p.plan.peak * p.plan.peak * double(p.plan.samples) / error);
      EXPECT_NEAR(psnr, r.psnr, 1.0) << name << " step " << step;
    }
    EXPECT_EQ(model.bits(p.plan.peak * 1024.0), 0.0);  // every index zero
  }
}

// The density-shaped estimate (the coder's ratio to the zero-order model by bits per sample):
// under the zero-order bits, and a smaller share of them in a sparse band than in a dense one.
TEST(PcRate, CodedEstimateFallsFurthestBelowTheModelInSparseBands) {
  const Image img = photo("coffee.png");
  Planned p(img);
  const PcRateModel model(p.plan, 0.05);
  const std::size_t finest = 3;  // luma HL of level 1 (bands: coarse, then coarsest to finest)
  ASSERT_EQ(p.plan.bands[p.plan.bands.size() - 1].level, 1);
  const std::size_t k = p.plan.bands.size() - finest;
  double last_share = 0.0;
  for (double step = 64.0; step >= 1.0; step /= 4.0) {  // sparse to dense
    const double bits = model.bits_of_band(k, step), coded = model.coded_bits_of_band(k, step);
    ASSERT_GT(bits, 0.0) << step;
    EXPECT_LT(coded, bits) << step;
    EXPECT_GT(coded / bits, last_share) << step;
    last_share = coded / bits;
  }
  EXPECT_GT(last_share, 0.6);  // dense: near the zero-order estimate
}

// decode_pc_into's reference: every resolution into int32 index planes, then dequantized into
// separate float planes (the decoder before it dequantized in place), each chroma detail
// sample plus its weights x the decoded luma (and Cb) sample, as docs/bitstream.md writes it.
// `predicted`: the blocks with a nonzero weight.
std::vector<std::vector<float>> decode_by_index_planes(const ParsedStream& s, const Extent& region,
                                                       int* predicted = nullptr) {
  const std::size_t n = region[0] * region[1];
  std::vector<std::vector<std::int32_t>> index(s.header.channels, std::vector<std::int32_t>(n, 0));
  std::vector<std::vector<float>> out(s.header.channels, std::vector<float>(n, 0.0f));
  std::vector<PcCfl> weights(s.blocks.size());
  // Blocks come resolution by resolution, components in order: parents, luma and Cb first.
  for (std::size_t i = 0; i < s.blocks.size(); ++i) {
    const CodeBlock& b = s.blocks[i];
    if (s.index[i].passes == 0) continue;
    std::int32_t* plane = index[b.component].data();
    weights[i].count = pc_cfl_applies(b, s.header.channels) ? pc_cfl_count(b) : 0;
    pc_decode_block(s.codeword(i), s.index[i].planes, b.size[0], b.size[1],
                    lc_parent(s.bands, b, plane, region[0], nullptr),
                    plane + b.offset[0] + region[0] * b.offset[1], region[0], pc_luma(b, index, region[0]),
                    weights[i].count ? &weights[i] : nullptr,
                    &pc_block_priors(s.bands, b, s.header.channels));
  }
  for (std::size_t i = 0; i < s.blocks.size(); ++i) {  // a band's luma and Cb blocks before its Cr's
    const CodeBlock& b = s.blocks[i];
    pc_dequantize_block(b, index[b.component].data(), out[b.component].data(), region[0],
                        s.header.steps[b.component * s.bands.size() + b.band], float(s.header.delta));
    const PcCfl& k = weights[i];
    if (predicted && !pc_cfl_none(k)) ++*predicted;
    for (std::size_t y = 0; y < b.size[1] && k.count > 0; ++y)
      for (std::size_t x = 0; x < b.size[0]; ++x) {
        const std::size_t at = b.offset[0] + x + region[0] * (b.offset[1] + y);
        float p = float(k.code[0]) * (1.0f / 16) * out[0][at];
        if (k.count == 2) p += float(k.code[1]) * (1.0f / 16) * out[1][at];
        out[b.component][at] += p;
      }
  }
  return out;
}

TEST(PcRate, InPlaceDecodeEqualsDecodingIntoIndexPlanesAtEveryLevel) {
  const Image img = crop(photo("coffee.png"), 451, 299);
  const EncodeResult r = encode_image(img, pc(RateMode::bpp, 1.5));
  for (int level : {0, 1, 3}) {
    const ParsedStream s = parse_container(r.bytes, level);
    const Extent region = level_extent(s.header.dims, level);
    std::vector<std::vector<float>> planes(s.header.channels,
                                           std::vector<float>(region[0] * region[1], 0.0f));
    std::vector<float*> pointers;
    for (auto& p : planes) pointers.push_back(p.data());
    decode_pc_into(s, region, serial_executor(), pointers);
    int predicted = 0;
    const auto reference = decode_by_index_planes(s, region, &predicted);
    EXPECT_GE(predicted, 4) << "level " << level;  // chroma from luma in use (coffee's chroma follows luma)
    for (std::size_t c = 0; c < planes.size(); ++c)
      EXPECT_EQ(std::memcmp(planes[c].data(), reference[c].data(), planes[c].size() * sizeof(float)), 0)
          << "level " << level << " component " << c;
  }
}

}  // namespace
}  // namespace pupwave
