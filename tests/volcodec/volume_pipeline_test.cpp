// The encoder's and decoder's passes outside the block coder: the one-pass value
// summary of a view, the fused store-and-correct pass of the max-error encoder, the vectorised
// requantization's model statistics and the decoder's row writes each give exactly what
// plain per-voxel reference code (written here) gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "codec/volume/volume_brick.h"
#include "codec/volume/volume_outliers.h"
#include "codec/volume/volume_view.h"
#include "transforms/separable.h"
#include "transforms/spec.h"
#include "volcodec/volcodec_test_util.h"

namespace pupwave {
namespace {

// The per-voxel reference: min/max of the active voxels, finiteness and largest |value| of all.
ValueSummary reference_summary(const VolumeView& v) {
  ValueSummary s;
  s.lo = std::numeric_limits<double>::infinity();
  s.hi = -s.lo;
  for_each_voxel(v, [&](double x, bool active) {
    s.finite = s.finite && std::isfinite(x);
    s.largest = std::max(s.largest, std::fabs(x));
    if (active) s.lo = std::min(s.lo, x), s.hi = std::max(s.hi, x);
  });
  return s;
}

template <class T>
std::vector<T> random_values(std::size_t n, double lo, double hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<T> v(n);
  for (T& x : v) x = T(std::is_integral_v<T> ? std::round(u(rng)) : u(rng));
  return v;
}

template <class T>
void expect_summary_matches(VoxelType type, double lo, double hi) {
  for (const Extent dims : {Extent{1, 1, 1}, Extent{3, 2, 2}, Extent{9, 5, 3}, Extent{33, 4, 2}}) {
    const std::vector<T> data = random_values<T>(dims[0] * dims[1] * dims[2], lo, hi, unsigned(dims[0]));
    const VolumeView v = contiguous_view(data.data(), dims, type);
    const ValueSummary got = summarize_values(v), want = reference_summary(v);
    EXPECT_EQ(got.lo, want.lo) << to_string(type) << " " << dims[0];
    EXPECT_EQ(got.hi, want.hi) << to_string(type) << " " << dims[0];
    EXPECT_EQ(got.largest, want.largest) << to_string(type) << " " << dims[0];
    EXPECT_TRUE(got.finite);
  }
}

TEST(VolumePipeline, SummaryEqualsPerVoxelScanForEveryStorage) {
  expect_summary_matches<std::uint8_t>(VoxelType::u8, 0, 255);
  expect_summary_matches<std::uint16_t>(VoxelType::u16, 0, 65535);
  expect_summary_matches<float>(VoxelType::f32, -3.5, 7.25);
  expect_summary_matches<double>(VoxelType::f64, -1e6, 2.0);
}

TEST(VolumePipeline, SummaryFindsNonFiniteVoxelsAnywhereAndIgnoresNanInTheRange) {
  for (std::size_t at : {0u, 1u, 4u, 10u, 22u}) {
    for (const float bad :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
      std::vector<float> data = random_values<float>(23, -1.0, 1.0, 3);
      data[at] = bad;
      const ValueSummary s = summarize_values(contiguous_view(data.data(), {23, 1, 1}, VoxelType::f32));
      EXPECT_FALSE(s.finite) << at;
      if (std::isnan(bad)) {  // as std::min / std::max over the voxels: NaN never enters the range
        const ValueSummary r = reference_summary(contiguous_view(data.data(), {23, 1, 1}, VoxelType::f32));
        EXPECT_EQ(s.lo, r.lo);
        EXPECT_EQ(s.hi, r.hi);
      }
    }
  }
}

TEST(VolumePipeline, SummaryOfStridedAndSparseViewsCountsOnlyActiveVoxelsInTheRange) {
  const Volume v = test::smooth_volume({12, 7, 5}, VoxelType::f32, 10.0, 2);
  const VolumeView strided = sub_view(view_of(v), {1, 2, 1}, {9, 4, 3});
  const ValueSummary a = summarize_values(strided), ra = reference_summary(strided);
  EXPECT_EQ(a.lo, ra.lo);
  EXPECT_EQ(a.hi, ra.hi);
  Volume sparse = v;
  sparse.active.assign(sparse.count(), 0);
  for (std::size_t i = 0; i < sparse.count(); i += 3) sparse.active[i] = 1;
  const ValueSummary b = summarize_values(view_of(sparse)), rb = reference_summary(view_of(sparse));
  EXPECT_EQ(b.lo, rb.lo);
  EXPECT_EQ(b.hi, rb.hi);
  EXPECT_EQ(b.largest, rb.largest);
  EXPECT_NE(b.lo, summarize_values(view_of(v)).lo);  // the mask made a difference here
}

TEST(VolumePipeline, StoreAndFindOutliersEqualsConvertThenFind) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (const VoxelType type : {VoxelType::u8, VoxelType::u16, VoxelType::f32, VoxelType::f64}) {
    const std::size_t n = 5000;
    std::vector<double> original(n);
    std::vector<float> requantized(n);
    std::vector<std::uint8_t> check(n);
    for (std::size_t i = 0; i < n; ++i) {
      original[i] = to_stored(100.0 + 20.0 * noise(rng), type);
      requantized[i] = float(original[i] + 1.5 * noise(rng));  // many beyond a bound of 2
      check[i] = std::uint8_t(i % 3 != 0);
    }
    for (const bool masked : {false, true}) {
      const std::span<const std::uint8_t> mask =
          masked ? std::span<const std::uint8_t>(check) : std::span<const std::uint8_t>();
      std::vector<double> want(n);
      for (std::size_t i = 0; i < n; ++i) want[i] = to_stored(double(requantized[i]), type);
      const std::vector<Outlier> want_outliers = find_outliers(original, want, mask, 2.0, type);
      std::vector<double> got(n);
      std::vector<Outlier> got_outliers{{7, 7}};  // cleared first
      StoredError error;
      store_and_find_outliers(original, requantized, got, mask, 2.0, type, got_outliers, &error);
      ASSERT_GT(want_outliers.size(), 100u);
      // The error of the stored values over the voxels that count, summed in voxel order.
      double want_max = 0.0, want_sse = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        if (masked && check[i] == 0) continue;
        const double e = std::abs(original[i] - want[i]);
        want_max = std::max(want_max, e);
        want_sse += e * e;
      }
      EXPECT_GT(want_max, 0.0);
      EXPECT_LE(want_max, 2.0);
      EXPECT_EQ(error.max, want_max) << to_string(type);
      EXPECT_EQ(error.sse, want_sse) << to_string(type);
      // Without the stored values (the encoder's candidates): the same outliers and error.
      std::vector<Outlier> bare_outliers;
      StoredError bare;
      store_and_find_outliers(original, requantized, {}, mask, 2.0, type, bare_outliers, &bare);
      ASSERT_EQ(bare_outliers.size(), want_outliers.size());
      EXPECT_EQ(bare.max, error.max);
      EXPECT_EQ(bare.sse, error.sse);
      // Nor the error (the encoder's candidate steps): the same outliers.
      std::vector<Outlier> only_outliers;
      store_and_find_outliers(original, requantized, {}, mask, 2.0, type, only_outliers, nullptr);
      ASSERT_EQ(only_outliers.size(), want_outliers.size());
      for (std::size_t k = 0; k < only_outliers.size(); ++k)
        EXPECT_EQ(only_outliers[k].k, want_outliers[k].k);
      ASSERT_EQ(got_outliers.size(), want_outliers.size()) << to_string(type);
      for (std::size_t k = 0; k < got_outliers.size(); ++k) {
        EXPECT_EQ(got_outliers[k].index, want_outliers[k].index);
        EXPECT_EQ(got_outliers[k].k, want_outliers[k].k);
      }
      for (std::size_t i = 0; i < n; ++i)
        ASSERT_EQ(std::bit_cast<std::uint64_t>(got[i]), std::bit_cast<std::uint64_t>(want[i])) << i;
    }
  }
}

// requantize_brick's model statistics, summed as the scalar loop it replaced summed them (the
// float sum of log2(index) in scan order): the step choice, and so the stream, depends on them.
TEST(VolumePipeline, RequantizeStatisticsEqualTheScalarSums) {
  const Volume v = test::smooth_volume({40, 33, 17}, VoxelType::f32, 50.0, 9);
  const auto t = make_transform("cdf97");
  const BrickCoding c{t.get(), default_levels(v.dims), 16, 0.4375, false};
  const std::vector<float> coef = analyze_brick(c, v.samples, v.dims);
  for (double base : {0.004, 0.05, 0.7}) {
    IndexStats got;
    std::vector<float> out;
    requantize_brick(c, coef, v.dims, base, out, &got);
    const std::vector<float> steps = brick_steps(c, v.dims, base);
    double significant = 0.0, log2_sum = 0.0;
    for (const CodeBlock& b : brick_blocks(c, v.dims)) {
      const float inv = 1.0f / steps[b.band];
      float sum = 0.0f;
      for (std::size_t z = 0; z < b.size[2]; ++z)
        for (std::size_t y = 0; y < b.size[1]; ++y)
          for (std::size_t x = 0; x < b.size[0]; ++x) {
            const float value =
                coef[b.offset[0] + x + v.dims[0] * (b.offset[1] + y + v.dims[1] * (b.offset[2] + z))];
            const auto q = std::uint32_t(std::int32_t(std::fabs(value) * inv));
            if (q == 0) {
              sum += 0.0f;
              continue;
            }
            significant += 1.0;
            const auto bits = std::bit_cast<std::uint32_t>(float(q));  // approximate_log2's definition
            const float f = std::bit_cast<float>((bits & 0x7fffffu) | 0x3f800000u) - 1.0f;
            sum += float(int(bits >> 23) - 127) + f * (1.3466f - 0.3466f * f);
          }
      log2_sum += double(sum);
    }
    EXPECT_GT(significant, 0.0);
    EXPECT_EQ(got.significant, significant) << base;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(got.log2_sum), std::bit_cast<std::uint64_t>(log2_sum)) << base;
  }
}

TEST(VolumePipeline, OutputRowsEqualVoxelByVoxelSets) {
  const std::vector<double> values = random_values<double>(7, 0.0, 200.0, 4);
  for (const VoxelType storage : {VoxelType::u8, VoxelType::u16, VoxelType::f32, VoxelType::f64}) {
    std::vector<double> rounded = values;
    for (double& x : rounded) x = to_stored(x, storage);
    std::vector<std::uint64_t> a(9 * 4 * 3, 0), b(a.size(), 0);  // room for every storage
    VolumeOutput oa = contiguous_output(a.data(), {9, 4, 3}, storage), ob = oa;
    ob.data = b.data();
    oa.strides = ob.strides = {1, 9, 36};
    for (const std::ptrdiff_t stride0 : {std::ptrdiff_t(1), std::ptrdiff_t(4)}) {
      oa.strides[0] = ob.strides[0] = stride0;
      oa.dims = ob.dims = {stride0 == 1 ? 9u : 2u, 4, 3};
      const std::size_t n = stride0 == 1 ? 7 : 2;
      oa.set_row(stride0 == 1 ? 2 : 0, 1, 2, rounded.data(), n);
      for (std::size_t i = 0; i < n; ++i) ob.set((stride0 == 1 ? 2 : 0) + i, 1, 2, rounded[i]);
      EXPECT_EQ(a, b) << to_string(storage) << " stride " << stride0;
    }
  }
}

}  // namespace
}  // namespace pupwave
