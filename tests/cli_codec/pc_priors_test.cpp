// The pc coder's trained start states (codec/entropy/pc_priors.h, stream version 6): every band
// class of an image has its own, the trained starts are probabilities (a silent neighbourhood's
// zero likely), a block decodes only from the starts it was coded with and codes shorter from
// them than from flat models, and the test photographs round-trip at several rates.
#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "codec/entropy/pc_blocks.h"
#include "codec/entropy/pc_cfl.h"
#include "codec/entropy/pc_groups.h"
#include "codec/entropy/pc_priors.h"
#include "codec/error.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_metrics.h"
#include "codec/image/image_stream.h"
#include "codec/image/lc_parent.h"
#include "photo_crops.h"
#include "transforms/separable.h"

namespace pupwave {
namespace {

using test::photo;

TEST(PcPriors, EveryBandOfASixLevelColourImageHasItsOwnClass) {
  const std::vector<Subband> bands = subbands(Extent{512, 512, 1}, 6);
  std::set<int> luma, chroma;
  for (const Subband& band : bands) {
    const int y = pc_prior_class(band, 0, 3);
    EXPECT_EQ(pc_prior_class(band, 1, 3), pc_prior_class(band, 2, 3));  // Cb and Cr share
    EXPECT_EQ(pc_prior_class(band, 0, 1), y);                           // grey takes luma's
    EXPECT_EQ(pc_prior_class(band, 1, 2), y);                           // so does a second of two
    luma.insert(y);
    chroma.insert(pc_prior_class(band, 1, 3));
  }
  EXPECT_EQ(luma.size(), bands.size());
  EXPECT_EQ(chroma.size(), bands.size());
  EXPECT_EQ(luma.size() + chroma.size(), std::size_t(kPcPriorClasses));
  for (const std::set<int>& s : {luma, chroma})
    for (const int c : s) {
      EXPECT_GE(c, 0);
      EXPECT_LT(c, kPcPriorClasses);
      EXPECT_EQ(chroma.count(c) + luma.count(c), 1u);
    }
  // Levels above 6 share level 6's classes.
  const std::vector<Subband> deep = subbands(Extent{2048, 2048, 1}, 8);
  for (const Subband& band : deep) {
    if (band.level != 8 || band.orientation == 0) continue;
    for (const Subband& six : bands) {
      if (six.level == 6 && six.orientation == band.orientation) {
        EXPECT_EQ(pc_prior_class(band, 0, 3), pc_prior_class(six, 0, 3));
      }
    }
  }
}

TEST(PcPriors, TrainedStartsAreProbabilitiesAndASilentZeroIsLikely) {
  for (int c = 0; c < kPcPriorClasses; ++c) {
    const PcModels& m = pc_prior_models(c);
    int trained = 0;
    pc_each_model(m, [&](const PcBit& b) {
      if (b.count == 0) {
        EXPECT_EQ(b.p0, kProbabilityOne / 2) << "class " << c;  // untrained: flat
        return;
      }
      ++trained;
      EXPECT_EQ(b.count, kPcPriorCount);
      EXPECT_GT(b.p0, 0u);
      EXPECT_LT(b.p0, kProbabilityOne);
    });
    EXPECT_GT(trained, 100) << "class " << c;
    for (const PcBit& b : m.unary[0]) EXPECT_EQ(b.max_shift, PcModels::kSilentShift);
    // In the two finest levels' bands, activity class 0 (no non-zero neighbour or parent): a
    // zero index is likely.
    if (c < 12) {
      EXPECT_GT(double(m.unary[0][0].p0) / kProbabilityOne, 0.8) << "class " << c;
    }
  }
  EXPECT_THROW((void)pc_prior_models(kPcPriorClasses), std::out_of_range);
}

// Every block of a photograph's stream decoded (parents and luma first, the stream's order) from
// its class's starts: coded again from them it gives the stream's codeword, from flat starts the
// photograph's blocks take more bytes, and decoded from flat or another class's starts a
// parentless block is refused or decodes to other indices.
TEST(PcPriors, ABlockDecodesOnlyFromTheStartsItWasCodedWith) {
  for (const char* name : {"chelsea.png", "camera.png"}) {
    const EncodeResult r = encode_image(photo(name), test::pc_options(RateMode::bpp, 0.5));
    const ParsedStream s = parse_container(r.bytes);
    const Extent& dims = s.header.dims;
    std::vector<std::vector<std::int32_t>> index(s.header.channels,
                                                 std::vector<std::int32_t>(dims[0] * dims[1], 0));
    std::size_t trained = 0, flat = 0;
    int parentless = 0;
    for (std::size_t i = 0; i < s.blocks.size(); ++i) {
      const CodeBlock& b = s.blocks[i];
      if (s.index[i].passes == 0) continue;
      const std::size_t w = b.size[0], h = b.size[1];
      const int cls = pc_prior_class(s.bands[b.band], b.component, s.header.channels);
      const PcModels& own = pc_prior_models(cls);
      std::int32_t* plane = index[b.component].data();
      const LcParent parent = lc_parent(s.bands, b, plane, dims[0], nullptr);
      const PcLuma luma = pc_luma(b, index, dims[0]);
      std::vector<std::int32_t> q(w * h);
      PcCfl cfl;  // a chroma block's weights head its codeword
      cfl.count = pc_cfl_applies(b, s.header.channels) ? pc_cfl_count(b) : 0;
      PcCfl* weights = cfl.count ? &cfl : nullptr;
      pc_decode_block(s.codeword(i), s.index[i].planes, w, h, parent, q.data(), w, luma, weights, &own);
      copy_block_in(q.data(), dims, b, plane);
      const auto word = s.codeword(i);
      std::vector<std::int32_t> copy = q;
      EXPECT_EQ(pc_encode_block(copy, w, h, parent, nullptr, luma, weights, &own).bytes,
                std::vector<std::uint8_t>(word.begin(), word.end()))
          << name << " block " << i;
      copy = q;
      flat += pc_encode_block(copy, w, h, parent, nullptr, luma, weights).bytes.size();
      trained += word.size();
      if (parent.origin || luma.origin) continue;
      ++parentless;
      for (const PcModels* other :
           {static_cast<const PcModels*>(nullptr), &pc_prior_models((cls + 2) % 36)}) {
        std::vector<std::int32_t> wrong(w * h);
        try {
          pc_decode_block(word, s.index[i].planes, w, h, parent, wrong.data(), w, luma, nullptr, other);
          EXPECT_NE(wrong, q) << name << " block " << i;
        } catch (const DecodeError&) {
        }
      }
    }
    EXPECT_EQ(parentless, 4) << name;  // the coarse band and the three coarsest detail bands
    EXPECT_LT(double(trained), 0.99 * double(flat)) << name;  // 1.7% (camera at 0.5 bpp) to 2.5%
  }
}

TEST(PcPriors, PhotographsRoundTripAtSeveralRates) {
  for (const char* name : {"astronaut.png", "camera.png", "chelsea.png", "coffee.png"}) {
    const Image img = photo(name);
    for (const double bpp : {0.125, 0.5, 2.0}) {
      const EncodeResult r = encode_image(img, test::pc_options(RateMode::bpp, bpp));
      ASSERT_EQ(r.bytes[4], 6);  // stream version 6: trained starts
      EXPECT_LE(double(r.bytes.size()), bpp * double(img.width * img.height) / 8.0) << name << " " << bpp;
      // The encoder's PSNR is of its own indices: equal only if the decoder gets them all.
      EXPECT_NEAR(compare_images(img, decode_image(r.bytes)).overall.psnr, r.psnr, 1e-9)
          << name << " " << bpp;
    }
  }
}

}  // namespace
}  // namespace pupwave
