// The conventions every subcommand shares (docs/cli.md): --help, -q/--quiet and -v/--verbose
// on every leaf command, found by walking `pupwave --help`; "-" as stdin on the commands that
// read one file; -q silencing status lines and reports but never the data.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "cli/run_cli.h"

namespace pupwave {
namespace {
namespace fs = std::filesystem;

// The subcommand names listed under "Subcommands:" in a help text.
std::vector<std::string> subcommands_in(const std::string& help) {
  std::vector<std::string> names;
  std::istringstream lines(help);
  std::string line;
  bool listing = false;
  while (std::getline(lines, line)) {
    if (line.rfind("Subcommands:", 0) == 0) {
      listing = true;
    } else if (listing && line.size() > 2 && line.rfind("  ", 0) == 0 && line[2] != ' ') {
      names.push_back(line.substr(2, line.find(' ', 2) - 2));
    } else if (listing && line.empty()) {
      listing = false;
    }
  }
  return names;
}

// Every leaf command as its words, e.g. {"filters", "list"}.
void collect_leaves(const std::vector<std::string>& path, std::vector<std::vector<std::string>>& leaves) {
  std::vector<std::string> args = path;
  args.push_back("--help");
  const test::CliResult r = test::run_cli(args);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::vector<std::string> children = subcommands_in(r.output);
  if (children.empty() && !path.empty()) leaves.push_back(path);
  for (const std::string& child : children) {
    std::vector<std::string> next = path;
    next.push_back(child);
    collect_leaves(next, leaves);
  }
}

std::string joined(const std::vector<std::string>& words) {
  std::string s;
  for (const auto& w : words) s += (s.empty() ? "" : " ") + w;
  return s;
}

class CliConventions : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pupwave_conventions_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  const std::string camera_ = std::string(PUPWAVE_TESTIMAGES_DIR) + "/camera.png";
};

TEST_F(CliConventions, EveryLeafCommandTakesHelpQuietAndVerbose) {
  std::vector<std::vector<std::string>> leaves;
  collect_leaves({}, leaves);
  ASSERT_GE(leaves.size(), 20u);  // info, psnr, ..., filters list, mesh info, bench rd, ...
  for (const auto& leaf : leaves) {
    std::vector<std::string> args = leaf;
    args.push_back("--help");
    const test::CliResult r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 0) << joined(leaf) << ": " << r.output;
    EXPECT_NE(r.output.find("-q,--quiet"), std::string::npos) << joined(leaf) << " lacks -q";
    EXPECT_NE(r.output.find("-v,--verbose"), std::string::npos) << joined(leaf) << " lacks -v";
  }
}

TEST_F(CliConventions, QuietGenerateVolumePrintsNothingAndWritesTheVolume) {
  const fs::path out = dir_ / "gs.raw";
  const test::CliResult r =
      test::run_cli({"generate-volume", "-q", "--size", "8", "--steps", "1", out.string()});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "");
  EXPECT_EQ(fs::file_size(out), 8u * 8u * 8u * 4u);
}

TEST_F(CliConventions, VolumeOnStdoutKeepsStatusOffTheData) {
  const fs::path file = dir_ / "gs.raw";
  ASSERT_EQ(test::run_cli({"generate-volume", "--size", "8", "--steps", "1", file.string(), "-q"}).exit_code,
            0);
  // stdout alone: the volume's bytes, with the status line on stderr.
  const test::CliResult piped = test::run_shell_output(test::shell_quote(PUPWAVE_CLI) +
                                                       " generate-volume --size 8 --steps 1 - 2>/dev/null");
  EXPECT_EQ(piped.exit_code, 0);
  std::ifstream in(file, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_EQ(piped.output, bytes);
}

TEST_F(CliConventions, QuietReportsStillCheck) {
  const fs::path pw = dir_ / "camera.pw";
  ASSERT_EQ(test::run_cli({"compress", camera_, pw.string(), "--bpp", "0.5", "-q"}).exit_code, 0);
  const test::CliResult info = test::run_cli({"info", "-q", pw.string()});
  EXPECT_EQ(info.exit_code, 0) << info.output;
  EXPECT_EQ(info.output, "");
  // A damaged stream still fails under -q: the checks run, only the report is silenced.
  std::fstream f(pw, std::ios::binary | std::ios::in | std::ios::out);
  f.seekp(std::streamoff(fs::file_size(pw) / 2));
  f.put('\x5a');
  f.close();
  const test::CliResult damaged = test::run_cli({"info", "-q", pw.string()});
  EXPECT_EQ(damaged.exit_code, 1) << damaged.output;
  EXPECT_NE(damaged.output.find("pupwave: error:"), std::string::npos) << damaged.output;
}

TEST_F(CliConventions, DashReadsStdinLikeTheFile) {
  const fs::path pw = dir_ / "camera.pw", decoded = dir_ / "camera.png";
  ASSERT_EQ(test::run_cli({"compress", camera_, pw.string(), "--bpp", "0.5", "-q"}).exit_code, 0);
  ASSERT_EQ(test::run_cli({"decompress", pw.string(), decoded.string(), "-q"}).exit_code, 0);
  const std::string cli = test::shell_quote(PUPWAVE_CLI);
  // psnr: B from stdin gives the same table as B by name.
  const test::CliResult by_name = test::run_cli({"psnr", camera_, decoded.string()});
  const test::CliResult piped = test::run_shell_output(cli + " psnr " + test::shell_quote(camera_) + " - < " +
                                                       test::shell_quote(decoded));
  ASSERT_EQ(by_name.exit_code, 0) << by_name.output;
  EXPECT_EQ(piped.exit_code, 0);
  EXPECT_EQ(piped.output, by_name.output);
  // info: the stream described from stdin as from the file (the name aside).
  const test::CliResult info = test::run_shell_output(cli + " info - < " + test::shell_quote(pw));
  EXPECT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("bytes"), std::string::npos) << info.output;
  const test::CliResult info_file = test::run_cli({"info", pw.string()});
  EXPECT_EQ(info.output.substr(info.output.find(':')), info_file.output.substr(info_file.output.find(':')));
}

}  // namespace
}  // namespace pupwave
