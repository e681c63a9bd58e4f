// Where outputs go: a regular file atomically, anything else in place. A FIFO, a character
// device (private copies of /dev/null and /dev/full made with mknod, never the system's own
// nodes) and a socket are written and stay what they were; a block device is refused; links
// are followed and stay links; errors name the user's path and the system's reason.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <iterator>
#include <string>
#include <vector>

#include "cli/run_cli.h"

namespace pupwave {
namespace {
namespace fs = std::filesystem;

std::vector<char> slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Reads a FIFO to its end (in a thread: opening a FIFO for writing waits for a reader).
std::future<std::vector<char>> read_fifo(const fs::path& fifo) {
  return std::async(std::launch::async, [fifo] { return slurp(fifo); });
}

bool is_char_device(const fs::path& p) {
  struct stat st {};
  return ::lstat(p.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}

class CliOutputs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pupwave_outputs_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    // The reference: the same command's output as a regular file.
    reference_ = dir_ / "reference.pw";
    const auto r = compress(reference_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  void TearDown() override { fs::remove_all(dir_); }

  test::CliResult compress(const fs::path& out) const {
    return test::run_cli({"compress", camera_, out.string(), "--bpp", "0.5", "-q"});
  }
  // A private device node: the tests run as root in CI; a non-root run cannot make one.
  fs::path make_node(const std::string& name, mode_t type, unsigned major_id, unsigned minor_id) const {
    const fs::path node = dir_ / name;
    if (::mknod(node.c_str(), type | 0666, makedev(major_id, minor_id)) != 0)
      ADD_FAILURE() << "mknod " << node << ": " << std::strerror(errno) << " (these tests need root)";
    return node;
  }

  fs::path dir_, reference_;
  const std::string camera_ = std::string(PUPWAVE_TESTIMAGES_DIR) + "/camera.png";
};

TEST_F(CliOutputs, FifoIsWrittenInPlaceAndStaysAFifo) {
  const fs::path fifo = dir_ / "pipe.pw";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  auto reader = read_fifo(fifo);
  const auto r = compress(fifo);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(reader.get(), slurp(reference_));
  EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo)));
}

TEST_F(CliOutputs, DecompressToAFifoNeedsAFormatAndThenWritesIt) {
  const fs::path fifo = dir_ / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // No extension and no --format: refused before anything is decoded or opened (no reader needed).
  const auto refused = test::run_cli({"decompress", reference_.string(), fifo.string()});
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_NE(refused.output.find(fifo.string() + ": its name has no extension"), std::string::npos)
      << refused.output;
  auto reader = read_fifo(fifo);
  const auto r = test::run_cli({"decompress", reference_.string(), fifo.string(), "--format", "pgm", "-q"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const std::vector<char> pgm = reader.get();
  ASSERT_GT(pgm.size(), 512u * 512u);
  EXPECT_EQ(std::string(pgm.begin(), pgm.begin() + 2), "P5");
  EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo)));
}

TEST_F(CliOutputs, NullDeviceCopyTakesTheOutputAndStaysADevice) {
  const fs::path null = make_node("null", S_IFCHR, 1, 3);
  ASSERT_TRUE(is_char_device(null));
  const auto r = compress(null);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(is_char_device(null)) << "the device node was replaced";
  const auto d = test::run_cli({"decompress", reference_.string(), null.string(), "--format", "png", "-q"});
  EXPECT_EQ(d.exit_code, 0) << d.output;
  EXPECT_TRUE(is_char_device(null));
}

TEST_F(CliOutputs, FullDeviceCopyGivesTheReasonAndStaysADevice) {
  const fs::path full = make_node("full", S_IFCHR, 1, 7);
  ASSERT_TRUE(is_char_device(full));
  const auto r = compress(full);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(full.string() + ": No space left on device"), std::string::npos) << r.output;
  EXPECT_TRUE(is_char_device(full)) << "the device node was replaced";
  const auto d = test::run_cli({"decompress", reference_.string(), full.string(), "--format", "png"});
  EXPECT_EQ(d.exit_code, 1) << d.output;
  EXPECT_NE(d.output.find(full.string() + ": No space left on device"), std::string::npos) << d.output;
  // Other writers (image conversion, raw volumes) reach the same end.
  const auto c = test::run_cli({"convert", camera_, full.string(), "--format", "ppm"});
  EXPECT_NE(c.output.find(full.string() + ": No space left on device"), std::string::npos) << c.output;
  const auto g = test::run_cli({"generate-volume", "--size", "8", "--steps", "2", full.string()});
  EXPECT_NE(g.output.find(full.string() + ": No space left on device"), std::string::npos) << g.output;
  EXPECT_TRUE(is_char_device(full));
  // Only the nodes and the reference: no temporary file is left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 2);
}

TEST_F(CliOutputs, BlockDeviceIsRefusedAndLeftAlone) {
  // Never opened: refused from its type alone (7,0 is the first loop device's number).
  const fs::path block = make_node("disk", S_IFBLK, 7, 0);
  const auto r = compress(block);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(block.string() + ": it is a block device"), std::string::npos) << r.output;
  struct stat st {};
  ASSERT_EQ(::lstat(block.c_str(), &st), 0);
  EXPECT_TRUE(S_ISBLK(st.st_mode));
}

TEST_F(CliOutputs, SocketIsConnectedToAndWritten) {
  const fs::path path = dir_ / "sock";
  const int server = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(server, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, path.c_str(), sizeof address.sun_path - 1);
  ASSERT_EQ(::bind(server, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
  ASSERT_EQ(::listen(server, 1), 0);
  auto received = std::async(std::launch::async, [server] {
    std::vector<char> bytes;
    const int peer = ::accept(server, nullptr, nullptr);
    char buffer[4096];
    for (ssize_t n; (n = ::read(peer, buffer, sizeof buffer)) > 0;)
      bytes.insert(bytes.end(), buffer, buffer + n);
    ::close(peer);
    return bytes;
  });
  const auto r = compress(path);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(received.get(), slurp(reference_));
  ::close(server);
  EXPECT_TRUE(fs::is_socket(fs::symlink_status(path)));
}

TEST_F(CliOutputs, LinksAreFollowedAndStayLinks) {
  const fs::path file = dir_ / "file.pw", link = dir_ / "link.pw";
  std::ofstream(file) << "old";
  fs::create_symlink(file.filename(), link);  // relative, as users make them
  ASSERT_EQ(compress(link).exit_code, 0);
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
  EXPECT_EQ(slurp(file), slurp(reference_));
  // A dangling link: the file it names is made, the link stays.
  const fs::path dangling = dir_ / "dangling.pw", named = dir_ / "named.pw";
  fs::create_symlink(named, dangling);
  ASSERT_EQ(compress(dangling).exit_code, 0);
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dangling)));
  EXPECT_EQ(slurp(named), slurp(reference_));
}

TEST_F(CliOutputs, FileWrittenAgainKeepsItsMode) {
  const fs::path file = dir_ / "private.pw";
  std::ofstream(file) << "old";
  fs::permissions(file, fs::perms::owner_read | fs::perms::owner_write);
  ASSERT_EQ(compress(file).exit_code, 0);
  EXPECT_EQ(fs::status(file).permissions(), fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_EQ(slurp(file), slurp(reference_));
}

TEST_F(CliOutputs, UndecidableImageFormatIsRefusedBeforeDecoding) {
  const fs::path out = dir_ / "decoded";
  const auto r = test::run_cli({"decompress", reference_.string(), out.string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(out.string() + ": its name has no extension"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  const auto odd = test::run_cli({"decompress", reference_.string(), (dir_ / "decoded.xyz").string()});
  EXPECT_NE(odd.output.find("unsupported image format '.xyz'"), std::string::npos) << odd.output;
  const auto named =
      test::run_cli({"decompress", reference_.string(), out.string(), "--format", "png", "-q"});
  EXPECT_EQ(named.exit_code, 0) << named.output;
  EXPECT_EQ(slurp(out).at(1), 'P');  // "\x89PNG"
}

TEST_F(CliOutputs, StdoutTakesTheSameBytes) {
  const auto r = test::run_shell_output(test::shell_quote(PUPWAVE_CLI) + " compress " + camera_ +
                                        " - --bpp 0.5 2>/dev/null");
  EXPECT_EQ(r.exit_code, 0);
  const std::vector<char> expected = slurp(reference_);
  EXPECT_EQ(std::vector<char>(r.output.begin(), r.output.end()), expected);
}

}  // namespace
}  // namespace pupwave
