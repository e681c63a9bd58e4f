// Encode statistics (codec/image/encode_stats.h) travel with the call: two encodes on different
// threads at once each keep exactly the figures they keep alone, an encode on another thread
// gives its figures to its caller, and asking for them leaves the streams as they are.
#include <gtest/gtest.h>

#include <latch>
#include <thread>

#include "codec/entropy/block_tally.h"
#include "codec/image/encode_stats.h"
#include "codec/image/image_codec.h"
#include "photo_crops.h"
#include "transforms/executor.h"

namespace pupwave {
namespace {

using test::photo;

// One image's statistics in one object: the bit-plane coder's context tally of its lossless
// stream (blocks coded as tasks of a 2-thread pool) and the pc coder's search for 0.25 bpp.
struct Figures {
  ContextTally tally;
  EncodeStats stats;
  Figures() { stats.tally = &tally; }
};

// The options of the two encodes of `f`. The pc encode runs serially: before a budget's lossy
// encode, a lossless trial (bit-plane blocks, which join the tally) stops at the first block
// over the budget, and with several threads which blocks were coded by then depends on timing.
EncodeOptions lossless_options(Figures& f, const Executor& executor) {
  EncodeOptions o;
  o.mode = RateMode::lossless;
  o.transform = "cdf53";
  o.entropy = EntropyCoder::ebcot;
  o.executor = &executor;
  o.stats = &f.stats;
  return o;
}
EncodeOptions pc_budget_options(Figures& f) {
  EncodeOptions o = test::pc_options(RateMode::bpp, 0.25);
  o.executor = &serial_executor();
  o.measure_psnr = false;
  o.stats = &f.stats;
  return o;
}

void encode_both(const Image& img, Figures& f) {
  const auto pool = make_pool_executor(2);
  encode_image(img, lossless_options(f, *pool));
  encode_image(img, pc_budget_options(f));
}

void expect_same_figures(const Figures& got, const Figures& alone, const char* name) {
  EXPECT_EQ(got.tally.blocks, alone.tally.blocks) << name;
  EXPECT_TRUE(got.tally.starts == alone.tally.starts) << name;
  EXPECT_EQ(got.stats.pc_passes, alone.stats.pc_passes) << name;
  EXPECT_EQ(got.stats.pc_trims, alone.stats.pc_trims) << name;
  EXPECT_EQ(got.stats.pc_abandoned_share, alone.stats.pc_abandoned_share) << name;
}

TEST(EncodeStats, ConcurrentEncodesEachKeepTheirOwnFigures) {
  const Image camera = photo("camera.png"), coffee = photo("coffee.png");
  Figures camera_alone, coffee_alone;
  encode_both(camera, camera_alone);
  encode_both(coffee, coffee_alone);
  // Figures worth comparing: both coders counted, and the two images' differ (a mix would show).
  EXPECT_GT(camera_alone.tally.blocks, 0u);
  EXPECT_GT(camera_alone.stats.pc_passes, 0);
  EXPECT_NE(camera_alone.tally.blocks, coffee_alone.tally.blocks);

  Figures camera_together, coffee_together;
  std::latch start(2);  // both threads code at the same time
  std::thread a([&] {
    start.arrive_and_wait();
    encode_both(camera, camera_together);
  });
  std::thread b([&] {
    start.arrive_and_wait();
    encode_both(coffee, coffee_together);
  });
  a.join();
  b.join();
  expect_same_figures(camera_together, camera_alone, "camera.png");
  expect_same_figures(coffee_together, coffee_alone, "coffee.png");
}

// The figures reach the caller that holds the object whichever thread coded: coffee's search
// coded on another thread, after camera's on this one (their abandoned shares differ at 0.25 bpp).
TEST(EncodeStats, FiguresOfAnEncodeOnAnotherThreadReachTheCaller) {
  const Image camera = photo("camera.png"), coffee = photo("coffee.png");
  Figures coffee_here, camera_here, coffee_there;
  encode_image(coffee, pc_budget_options(coffee_here));
  encode_image(camera, pc_budget_options(camera_here));
  ASSERT_NE(camera_here.stats.pc_abandoned_share, coffee_here.stats.pc_abandoned_share);
  std::thread([&] { encode_image(coffee, pc_budget_options(coffee_there)); }).join();
  expect_same_figures(coffee_there, coffee_here, "coffee.png");
}

// Figures add up over the encodes an object is passed to.
TEST(EncodeStats, FiguresAddUpOverTheEncodesPassedTheObject) {
  const Image camera = photo("camera.png");
  Figures once, twice;
  encode_image(camera, pc_budget_options(once));
  encode_image(camera, pc_budget_options(twice));
  encode_image(camera, pc_budget_options(twice));
  EXPECT_GT(once.stats.pc_passes, 0);
  EXPECT_EQ(twice.stats.pc_passes, 2 * once.stats.pc_passes);
  EXPECT_EQ(twice.stats.pc_trims, 2 * once.stats.pc_trims);
  EXPECT_EQ(twice.tally.blocks, 2 * once.tally.blocks);
}

// Keeping statistics changes no byte: the bit-plane coder at a budget and lossless, and the pc
// coder at a budget, with and without an object.
TEST(EncodeStats, StreamsAreTheSameWithAndWithoutStatistics) {
  const Image coffee = photo("coffee.png");
  Figures f;
  EncodeOptions ebcot;
  ebcot.mode = RateMode::bpp;
  ebcot.target = 0.5;
  ebcot.entropy = EntropyCoder::ebcot;
  ebcot.measure_psnr = false;
  const EncodeOptions lossless = lossless_options(f, default_executor());
  const EncodeOptions pc = pc_budget_options(f);
  for (EncodeOptions with : {ebcot, lossless, pc}) {
    EncodeOptions without = with;
    with.stats = &f.stats;
    without.stats = nullptr;
    EXPECT_EQ(encode_image(coffee, with).bytes, encode_image(coffee, without).bytes);
  }
  EXPECT_GT(f.tally.blocks, 0u);
  EXPECT_GT(f.stats.pc_passes, 0);
}

}  // namespace
}  // namespace pupwave
