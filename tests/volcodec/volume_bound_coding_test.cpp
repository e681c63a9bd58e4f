// Max-error coding: the encoder predicts the decoder's reconstruction from the
// quantized coefficients without decoding (requantize_brick), picks a step per brick from a
// size model, and codes bricks in parallel. Checked here: that prediction is bit-exact for
// every irreversible transform and stored type, streams do not depend on the thread count,
// and on real data (wmag91) the bound holds on every voxel, is nearly used, and the ratio stays
// 5% above SPERR's published figures.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "codec/volume/volume_brick.h"
#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_outliers.h"
#include "transforms/separable.h"
#include "transforms/spec.h"
#include "volcodec/volcodec_test_util.h"

namespace pupwave {
namespace {

// The decoder's level-0 reconstruction of a brick coded with every pass of every block.
std::vector<double> decoded(const BrickCoding& c, std::span<const float> coef, const Extent& size,
                            double base) {
  const CodedBrick coded = code_coefficients(c, coef, size, base);
  std::vector<BlockEntry> entries;
  std::vector<std::vector<std::uint8_t>> words;
  for (const EncodedBlock& b : coded.coded) {
    const int passes = b.pass_count();
    entries.push_back({passes > 0 ? b.planes : 0, passes, std::uint32_t(b.size(passes))});
    words.push_back(b.codeword(passes));
  }
  std::vector<std::span<const std::uint8_t>> spans(words.begin(), words.end());
  return decode_brick(c, size, base, entries, spans, 0);
}

TEST(VolumeBoundCoding, RequantizedBrickEqualsTheDecodedBrickBitForBit) {
  const Volume v = test::smooth_volume({19, 16, 11}, VoxelType::f32, 50.0, 5);
  for (const std::string& spec : transform_specs()) {
    const auto t = make_transform(spec);
    if (t->is_reversible()) continue;  // lossless coding never takes this path
    // Rate modes' offset, the dead zone at the midpoint, and max-error mode's rounding quantizer,
    // through both block coders.
    const std::pair<double, float> quantizers[] = {{0.4375, 0.0f}, {0.5, 0.0f}, {0.125, 0.375f}};
    for (const auto& [delta, rounding] : quantizers)
      for (const bool coef_coder : {false, true}) {
        BrickCoding c{t.get(), default_levels(v.dims), 16, delta, false, coef_coder};
        c.rounding = rounding;
        const std::vector<float> coef = analyze_brick(c, v.samples, v.dims);
        for (double base : {0.003, 0.05, 0.9}) {
          std::vector<float> predicted;
          IndexStats stats;
          requantize_brick(c, coef, v.dims, base, predicted, &stats);
          const std::vector<double> reference = decoded(c, coef, v.dims, base);
          ASSERT_EQ(predicted.size(), reference.size());
          // Bit patterns, not values: the outlier search relies on the very same floats.
          std::size_t differing = 0;
          for (std::size_t i = 0; i < predicted.size(); ++i) {
            const double p = predicted[i];
            differing += std::memcmp(&p, &reference[i], sizeof p) != 0;
          }
          EXPECT_EQ(differing, 0u) << spec << " base " << base << " rounding " << rounding << " coef "
                                   << coef_coder;
          EXPECT_GT(stats.significant, 0.0) << spec << " base " << base;
        }
      }
  }
}

TEST(VolumeBoundCoding, Wmag91StreamsAreThreadCountFreeAndBeatSperrByFivePercent) {
  VolumeGrid g;
  g.name = "wmag91";
  g.volume = test::read_wmag91();
  const double range = test::range_of(g.volume);
  // SPERR's ratios on wmag91 at these bounds (20.97, 6.92; /work/shared/data/README.md) x 1.05.
  const std::pair<double, double> cases[] = {{1e-2, 22.0}, {1e-3, 7.27}};
  for (const auto& [rel, least_ratio] : cases) {
    VolumeEncodeOptions o;
    o.target = rel * range;
    o.executor = &serial_executor();
    const auto serial = encode_volumes({g}, o);
    for (unsigned threads : {2u, 5u}) {
      const auto pool = make_pool_executor(threads);
      o.executor = pool.get();
      EXPECT_EQ(encode_volumes({g}, o).bytes, serial.bytes) << rel << " threads " << threads;
    }
    const auto out = decode_volumes(serial.bytes);
    const double worst = test::worst_error(g.volume, out[0].volume);
    EXPECT_LE(worst, o.target) << rel;
    EXPECT_GE(worst, 0.9 * o.target) << rel << ": the bound is not used";
    EXPECT_GE(double(g.volume.count() * 4) / double(serial.bytes.size()), least_ratio) << rel;
  }
}

TEST(VolumeBoundCoding, IntegerVolumesHoldTheBoundAfterRounding) {
  for (VoxelType type : {VoxelType::u8, VoxelType::u16}) {
    VolumeGrid g;
    g.name = "ints";
    g.volume = test::smooth_volume({33, 20, 17}, type, type == VoxelType::u8 ? 255.0 : 65535.0, 7);
    VolumeEncodeOptions o;
    o.target = (type == VoxelType::u8 ? 255.0 : 65535.0) * 1e-2;
    o.brick = 16;
    const auto out = decode_volumes(encode_volumes({g}, o).bytes);
    EXPECT_LE(test::worst_error(g.volume, out[0].volume), o.target);
  }
}

}  // namespace
}  // namespace pupwave
