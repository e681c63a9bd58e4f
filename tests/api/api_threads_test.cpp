// The public C++ API (pupwave/pupwave.hpp): round trips on real data, error statuses, and the
// stated thread safety: two threads coding different inputs at once get the serial results.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <thread>
#include <vector>

#include "pupwave/pupwave.hpp"

namespace {

namespace api = pupwave::api;

api::ImageOptions image_options(api::ImageRate rate, double target) {
  api::ImageOptions o;
  o.rate = rate;
  o.target = target;
  return o;
}

api::VolumeOptions volume_options(api::VolumeRate rate, double target) {
  api::VolumeOptions o;
  o.rate = rate;
  o.target = target;
  return o;
}

std::vector<float> read_wmag() {
  std::vector<float> v(91 * 91 * 91);
  std::ifstream in(PUPWAVE_TESTIMAGES_DIR "/wmag91.float", std::ios::binary);
  in.read(reinterpret_cast<char*>(v.data()), std::streamsize(v.size() * sizeof(float)));
  EXPECT_TRUE(in.good());
  return v;
}

std::vector<std::uint16_t> pattern(std::size_t w, std::size_t h, std::size_t c) {
  std::vector<std::uint16_t> px(w * h * c);
  for (std::size_t i = 0; i < px.size(); ++i)
    px[i] = std::uint16_t(30000 + 20000 * std::sin(double(i % (w * c)) * 0.01) *
                                      std::cos(double(i / (w * c)) * 0.02));
  return px;
}

TEST(PublicApi, ImageLosslessAndLevels) {
  const auto px = pattern(70, 50, 3);
  const auto view = api::interleaved_view(px.data(), 70, 50, 3, api::SampleType::u16);
  // The lossless default (lc) codes no wavelet levels, so a reduced level is refused...
  const auto flat = api::compress_image(view, image_options(api::ImageRate::lossless, 0));
  const api::Image exact = api::decompress_image(flat);
  ASSERT_EQ(exact.data.size(), px.size() * 2);
  EXPECT_EQ(std::memcmp(exact.data.data(), px.data(), exact.data.size()), 0);
  EXPECT_THROW(api::decompress_image(flat, 1), api::Error);
  // ...and with levels asked for, it decodes at half size.
  api::ImageOptions leveled = image_options(api::ImageRate::lossless, 0);
  leveled.levels = 3;
  const auto bytes = api::compress_image(view, leveled);
  const api::Image back = api::decompress_image(bytes);
  ASSERT_EQ(back.data.size(), px.size() * 2);
  EXPECT_EQ(std::memcmp(back.data.data(), px.data(), back.data.size()), 0);
  const api::Image half = api::decompress_image(bytes, 1);
  EXPECT_EQ(half.width, 35u);
  EXPECT_EQ(half.height, 25u);
  const api::StreamInfo info = api::info(bytes);
  EXPECT_FALSE(info.volume);
  EXPECT_EQ(info.type, "u16");
  EXPECT_TRUE(info.lossless);
}

TEST(PublicApi, VolumeMaxErrorOnWmag91) {
  const auto v = read_wmag();
  const auto bytes = api::compress_volume({v.data(), {91, 91, 91}, api::VoxelType::f32},
                                          volume_options(api::VolumeRate::max_error, 0.25));
  const auto grids = api::decompress_volume(bytes);
  ASSERT_EQ(grids.size(), 1u);
  const float* back = reinterpret_cast<const float*>(grids[0].data.data());
  double worst = 0;
  for (std::size_t i = 0; i < v.size(); ++i) worst = std::max(worst, std::abs(double(back[i]) - v[i]));
  EXPECT_LE(worst, 0.25);
  EXPECT_GT(worst, 0.0);
}

TEST(PublicApi, SparseBricksKeepInactiveVoxels) {
  std::vector<float> a(8 * 8 * 8), b(4 * 4 * 4);
  std::vector<std::uint8_t> mask(b.size(), 1);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = float(std::sin(double(i) * 0.1));
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = float(i) * 0.01f;
  mask[5] = 0;
  const api::BrickView bricks[] = {{{0, 0, 0}, {a.data(), {8, 8, 8}, api::VoxelType::f32}, nullptr},
                                   {{16, 0, 4}, {b.data(), {4, 4, 4}, api::VoxelType::f32}, mask.data()}};
  const auto bytes =
      api::compress_sparse_volume(bricks, -3.0, volume_options(api::VolumeRate::max_error, 1e-3));
  const auto grids = api::decompress_volume(bytes);
  ASSERT_EQ(grids.size(), 1u);
  const api::Volume& g = grids[0];
  EXPECT_EQ(g.dims[0], 20u);
  EXPECT_EQ(g.dims[2], 8u);
  ASSERT_EQ(g.active.size(), 20u * 8 * 8);
  const float* v = reinterpret_cast<const float*>(g.data.data());
  EXPECT_NEAR(v[g.dims[0] * (1 + 8 * 2) + 3], a[3 + 8 * (1 + 8 * 2)], 1e-3);
  EXPECT_EQ(g.active[16 + 20 * (0 + 8 * 4)], 1);
  EXPECT_EQ(g.active[17 + 20 * (1 + 8 * 4)], 0);  // mask[5] = voxel (1, 1, 0) of brick b
  EXPECT_EQ(g.active[10], 0);                     // between the bricks
  EXPECT_EQ(v[10], -3.0f);
  EXPECT_TRUE(api::info(bytes).sparse);
}

TEST(PublicApi, ErrorsCarryStatus) {
  const std::uint8_t junk[16] = {'P', 'U', 'P', 'W', 9, 9, 9};
  try {
    api::decompress_image(junk);
    FAIL();
  } catch (const api::Error& e) {
    EXPECT_EQ(e.status(), api::Status::corrupt_stream);
  }
  const float one = 1;
  try {
    api::compress_image(api::interleaved_view(&one, 1, 1, 1, api::SampleType::f32),
                        image_options(api::ImageRate::bpp, -2));
    FAIL();
  } catch (const api::Error& e) {
    EXPECT_EQ(e.status(), api::Status::invalid_argument);
    EXPECT_NE(std::string(e.what()).find("positive"), std::string::npos);
  }
}

// The stated thread-safety: independent calls on two threads at once give the serial results.
TEST(PublicApi, TwoThreadsGiveSerialResults) {
  const auto px = pattern(300, 200, 3);
  const auto v = read_wmag();
  const auto image_view = api::interleaved_view(px.data(), 300, 200, 3, api::SampleType::u16);
  const api::VolumeView volume_view{v.data(), {91, 91, 91}, api::VoxelType::f32};
  const api::ImageOptions image_opts = image_options(api::ImageRate::bpp, 1.0);
  const api::VolumeOptions volume_opts = volume_options(api::VolumeRate::max_error, 0.5);
  const auto image_serial = api::compress_image(image_view, image_opts);
  const auto volume_serial = api::compress_volume(volume_view, volume_opts);
  const auto image_decoded = api::decompress_image(image_serial).data;
  std::vector<std::uint8_t> image_bytes[2], volume_bytes[2];
  std::vector<std::byte> decoded[2];
  std::thread a([&] {
    for (int i = 0; i < 2; ++i) {
      image_bytes[i] = api::compress_image(image_view, image_opts);
      decoded[i] = api::decompress_image(image_bytes[i]).data;
    }
  });
  std::thread b([&] {
    for (int i = 0; i < 2; ++i) volume_bytes[i] = api::compress_volume(volume_view, volume_opts);
  });
  a.join();
  b.join();
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(image_bytes[i], image_serial);
    EXPECT_EQ(volume_bytes[i], volume_serial);
    EXPECT_EQ(decoded[i], image_decoded);
  }
}

}  // namespace
