// One volume and one set of options give the same .pw bytes from every front door: the CLI's
// flags, the C API and the C++ API, on the real float field testimages/wmag91.float and on the
// same field stored as 16-bit integers (the options are resolved in one place,
// codec/api/api_volume_options.h). Python is compared with the CLI in
// tests/python/test_volume_front_doors.py, the HDF5 filter and numcodecs in
// tests/hdf5/test_chunk_front_doors.py.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "pupwave/pupwave.h"
#include "pupwave/pupwave.hpp"

namespace {

namespace api = pupwave::api;
namespace fs = std::filesystem;

constexpr std::size_t kEdge = 91;  // wmag91.float: 91^3 float32, x fastest

// CLI flags and the C++ options that say the same; C API calls are derived from the latter.
struct OptionSet {
  std::string flags;
  api::VolumeOptions options;
};

api::VolumeOptions options(api::VolumeRate rate, double target) {
  api::VolumeOptions o;
  o.rate = rate;
  o.target = target;
  return o;
}

// The rate modes with a target; lossless and the default are added per voxel type.
std::vector<OptionSet> rate_sets() {
  using api::VolumeRate;
  std::vector<OptionSet> sets;
  sets.push_back({"", api::VolumeOptions{}});
  sets.push_back({"--max-error 0.5", options(VolumeRate::max_error, 0.5)});
  sets.push_back({"--max-error-rel 1e-4", options(VolumeRate::max_error_rel, 1e-4)});
  sets.push_back({"--bpv 1.5", options(VolumeRate::bpv, 1.5)});
  sets.push_back({"--psnr 60", options(VolumeRate::psnr, 60.0)});
  sets.push_back({"--step 0.25", options(VolumeRate::step, 0.25)});
  sets.push_back(
      {"--max-error 2 --transform cdf97 --levels 2 --brick 32", options(VolumeRate::max_error, 2.0)});
  sets.back().options.transform = "cdf97";
  sets.back().options.levels = 2;
  sets.back().options.brick = 32;
  return sets;
}

std::vector<std::uint8_t> read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

template <class T>
void write_file(const fs::path& path, const std::vector<T>& values) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(T)));
}

std::vector<float> wmag91() {
  const std::vector<std::uint8_t> bytes = read_file(std::string(PUPWAVE_TESTIMAGES_DIR) + "/wmag91.float");
  std::vector<float> v(kEdge * kEdge * kEdge);
  EXPECT_EQ(bytes.size(), v.size() * sizeof(float));
  std::memcpy(v.data(), bytes.data(), std::min(bytes.size(), v.size() * sizeof(float)));
  return v;
}

// The field in hundredths (0..26525), as a u16 volume: integer data whose default is lossless.
std::vector<std::uint16_t> wmag91_u16(const std::vector<float>& field) {
  std::vector<std::uint16_t> v(field.size());
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = std::uint16_t(std::lround(double(field[i]) * 100.0));
  return v;
}

// The CLI codes a raw file's grid under the file's stem: "volume", as the APIs name theirs.
std::vector<std::uint8_t> cli_stream(const fs::path& raw, const char* dtype, const std::string& flags,
                                     const fs::path& out) {
  const std::string command = std::string(PUPWAVE_CLI) + " compress -q '" + raw.string() + "' '" +
                              out.string() + "' --dims 91,91,91 --dtype " + dtype + " " + flags;
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return read_file(out);
}

std::vector<std::uint8_t> cpp_stream(const void* data, api::VoxelType type,
                                     const api::VolumeOptions& options) {
  return api::compress_volume(api::VolumeView{data, {kEdge, kEdge, kEdge}, type}, options);
}

// The C API told only what differs from its defaults (none: NULL options), so its defaults are
// compared too.
std::vector<std::uint8_t> c_stream(const void* data, pupwave_type type, const api::VolumeOptions& o) {
  const api::VolumeOptions defaults;
  pupwave_options* c = nullptr;
  const auto set = [&c] {
    if (c == nullptr) c = pupwave_options_create();
    return c;
  };
  // The C rate codes of api::VolumeRate max_error .. lossless.
  constexpr pupwave_rate rates[] = {PUPWAVE_RATE_MAX_ERROR, PUPWAVE_RATE_MAX_ERROR_REL,
                                    PUPWAVE_RATE_BPV,       PUPWAVE_RATE_PSNR,
                                    PUPWAVE_RATE_STEP,      PUPWAVE_RATE_LOSSLESS};
  std::vector<pupwave_status> statuses;  // checked after the calls
  if (o.rate != defaults.rate || o.target != defaults.target)
    statuses.push_back(pupwave_options_set_rate(set(), rates[int(o.rate)], o.target));
  if (o.transform != defaults.transform)
    statuses.push_back(pupwave_options_set_transform(set(), o.transform.c_str()));
  if (o.levels != defaults.levels) statuses.push_back(pupwave_options_set_levels(set(), o.levels));
  if (o.brick != defaults.brick) statuses.push_back(pupwave_options_set_brick(set(), o.brick));
  if (o.fill_value) statuses.push_back(pupwave_options_set_fill_value(set(), *o.fill_value));
  for (pupwave_status s : statuses) EXPECT_EQ(s, PUPWAVE_OK) << pupwave_last_error();
  pupwave_stream* stream = nullptr;
  EXPECT_EQ(pupwave_compress_volume(c, data, type, kEdge, kEdge, kEdge, &stream), PUPWAVE_OK)
      << pupwave_last_error();
  std::vector<std::uint8_t> bytes;
  if (stream)
    bytes.assign(pupwave_stream_data(stream), pupwave_stream_data(stream) + pupwave_stream_size(stream));
  pupwave_stream_destroy(stream);
  pupwave_options_destroy(c);
  return bytes;
}

class VolumeFrontDoors : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pupwave_volume_front_doors_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(VolumeFrontDoors, FloatFieldGivesTheSameBytesFromTheCliCAndCpp) {
  const std::vector<float> field = wmag91();
  const fs::path raw = dir_ / "volume.f32";
  write_file(raw, field);
  for (const OptionSet& set : rate_sets()) {
    const std::vector<std::uint8_t> cli = cli_stream(raw, "f32", set.flags, dir_ / "cli.pw");
    ASSERT_GT(cli.size(), 100u) << set.flags;
    EXPECT_TRUE(cpp_stream(field.data(), api::VoxelType::f32, set.options) == cli)
        << "C++ API vs CLI '" << set.flags << "'";
    EXPECT_TRUE(c_stream(field.data(), PUPWAVE_F32, set.options) == cli)
        << "C API vs CLI '" << set.flags << "'";
  }
}

// Missing values (NaN below 8, a block of -999 given as the fill value): the same bytes from
// every door, and the C API refuses a non-finite fill value.
TEST_F(VolumeFrontDoors, FieldWithMissingValuesGivesTheSameBytesFromTheCliCAndCpp) {
  std::vector<float> field = wmag91();
  for (float& v : field)
    if (v < 8.0f) v = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < 4000; ++i) field[i] = -999.0f;
  const fs::path raw = dir_ / "volume.f32";
  write_file(raw, field);
  OptionSet set{"--max-error-rel 1e-3 --fill-value -999", options(api::VolumeRate::max_error_rel, 1e-3)};
  set.options.fill_value = -999.0;
  const std::vector<std::uint8_t> cli = cli_stream(raw, "f32", set.flags, dir_ / "cli.pw");
  ASSERT_GT(cli.size(), 100u) << set.flags;
  EXPECT_TRUE(cpp_stream(field.data(), api::VoxelType::f32, set.options) == cli) << set.flags;
  EXPECT_TRUE(c_stream(field.data(), PUPWAVE_F32, set.options) == cli) << set.flags;
  pupwave_options* c = pupwave_options_create();
  EXPECT_NE(pupwave_options_set_fill_value(c, std::numeric_limits<double>::quiet_NaN()), PUPWAVE_OK);
  EXPECT_NE(std::string(pupwave_last_error()).find("fill value"), std::string::npos) << pupwave_last_error();
  pupwave_options_destroy(c);
}

TEST_F(VolumeFrontDoors, IntegerFieldGivesTheSameBytesFromTheCliCAndCpp) {
  const std::vector<std::uint16_t> field = wmag91_u16(wmag91());
  const fs::path raw = dir_ / "volume.u16";
  write_file(raw, field);
  std::vector<OptionSet> sets = rate_sets();
  sets.push_back({"--lossless", options(api::VolumeRate::lossless, 0.0)});
  for (const OptionSet& set : sets) {
    const std::vector<std::uint8_t> cli = cli_stream(raw, "u16", set.flags, dir_ / "cli.pw");
    ASSERT_GT(cli.size(), 100u) << set.flags;
    EXPECT_TRUE(cpp_stream(field.data(), api::VoxelType::u16, set.options) == cli)
        << "C++ API vs CLI '" << set.flags << "'";
    EXPECT_TRUE(c_stream(field.data(), PUPWAVE_U16, set.options) == cli)
        << "C API vs CLI '" << set.flags << "'";
  }
}

// The default codes integer data lossless and float data within 1e-3 of its range, as the CLI
// says it does.
TEST_F(VolumeFrontDoors, TheDefaultIsLosslessForIntegersAndARelativeBoundForFloats) {
  const std::vector<float> field = wmag91();
  const std::vector<std::uint16_t> ints = wmag91_u16(field);
  const api::StreamInfo u16 = api::info(cpp_stream(ints.data(), api::VoxelType::u16, {}));
  EXPECT_TRUE(u16.lossless);
  const api::StreamInfo f32 = api::info(cpp_stream(field.data(), api::VoxelType::f32, {}));
  EXPECT_FALSE(f32.lossless);
  const auto [lo, hi] = std::minmax_element(field.begin(), field.end());
  EXPECT_NEAR(f32.max_error, 1e-3 * (double(*hi) - double(*lo)), 1e-9);
}

}  // namespace
