// How an encode hands its stream out and how a decode reports its output, the two things that keep
// their peak memory near the bricks in flight: the writer gets the head and then one chunk per
// brick, in order and one call at a time, whatever the thread count, making up exactly the stream
// an encode without a writer returns; decode_volume_into reports each finished z-slab of a dense
// output once, with its final values already written. And the encoder's switch to lossless coding
// for integer bounds below 1, which only exact values meet.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_view.h"
#include "transforms/executor.h"
#include "volcodec/volcodec_test_util.h"

namespace pupwave {
namespace {

using test::worst_error;

VolumeGrid grid_of(Volume v) {
  VolumeGrid g;
  g.name = "field";
  g.volume = std::move(v);
  return g;
}

VolumeEncodeOptions options(VolumeRateMode mode, double target, const char* spec, const Executor& ex) {
  VolumeEncodeOptions o;
  o.mode = mode;
  o.target = target;
  o.transform = spec;
  o.brick = 16;  // 37x29x45: 3x2x3 bricks
  o.block = 16;
  o.executor = &ex;
  return o;
}

const Extent kDims{37, 29, 45};

// What a writer received: the pieces in order, and whether two calls ever overlapped.
struct Received {
  std::vector<std::uint8_t> bytes;
  std::size_t pieces = 0;
  std::atomic<int> inside{0};
  bool overlapped = false;
};

void check_writer(const Volume& v, VolumeEncodeOptions o) {
  const auto reference = encode_volumes({grid_of(v)}, o);  // serial, no writer
  ASSERT_FALSE(reference.bytes.empty());
  for (unsigned threads : {1u, 2u, 4u}) {
    const auto pool = make_pool_executor(threads);
    o.executor = pool.get();
    Received got;
    const auto r = encode_volumes({grid_of(v)}, {}, o, [&](std::span<const std::uint8_t> piece) {
      if (got.inside.fetch_add(1) != 0) got.overlapped = true;
      got.bytes.insert(got.bytes.end(), piece.begin(), piece.end());
      ++got.pieces;
      got.inside.fetch_sub(1);
    });
    EXPECT_TRUE(r.bytes.empty());
    EXPECT_FALSE(got.overlapped) << threads;
    EXPECT_EQ(got.bytes, reference.bytes) << "threads " << threads;
    EXPECT_EQ(r.size, reference.bytes.size());
    EXPECT_EQ(got.pieces, 1u + 3u * 2u * 3u) << "the head, then one chunk per brick";
    EXPECT_EQ(r.max_error, reference.max_error);
    EXPECT_EQ(r.psnr, reference.psnr);  // squared errors summed in brick order
    EXPECT_EQ(r.outliers, reference.outliers);
  }
}

TEST(VolumeStreaming, WriterGetsTheStreamInOrderOneCallAtATime) {
  const Volume f = test::smooth_volume(kDims, VoxelType::f32, 10.0);
  const Executor& serial = serial_executor();
  check_writer(f, options(VolumeRateMode::max_error, 1e-3, "cdf97", serial));
  check_writer(f, options(VolumeRateMode::step, 0.05, "cdf97", serial));
  check_writer(test::smooth_volume(kDims, VoxelType::u16, 4000.0),
               options(VolumeRateMode::lossless, 0.0, "cdf53", serial));
}

TEST(VolumeStreaming, IntegerBoundBelowOneCodesLosslessInstead) {
  for (const VoxelType type : {VoxelType::u8, VoxelType::u16}) {
    const Volume v = test::smooth_volume(kDims, type, type == VoxelType::u8 ? 255.0 : 4000.0);
    const auto lossless =
        encode_volumes({grid_of(v)}, options(VolumeRateMode::lossless, 0.0, "cdf53", serial_executor()));
    EXPECT_FALSE(lossless.switched_to_lossless);
    for (const double bound : {0.255, 0.5, 0.999}) {
      const auto r =
          encode_volumes({grid_of(v)}, options(VolumeRateMode::max_error, bound, "cdf97", serial_executor()));
      EXPECT_TRUE(r.switched_to_lossless) << bound;
      EXPECT_EQ(r.bytes, lossless.bytes) << to_string(type) << " bound " << bound;
      EXPECT_EQ(r.max_error, 0.0);
      EXPECT_EQ(r.outliers, 0u);
      EXPECT_EQ(decode_volumes(r.bytes)[0].volume.samples, v.samples);
    }
    // From a bound of 1 an error of 1 is allowed: transform coding with corrections, within it.
    const auto lossy =
        encode_volumes({grid_of(v)}, options(VolumeRateMode::max_error, 1.0, "cdf97", serial_executor()));
    EXPECT_FALSE(lossy.switched_to_lossless);
    EXPECT_NE(lossy.bytes, lossless.bytes);
    EXPECT_LE(worst_error(v, decode_volumes(lossy.bytes)[0].volume), 1.0);
  }
  // Float samples can have errors below 1: the bound is met by transform coding, as asked.
  const Volume f = test::smooth_volume(kDims, VoxelType::f32, 10.0);
  const auto r =
      encode_volumes({grid_of(f)}, options(VolumeRateMode::max_error, 0.3, "cdf97", serial_executor()));
  EXPECT_FALSE(r.switched_to_lossless);
  EXPECT_GT(r.max_error, 0.0);
  EXPECT_LE(r.max_error, 0.3);
}

// Each plane a done_slabs call covered (calls come from worker threads), and whether the output
// then already held the plane's final values.
struct Reports {
  std::mutex mutex;
  std::vector<int> times;
  const std::vector<float>* output = nullptr;
  const std::vector<double>* want = nullptr;
  std::size_t plane = 0;
  bool early = false;  // a reported plane not yet fully written
};

void report(const void* context, const VolumeOutput& out, std::size_t z0, std::size_t z1) {
  auto* r = static_cast<Reports*>(const_cast<void*>(context));
  const std::lock_guard<std::mutex> lock(r->mutex);
  for (std::size_t z = z0; z < z1 && z < out.dims[2]; ++z) {
    ++r->times[z];
    for (std::size_t i = z * r->plane; i < (z + 1) * r->plane; ++i)
      if ((*r->output)[i] != float((*r->want)[i])) r->early = true;
  }
}

TEST(VolumeStreaming, DecodeIntoReportsEveryFinishedSlabOnce) {
  const Volume f = test::smooth_volume(kDims, VoxelType::f32, 10.0);
  const auto bytes =
      encode_volumes({grid_of(f)}, options(VolumeRateMode::max_error, 1e-3, "cdf97", serial_executor()))
          .bytes;
  const std::vector<double> want = decode_volumes(bytes)[0].volume.samples;
  for (unsigned threads : {1u, 3u}) {
    const auto pool = make_pool_executor(threads);
    std::vector<float> out(f.count(), -1.0f);
    Reports reports;
    reports.times.assign(kDims[2], 0);
    reports.output = &out;
    reports.want = &want;
    reports.plane = kDims[0] * kDims[1];
    const auto grid = decode_volume_into(bytes, "", 0, *pool, DecodeLimits{}, [&](const VolumeGrid& g) {
      VolumeOutput target = contiguous_output(out.data(), g.volume.dims, VoxelType::f32);
      target.done_slabs = report;
      target.done_context = &reports;
      return target;
    });
    ASSERT_TRUE(grid.has_value());
    EXPECT_FALSE(reports.early) << threads;
    for (std::size_t z = 0; z < kDims[2]; ++z) EXPECT_EQ(reports.times[z], 1) << "plane " << z;
    for (std::size_t i = 0; i < out.size(); ++i) ASSERT_EQ(out[i], float(want[i])) << i;
  }
}

TEST(VolumeStreaming, DecodeIntoReportsNothingBelowFullResolution) {
  const Volume f = test::smooth_volume(kDims, VoxelType::f32, 10.0);
  const auto bytes =
      encode_volumes({grid_of(f)}, options(VolumeRateMode::max_error, 1e-3, "cdf97", serial_executor()))
          .bytes;
  std::vector<float> out;
  int calls = 0;
  const auto grid =
      decode_volume_into(bytes, "", 1, serial_executor(), DecodeLimits{}, [&](const VolumeGrid& g) {
        out.resize(g.volume.count());
        VolumeOutput target = contiguous_output(out.data(), g.volume.dims, VoxelType::f32);
        target.done_slabs = [](const void* c, const VolumeOutput&, std::size_t, std::size_t) {
          ++*static_cast<int*>(const_cast<void*>(c));
        };
        target.done_context = &calls;
        return target;
      });
  ASSERT_TRUE(grid.has_value());
  EXPECT_EQ(calls, 0);
}

}  // namespace
}  // namespace pupwave
