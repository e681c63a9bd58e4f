// The outlier list coder (codec/volume/volume_outliers.*, stream version 6): exact round trips of
// lists of every density and correction size, including the one-outlier list whose range-coded
// codeword is empty before the encoder pads it, and bounded refusal of corrupt lists.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "codec/error.h"
#include "codec/volume/volume_outliers.h"

namespace pupwave {
namespace {

void expect_round_trip(const std::vector<Outlier>& list, std::size_t count) {
  const std::vector<std::uint8_t> bytes = encode_outliers(list);
  ASSERT_FALSE(bytes.empty());  // empty means "no outliers" to the decoder
  const std::vector<Outlier> back = decode_outliers(bytes, count);
  ASSERT_EQ(back.size(), list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    EXPECT_EQ(back[i].index, list[i].index) << i;
    EXPECT_EQ(back[i].k, list[i].k) << i;
  }
}

TEST(VolumeOutliers, EmptyListCodesToNoBytes) {
  EXPECT_TRUE(encode_outliers({}).empty());
  EXPECT_TRUE(decode_outliers({}, 100).empty());
}

TEST(VolumeOutliers, SingleOutliersRoundTrip) {
  for (std::uint32_t index : {0u, 1u, 7u, 4095u, 262143u})
    for (std::int64_t k : {std::int64_t(1), std::int64_t(-1), std::int64_t(2), std::int64_t(-9),
                           std::int64_t(1000), -(std::int64_t(1) << 52)})
      expect_round_trip({{index, k}}, 262144);
}

TEST(VolumeOutliers, ListsOfEveryDensityRoundTrip) {
  std::mt19937 rng(5);
  for (double density : {0.001, 0.04, 0.3, 1.0}) {
    std::vector<Outlier> list;
    const std::size_t count = 64 * 64 * 64;
    for (std::uint32_t i = 0; i < count; ++i) {
      if (double(rng() % 100000) >= density * 100000.0) continue;
      std::int64_t k = 1 + (rng() % 4 == 0 ? std::int64_t(rng() % 50) : 0);
      list.push_back({i, rng() % 2 ? k : -k});
    }
    expect_round_trip(list, count);
  }
}

TEST(VolumeOutliers, ACompressibleListCostsFewBytesPerOutlier) {
  // 4% of the voxels, |k| = 1: position entropy ~6 bits and a sign bit per outlier.
  std::mt19937 rng(9);
  std::vector<Outlier> list;
  for (std::uint32_t i = 0; i < 64 * 64 * 64; ++i)
    if (rng() % 25 == 0) list.push_back({i, rng() % 2 ? 1 : -1});
  const double bits = 8.0 * double(encode_outliers(list).size()) / double(list.size());
  EXPECT_LT(bits, 7.6);
  EXPECT_GT(bits, 6.5);  // below the entropy would mean a broken measurement
}

TEST(VolumeOutliers, CorruptListsDecodeInBoundsOrAreRefused) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<std::uint8_t> bytes(1 + rng() % 40);
    for (auto& b : bytes) b = std::uint8_t(rng());
    const std::size_t count = 1 + rng() % 600;
    try {
      const std::vector<Outlier> list = decode_outliers(bytes, count);
      ASSERT_LE(list.size(), count);
      for (std::size_t i = 0; i < list.size(); ++i) {
        ASSERT_LT(list[i].index, count);
        ASSERT_NE(list[i].k, 0);
        if (i > 0) ASSERT_GT(list[i].index, list[i - 1].index);
      }
    } catch (const DecodeError&) {
    }
  }
}

}  // namespace
}  // namespace pupwave
