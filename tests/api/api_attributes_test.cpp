// The public C++ API's text attributes (pupwave::api::Attribute): stored in image and volume
// streams, handed back by decode and info, absent from streams coded without them, and refused
// when the stream could not hold them as given.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <vector>

#include "pupwave/pupwave.hpp"

namespace {

namespace api = pupwave::api;

std::vector<float> read_wmag() {
  std::vector<float> v(91 * 91 * 91);
  std::ifstream in(PUPWAVE_TESTIMAGES_DIR "/wmag91.float", std::ios::binary);
  in.read(reinterpret_cast<char*>(v.data()), std::streamsize(v.size() * sizeof(float)));
  EXPECT_TRUE(in.good());
  return v;
}

const std::vector<api::Attribute> kAttributes{{"pupwave:dtype", "<f8"}, {"note", std::string(300, 'x')}};

TEST(PublicApiAttributes, ImageKeepsThemAndDecodesTheSameSamples) {
  const std::vector<float> wmag = read_wmag();
  const api::ImageView view = api::interleaved_view(wmag.data(), 91, 91, 1, api::SampleType::f32);
  api::ImageOptions options;
  const std::vector<std::uint8_t> plain = api::compress_image(view, options);
  options.attributes = kAttributes;
  const std::vector<std::uint8_t> tagged = api::compress_image(view, options);
  EXPECT_GT(tagged.size(), plain.size());
  const api::Image a = api::decompress_image(plain), b = api::decompress_image(tagged);
  EXPECT_TRUE(a.attributes.empty());
  ASSERT_EQ(a.data.size(), b.data.size());
  EXPECT_EQ(std::memcmp(a.data.data(), b.data.data(), a.data.size()), 0);
  // The META chunk keeps its entries in the given order.
  EXPECT_EQ(b.attributes, kAttributes);
  EXPECT_EQ(api::info(tagged).attributes, kAttributes);
  EXPECT_TRUE(api::info(plain).attributes.empty());
}

TEST(PublicApiAttributes, VolumeGridKeepsThem) {
  const std::vector<float> wmag = read_wmag();
  const api::VolumeView view{wmag.data(), {91, 91, 91}, api::VoxelType::f32};
  api::VolumeOptions options;
  options.rate = api::VolumeRate::max_error;
  options.target = 0.01;
  const std::vector<std::uint8_t> plain = api::compress_volume(view, options);
  options.attributes = kAttributes;
  const std::vector<std::uint8_t> tagged = api::compress_volume(view, options);
  EXPECT_GT(tagged.size(), plain.size());
  const std::vector<api::Volume> grids = api::decompress_volume(tagged);
  ASSERT_EQ(grids.size(), 1u);
  // Grid metadata is a map: it comes back sorted by name.
  const std::vector<api::Attribute> sorted{kAttributes[1], kAttributes[0]};
  EXPECT_EQ(grids[0].attributes, sorted);
  EXPECT_EQ(api::info(tagged).attributes, sorted);
  EXPECT_TRUE(api::decompress_volume(plain)[0].attributes.empty());
}

TEST(PublicApiAttributes, UnstorableListsAreRefused) {
  const std::vector<float> wmag = read_wmag();
  const api::ImageView image = api::interleaved_view(wmag.data(), 91, 91, 1, api::SampleType::f32);
  const api::VolumeView volume{wmag.data(), {91, 91, 91}, api::VoxelType::f32};
  const std::vector<std::vector<api::Attribute>> bad{
      {{"", "empty name"}},
      {{"twice", "a"}, {"twice", "b"}},
      {{"long", std::string(65536, 'v')}},
      {{std::string(4097, 'n'), "long name"}},
  };
  for (const auto& list : bad) {
    api::ImageOptions io;
    io.attributes = list;
    api::VolumeOptions vo;
    vo.attributes = list;
    try {
      api::compress_image(image, io);
      ADD_FAILURE() << "image accepted " << list[0].name.substr(0, 8);
    } catch (const api::Error& e) {
      EXPECT_EQ(e.status(), api::Status::invalid_argument);
      EXPECT_NE(std::string(e.what()).find("attribute"), std::string::npos) << e.what();
    }
    EXPECT_THROW(api::compress_volume(volume, vo), api::Error);
  }
}

}  // namespace
