// One image and one set of options give the same .pw bytes from every front door: the CLI's
// flags, the C API and the C++ API, on the test photographs (the options are resolved in one
// place, codec/api/api_image_options.h). Python is compared with the CLI in
// tests/python/test_front_doors.py, the OpenImageIO plugin in tests/api/oiio_round_trip.sh.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "pupwave/pupwave.h"
#include "pupwave/pupwave.hpp"
#include "tools/image_io.h"

namespace {

namespace api = pupwave::api;
namespace fs = std::filesystem;

// CLI flags and the C++ options that say the same; C API calls are derived from the latter.
struct OptionSet {
  std::string flags;
  api::ImageOptions options;
};

api::ImageOptions options(api::ImageRate rate, double target, api::Coder coder = api::Coder::automatic) {
  api::ImageOptions o;
  o.rate = rate;
  o.target = target;
  o.coder = coder;
  return o;
}

std::vector<OptionSet> option_sets() {
  using api::ImageRate;
  std::vector<OptionSet> sets;
  sets.push_back({"", api::ImageOptions{}});
  sets.push_back({"--bpp 1", options(ImageRate::bpp, 1.0)});
  sets.push_back({"--bpp 0.5 --entropy ebcot --effort 2", options(ImageRate::bpp, 0.5, api::Coder::ebcot)});
  sets.back().options.effort = 2;
  sets.push_back({"--lossless", options(ImageRate::lossless, 0.0)});
  sets.push_back({"--lossless --entropy ebcot", options(ImageRate::lossless, 0.0, api::Coder::ebcot)});
  sets.push_back({"--psnr 35 --transform cdf53", options(ImageRate::psnr, 35.0)});
  sets.back().options.transform = "cdf53";
  sets.push_back({"--levels 3 --bpp 1", options(ImageRate::bpp, 1.0)});
  sets.back().options.levels = 3;
  sets.push_back({"--entropy ht --bpp 1", options(ImageRate::bpp, 1.0, api::Coder::ht)});
  sets.push_back({"--bpp 0.5 --tune visual", options(ImageRate::bpp, 0.5)});
  sets.back().options.tune = api::Tune::visual;
  sets.push_back(
      {"--psnr 33 --entropy ebcot --tune visual", options(ImageRate::psnr, 33.0, api::Coder::ebcot)});
  sets.back().options.tune = api::Tune::visual;
  return sets;
}

// An 8-bit photograph, interleaved (pixel after pixel, channels adjacent).
struct Photo {
  std::string path;
  std::size_t width = 0, height = 0, channels = 0;
  std::vector<std::uint8_t> samples;
};

Photo read_photo(const std::string& name) {
  Photo p;
  p.path = std::string(PUPWAVE_TESTIMAGES_DIR) + "/" + name;
  const pupwave::Image image = pupwave::cli::read_image(p.path);
  p.width = image.width, p.height = image.height, p.channels = image.channels;
  p.samples.resize(image.samples.size());
  for (std::size_t c = 0; c < image.channels; ++c)
    for (std::size_t i = 0; i < image.plane_size(); ++i)
      p.samples[i * image.channels + c] = std::uint8_t(image.plane(c)[i]);
  return p;
}

std::vector<std::uint8_t> read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::uint8_t> cli_stream(const Photo& photo, const std::string& flags, const fs::path& out) {
  const std::string command =
      std::string(PUPWAVE_CLI) + " compress -q '" + photo.path + "' '" + out.string() + "' " + flags;
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return read_file(out);
}

std::vector<std::uint8_t> cpp_stream(const Photo& p, const api::ImageOptions& options) {
  return api::compress_image(
      api::interleaved_view(p.samples.data(), p.width, p.height, p.channels, api::SampleType::u8), options);
}

// The C API told only what differs from its defaults (none: NULL options), so its defaults are
// compared too.
std::vector<std::uint8_t> c_stream(const Photo& p, const api::ImageOptions& o) {
  const api::ImageOptions defaults;
  pupwave_options* c = nullptr;
  const auto set = [&c] {
    if (c == nullptr) c = pupwave_options_create();
    return c;
  };
  // Setter statuses, checked after the calls (EXPECT_EQ under an unbraced if draws -Wdangling-else).
  std::vector<pupwave_status> statuses;
  if (o.rate != defaults.rate || o.target != defaults.target)
    statuses.push_back(pupwave_options_set_rate(set(), pupwave_rate(o.rate), o.target));
  if (o.transform != defaults.transform)
    statuses.push_back(pupwave_options_set_transform(set(), o.transform.c_str()));
  if (o.levels != defaults.levels) statuses.push_back(pupwave_options_set_levels(set(), o.levels));
  if (o.coder != defaults.coder) statuses.push_back(pupwave_options_set_coder(set(), pupwave_coder(o.coder)));
  if (o.effort != defaults.effort) statuses.push_back(pupwave_options_set_effort(set(), o.effort));
  if (o.tune != defaults.tune) statuses.push_back(pupwave_options_set_tune(set(), pupwave_tune(o.tune)));
  for (pupwave_status s : statuses) EXPECT_EQ(s, PUPWAVE_OK) << pupwave_last_error();
  const auto ch = std::ptrdiff_t(p.channels);
  pupwave_stream* stream = nullptr;
  EXPECT_EQ(pupwave_compress_image(c, p.samples.data(), PUPWAVE_U8, p.width, p.height, p.channels, 1, ch,
                                   ch * std::ptrdiff_t(p.width), &stream),
            PUPWAVE_OK)
      << pupwave_last_error();
  std::vector<std::uint8_t> bytes;
  if (stream)
    bytes.assign(pupwave_stream_data(stream), pupwave_stream_data(stream) + pupwave_stream_size(stream));
  pupwave_stream_destroy(stream);
  pupwave_options_destroy(c);
  return bytes;
}

// A folder of its own per test (parameterised names hold a '/').
class WithFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::replace(name.begin(), name.end(), '/', '_');
    dir_ = fs::temp_directory_path() / ("pupwave_front_doors_" + std::to_string(::getpid()) + "_" + name);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

class FrontDoors : public WithFolder, public ::testing::WithParamInterface<const char*> {};
class FrontDoorRefusals : public WithFolder {};

TEST_P(FrontDoors, CliCAndCppGiveTheSameBytes) {
  const Photo photo = read_photo(GetParam());
  for (const OptionSet& set : option_sets()) {
    const std::vector<std::uint8_t> cli = cli_stream(photo, set.flags, dir_ / "cli.pw");
    ASSERT_GT(cli.size(), 100u) << set.flags;
    EXPECT_TRUE(cpp_stream(photo, set.options) == cli) << "C++ API vs CLI '" << set.flags << "'";
    EXPECT_TRUE(c_stream(photo, set.options) == cli) << "C API vs CLI '" << set.flags << "'";
  }
}

// Settings whose stream the decoder would reject (band steps beyond the header's floats) are
// refused by the CLI, which writes no file, as by the C++ API (which C and Python call).
TEST_F(FrontDoorRefusals, ASettingTheDecoderRejectsIsRefusedByTheCliAsByTheApi) {
  const Photo photo = read_photo("camera.png");
  const fs::path out = dir_ / "step.pw";
  const std::string command = std::string(PUPWAVE_CLI) + " compress -q '" + photo.path + "' '" +
                              out.string() + "' --step 1e30 --entropy ebcot 2>" + (dir_ / "err.txt").string();
  EXPECT_NE(std::system(command.c_str()), 0);
  EXPECT_FALSE(fs::exists(out));
  const std::vector<std::uint8_t> err = read_file(dir_ / "err.txt");
  EXPECT_NE(std::string(err.begin(), err.end()).find("decoder rejects"), std::string::npos);
  EXPECT_THROW(cpp_stream(photo, options(api::ImageRate::step, 1e30, api::Coder::ebcot)), api::Error);
}

INSTANTIATE_TEST_SUITE_P(Photographs, FrontDoors,
                         ::testing::Values("camera.png", "astronaut.png", "chelsea.png", "coffee.png"),
                         [](const ::testing::TestParamInfo<const char*>& param) {
                           return std::string(param.param).substr(0, std::string(param.param).find('.'));
                         });

}  // namespace
