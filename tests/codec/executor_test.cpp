// Parallelism is injected (transforms/executor.h): a caller's executor runs the work, streams do
// not depend on it, and independent encodes on different threads do not interfere.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>

#include "codec/image/image_codec.h"
#include "codec/volume/volume_codec.h"
#include "test_images.h"
#include "volcodec/volcodec_test_util.h"

namespace pupwave {
namespace {

// A caller-supplied executor: runs tasks serially in reverse order and counts them, so a test
// sees that the codec used it and that task order does not matter.
class ReverseCountingExecutor final : public Executor {
 public:
  void run(std::size_t count, const std::function<void(std::size_t)>& task) const override {
    for (std::size_t i = count; i-- > 0;) task(i);
    tasks += count;
  }
  unsigned concurrency() const override { return 3; }
  mutable std::atomic<std::size_t> tasks{0};
};

EncodeOptions rgb_options(const Executor* ex) {
  EncodeOptions o;
  o.mode = RateMode::bpp;
  o.target = 1.0;
  o.executor = ex;
  return o;
}

EncodeOptions grey_options(const Executor* ex) {
  EncodeOptions o;
  o.mode = RateMode::psnr;
  o.target = 38.0;
  o.transform = "pups:chaikin";
  o.executor = ex;
  return o;
}

VolumeEncodeOptions volume_options(const Executor* ex) {
  VolumeEncodeOptions o;
  o.target = 1e-2;
  o.brick = 16;
  o.executor = ex;
  return o;
}

std::vector<VolumeGrid> test_grids() {
  VolumeGrid g;
  g.name = "field";
  g.volume = test::smooth_volume({40, 33, 20}, VoxelType::f32, 5.0);
  return {g};
}

TEST(Executor, PoolRunsEveryTaskOnceAndRethrows) {
  for (unsigned threads : {0u, 1u, 2u, 5u}) {
    const auto ex = make_pool_executor(threads);
    std::vector<std::atomic<int>> hits(1000);
    ex->run(hits.size(), [&](std::size_t i) { ++hits[i]; });
    for (const auto& h : hits) ASSERT_EQ(h.load(), 1) << threads;
    EXPECT_THROW(ex->run(100,
                         [](std::size_t i) {
                           if (i == 37) throw std::runtime_error("task 37");
                         }),
                 std::runtime_error);
  }
  EXPECT_EQ(serial_executor().concurrency(), 1u);
  EXPECT_GE(default_executor().concurrency(), 1u);
}

TEST(Executor, CallerExecutorRunsTheWorkAndStreamsDoNotDependOnIt) {
  const Image img = testing::synthetic_image(200, 150, 3, SampleType::u8, 31);
  const auto serial = encode_image(img, rgb_options(&serial_executor())).bytes;
  ReverseCountingExecutor mine;
  EXPECT_EQ(encode_image(img, rgb_options(&mine)).bytes, serial);
  EXPECT_GT(mine.tasks.load(), 0u);
  const std::size_t before = mine.tasks.load();
  EXPECT_EQ(decode_image(serial, 0, mine).samples, decode_image(serial, 0, serial_executor()).samples);
  EXPECT_GT(mine.tasks.load(), before);

  const auto grids = test_grids();
  const auto vserial = encode_volumes(grids, volume_options(&serial_executor())).bytes;
  EXPECT_EQ(encode_volumes(grids, volume_options(&mine)).bytes, vserial);
}

TEST(Executor, ConcurrentEncodesOnTwoThreadsMatchSerialRuns) {
  const Image rgb = testing::synthetic_image(320, 240, 3, SampleType::u8, 32);
  const Image grey = testing::synthetic_image(257, 199, 1, SampleType::u16, 33);
  const auto grids = test_grids();
  const auto rgb_serial = encode_image(rgb, rgb_options(&serial_executor())).bytes;
  const auto grey_serial = encode_image(grey, grey_options(&serial_executor())).bytes;
  const auto vol_serial = encode_volumes(grids, volume_options(&serial_executor())).bytes;
  for (int round = 0; round < 3; ++round) {
    std::vector<std::uint8_t> rgb_bytes, grey_bytes, vol_bytes;
    std::thread a([&] { rgb_bytes = encode_image(rgb, rgb_options(nullptr)).bytes; });  // shared pool
    std::thread b([&] {
      const auto two = make_pool_executor(2);
      grey_bytes = encode_image(grey, grey_options(two.get())).bytes;
      vol_bytes = encode_volumes(grids, volume_options(nullptr)).bytes;
    });
    a.join();
    b.join();
    EXPECT_EQ(rgb_bytes, rgb_serial) << round;
    EXPECT_EQ(grey_bytes, grey_serial) << round;
    EXPECT_EQ(vol_bytes, vol_serial) << round;
  }
}

}  // namespace
}  // namespace pupwave
