// `pupwave info` on image files and on compressed streams (valid and damaged).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "cli/run_cli.h"

namespace pupwave {
namespace {
namespace fs = std::filesystem;

TEST(InfoCli, DescribesImagesAndStreams) {
  const fs::path dir = fs::temp_directory_path() / ("pupwave_info_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string coffee = std::string(PUPWAVE_TESTIMAGES_DIR) + "/coffee.png";
  auto r = test::run_cli({"info", coffee});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("600 x 400, 3 channels"), std::string::npos) << r.output;

  const fs::path pw = dir / "coffee.pw";
  r = test::run_cli({"compress", coffee, pw.string(), "--bpp", "0.5", "--transform", "cdf53"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = test::run_cli({"info", pw.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("pupwave stream"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("600 x 400"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("cdf53"), std::string::npos) << r.output;

  // Truncate the stream: info must report the damage, not crash or print a description.
  std::vector<char> bytes(fs::file_size(pw));
  std::ifstream(pw, std::ios::binary).read(bytes.data(), std::streamsize(bytes.size()));
  std::ofstream(pw, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), std::streamsize(bytes.size() / 2));
  r = test::run_cli({"info", pw.string()});
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("truncated"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

TEST(InfoCli, DescribesVolumeStreams) {
  const fs::path dir = fs::temp_directory_path() / ("pupwave_vinfo_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path pw = dir / "sphere.pw";
  auto r = test::run_cli({"compress", std::string(PUPWAVE_TESTIMAGES_DIR) + "/sphere_ls.vdb", pw.string(),
                          "--max-error", "0.002"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = test::run_cli({"info", pw.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("volume stream"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("level set"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("max error   0.002"), std::string::npos) << r.output;
  fs::resize_file(pw, fs::file_size(pw) - 7);
  r = test::run_cli({"info", pw.string()});
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("pupwave: error:"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pupwave
