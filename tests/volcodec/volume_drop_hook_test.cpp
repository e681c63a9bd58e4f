// VolumeView's drop hook (how the CLI unmaps a raw input's pages once read): every row of every
// plane is dropped exactly once per pass over the input (summarize_values by whole planes, then
// the brick pass by rows of bricks, which finish in any order on a pool), and the stream is the
// same as without the hook.
#include <gtest/gtest.h>

#include <cstdint>
#include <mutex>
#include <vector>

#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_view.h"
#include "transforms/executor.h"
#include "volcodec/volcodec_test_util.h"

namespace pupwave {
namespace {

// How many times each row y of each plane z was dropped, at z * rows + y (calls come from
// worker threads).
struct Drops {
  std::mutex mutex;
  std::vector<int> times;
  std::size_t rows = 0;
  bool out_of_range = false;
};

void record(const void* context, const VolumeView& v, std::size_t z0, std::size_t z1, std::size_t y0,
            std::size_t y1) {
  auto* drops = static_cast<Drops*>(const_cast<void*>(context));
  std::lock_guard<std::mutex> lock(drops->mutex);
  if (z0 >= z1 || z1 > v.dims[2] || y0 >= y1 || y1 > v.dims[1]) drops->out_of_range = true;
  for (std::size_t z = z0; z < z1 && z < v.dims[2]; ++z)
    for (std::size_t y = y0; y < y1 && y < v.dims[1]; ++y) ++drops->times[z * drops->rows + y];
}

// Every row of every plane dropped `passes` times.
void expect_every_row(const Drops& drops, int passes) {
  for (std::size_t i = 0; i < drops.times.size(); ++i)
    EXPECT_EQ(drops.times[i], passes) << "plane " << i / drops.rows << " row " << i % drops.rows;
}

template <class T>
std::vector<T> stored(const Volume& v) {
  return std::vector<T>(v.samples.begin(), v.samples.end());
}

VolumeEncodeOptions options(VolumeRateMode mode, double target, const Executor& executor) {
  VolumeEncodeOptions o;
  o.mode = mode;
  o.target = target;
  o.brick = 16;  // 37x29x45: slabs of bricks at z 0, 16, 32 (the last 13 planes)
  o.block = 16;
  o.executor = &executor;
  return o;
}

std::vector<std::uint8_t> encode(const VolumeView& view, const VolumeEncodeOptions& o) {
  const VolumeView views[] = {view};
  return encode_volumes({describe_view(view, "v")}, views, o).bytes;
}

// Encodes with and without the hook; each row of each plane must be dropped `passes` times (-1:
// the same number of times as row 0 of plane 0, at least 3).
void check_drops(const VolumeView& plain, const VolumeEncodeOptions& o, int passes) {
  Drops drops;
  drops.rows = plain.dims[1];
  drops.times.assign(plain.dims[2] * drops.rows, 0);
  VolumeView hooked = plain;
  hooked.drop_rows = record;
  hooked.drop_context = &drops;
  EXPECT_EQ(encode(hooked, o), encode(plain, o));
  EXPECT_FALSE(drops.out_of_range);
  if (passes < 0) {
    passes = drops.times[0];
    EXPECT_GE(passes, 3);
  }
  expect_every_row(drops, passes);
}

const Extent kDims{37, 29, 45};

TEST(VolumeDropHook, SummarizeDropsEveryPlaneOnce) {
  const auto data = stored<float>(test::smooth_volume(kDims, VoxelType::f32, 10.0));
  Drops drops;
  drops.rows = kDims[1];
  drops.times.assign(kDims[2] * drops.rows, 0);
  VolumeView view = contiguous_view(data.data(), kDims, VoxelType::f32);
  view.drop_rows = record;
  view.drop_context = &drops;
  summarize_values(view);
  EXPECT_FALSE(drops.out_of_range);
  expect_every_row(drops, 1);
}

TEST(VolumeDropHook, MaxErrorAndStepDropEachPlaneOncePerPassSameStream) {
  const auto data = stored<float>(test::smooth_volume(kDims, VoxelType::f32, 10.0));
  const VolumeView view = contiguous_view(data.data(), kDims, VoxelType::f32);
  const auto pool = make_pool_executor(3);
  check_drops(view, options(VolumeRateMode::max_error, 1e-3, *pool), 2);  // summarize + bricks
  check_drops(view, options(VolumeRateMode::step, 0.05, *pool), 2);
  check_drops(view, options(VolumeRateMode::max_error, 1e-2, serial_executor()), 2);
}

TEST(VolumeDropHook, LosslessU16DropsEachPlaneTwiceSameStream) {
  const auto data = stored<std::uint16_t>(test::smooth_volume(kDims, VoxelType::u16, 4000.0));
  const VolumeView view = contiguous_view(data.data(), kDims, VoxelType::u16);
  const auto pool = make_pool_executor(2);
  VolumeEncodeOptions o = options(VolumeRateMode::lossless, 0.0, *pool);
  o.transform = "cdf53";
  check_drops(view, o, 2);
}

// Rate modes read the bricks in several passes (code, then measure the chosen passes): each
// row is dropped once in each of them, so the same number of times, at least three.
TEST(VolumeDropHook, RateModeDropsEveryPlaneOncePerPassSameStream) {
  const auto data = stored<float>(test::smooth_volume(kDims, VoxelType::f32, 10.0));
  const VolumeView view = contiguous_view(data.data(), kDims, VoxelType::f32);
  const auto pool = make_pool_executor(2);
  check_drops(view, options(VolumeRateMode::bpv, 2.0, *pool), -1);
}

}  // namespace
}  // namespace pupwave
