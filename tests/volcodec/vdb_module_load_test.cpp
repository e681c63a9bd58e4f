// The CLI loads OpenVDB only for .vdb files (tools/vdb_module.h): a raw volume's compress and
// decompress never map libopenvdb, a .vdb command loads the module, and an installed layout
// (binary and module in one folder) loads the module from beside the binary.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli/run_cli.h"

namespace pupwave {
namespace {
namespace fs = std::filesystem;
using test::shell_quote;

// The command's output with ld.so's list of the shared objects it opened (LD_DEBUG=files).
test::CliResult run_traced(const std::string& exe, const std::vector<std::string>& args) {
  std::string command = "LD_DEBUG=files " + shell_quote(exe);
  for (const auto& a : args) command += " " + shell_quote(a);
  return test::run_shell_output(command + " 2>&1 </dev/null");
}

bool opened(const std::string& trace, const std::string& library) {
  return trace.find("file=" + library) != std::string::npos || trace.find("/" + library) != std::string::npos;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pupwave_vdb_module_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(VdbModuleLoad, RawVolumeCommandsNeverLoadOpenVdb) {
  const fs::path dir = fresh_dir("raw");
  const std::string in = std::string(PUPWAVE_TESTIMAGES_DIR) + "/wmag91.float";
  const std::string pw = (dir / "w.pw").string(), out = (dir / "w.raw").string();
  const auto enc = run_traced(
      PUPWAVE_CLI, {"compress", in, pw, "--dims", "91,91,91", "--dtype", "f32", "--max-error-rel", "1e-3"});
  ASSERT_EQ(enc.exit_code, 0) << enc.output;
  const auto dec = run_traced(PUPWAVE_CLI, {"decompress", pw, out});
  ASSERT_EQ(dec.exit_code, 0) << dec.output;
  EXPECT_EQ(fs::file_size(out), fs::file_size(in));
  for (const auto* r : {&enc, &dec}) {
    EXPECT_FALSE(opened(r->output, "libopenvdb")) << r->output;
    EXPECT_FALSE(opened(r->output, "libpupwave_vdb")) << r->output;
  }
  const auto version = run_traced(PUPWAVE_CLI, {"--version"});
  EXPECT_FALSE(opened(version.output, "libopenvdb")) << version.output;
  fs::remove_all(dir);
}

TEST(VdbModuleLoad, VdbFileLoadsTheModule) {
  const std::string vdb = std::string(PUPWAVE_TESTIMAGES_DIR) + "/sphere_ls.vdb";
  const auto info = run_traced(PUPWAVE_CLI, {"info", vdb});
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("OpenVDB file, 1 grid(s)"), std::string::npos) << info.output;
  EXPECT_TRUE(opened(info.output, "libpupwave_vdb")) << info.output;
  EXPECT_TRUE(opened(info.output, "libopenvdb")) << info.output;
}

// `cmake --install` puts the module beside the binary (bin/); the binary must find it there.
TEST(VdbModuleLoad, ModuleBesideTheBinaryIsUsed) {
  const fs::path dir = fresh_dir("installed");
  const fs::path cli = fs::path(PUPWAVE_CLI);
  fs::copy_file(cli, dir / "pupwave");
  fs::copy_file(cli.parent_path() / "libpupwave_vdb.so", dir / "libpupwave_vdb.so");
  const std::string vdb = std::string(PUPWAVE_TESTIMAGES_DIR) + "/sphere_ls.vdb";
  const auto info = run_traced((dir / "pupwave").string(), {"info", vdb});
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("file=" + (dir / "libpupwave_vdb.so").string()), std::string::npos)
      << info.output;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pupwave
