// Hostile and broken volume input: a clear error, a non-zero exit, no crash and no output file.
#include <fstream>
#include <iterator>

#include "tools/volume_io.h"
#include "volumes/volume_test_util.h"

namespace pupwave::test {
namespace {

// The message of the runtime_error `f` throws (fails the test when it throws nothing).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return {};
}

std::vector<char> file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& p, const std::vector<char>& bytes) {
  std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

void expect_has(const std::string& text, const std::string& needle) {
  EXPECT_NE(text.find(needle), std::string::npos) << "expected '" << needle << "' in: " << text;
}

TEST_F(VolumeTest, RawTruncatedWrongDimsAbsurdDims) {
  const fs::path p = dir_ / "v.raw";
  write_bytes(p, std::vector<char>(7 * 5 * 3 * 4 - 1, 0));  // one byte short of 7x5x3 f32
  const std::string truncated = error_of([&] { cli::read_raw_volume(p, {7, 5, 3}, VoxelType::f32); });
  expect_has(truncated, "419 bytes");
  expect_has(truncated, "needs 420");
  expect_has(error_of([&] { cli::read_raw_volume(p, {7, 5, 4}, VoxelType::u8); }), "--dims 7,5,4");
  expect_has(error_of([&] {
               cli::read_raw_volume(p, {100000, 100000, 100000}, VoxelType::f32);
             }),
             "too large");
  const std::size_t big = std::size_t(1) << 40;  // product overflows 64 bits
  expect_has(error_of([&] { cli::read_raw_volume(p, {big, big, big}, VoxelType::f64); }), "too large");
  expect_has(error_of([&] {
               cli::read_raw_volume(dir_ / "none.raw", {1, 1, 1}, VoxelType::u8);
             }),
             "no such file");
}

// Every broken .vdb given to `pupwave lod`: exit 1 with pupwave's message, nothing written.
void expect_lod_rejects(const fs::path& dir, const fs::path& in, const std::string& needle) {
  const CliResult r = run_cli({"lod", in.string(), (dir / "out.vdb").string(), "--levels", "1"});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  expect_has(r.output, "pupwave: error: ");
  expect_has(r.output, needle);
  EXPECT_FALSE(fs::exists(dir / "out.vdb"));
}

TEST_F(VolumeTest, CorruptVdbFiles) {
  const std::vector<char> good = file_bytes(testimage("sphere_ls.vdb"));
  ASSERT_GT(good.size(), 1000u);
  write_bytes(dir_ / "truncated.vdb",
              std::vector<char>(good.begin(), good.begin() + std::ptrdiff_t(good.size() / 2)));
  write_bytes(dir_ / "header.vdb", std::vector<char>(good.begin(), good.begin() + 40));
  std::vector<char> magic = good;
  magic[0] = char(magic[0] ^ 0x5A);
  write_bytes(dir_ / "magic.vdb", magic);
  write_bytes(dir_ / "text.vdb", std::vector<char>(300, 'x'));
  write_bytes(dir_ / "empty.vdb", {});
  for (const char* name : {"truncated.vdb", "header.vdb", "magic.vdb", "text.vdb", "empty.vdb"})
    expect_lod_rejects(dir_, dir_ / name, "cannot read");
  expect_lod_rejects(dir_, dir_ / "missing.vdb", "no such file");
  EXPECT_EQ(files_in_dir(), 5u);  // only the inputs
}

// Bytes flipped inside the grid data: OpenVDB files carry no checksum, so some flips decode to
// other values; whatever happens must be a clean exit (0 or 1), never a crash.
TEST_F(VolumeTest, FlippedBytesNeverCrash) {
  const std::vector<char> good = file_bytes(testimage("dodeca_fog.vdb"));
  std::mt19937 rng(9);
  for (int trial = 0; trial < 12; ++trial) {
    std::vector<char> bad = good;
    for (int f = 0; f < 4; ++f) bad[rng() % bad.size()] ^= char(1 + rng() % 255);
    write_bytes(dir_ / "bad.vdb", bad);
    const CliResult r =
        run_cli({"lod", (dir_ / "bad.vdb").string(), (dir_ / "out.vdb").string(), "--levels", "1"});
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1)
        << "trial " << trial << ": exit " << r.exit_code << r.output;
    EXPECT_EQ(r.output.find("terminate called"), std::string::npos) << r.output;
    if (r.exit_code != 0) {
      EXPECT_FALSE(fs::exists(dir_ / "out.vdb"));
    }
    fs::remove(dir_ / "out.vdb");
  }
}

// A few bytes of file can declare an active tile spanning billions of voxels: refused before
// any dense allocation, in the library and through the CLI.
TEST_F(VolumeTest, HugeActiveTileIsRefused) {
  auto g = openvdb::FloatGrid::create(0.0f);
  g->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(4095)), 1.0f, true);  // one root-level tile
  g->setName("huge");
  write_grids({g}, dir_ / "huge.vdb");
  ASSERT_LT(fs::file_size(dir_ / "huge.vdb"), 100000u);
  expect_has(error_of([&] { cli::read_vdb_dense(dir_ / "huge.vdb"); }), "more than the limit");
  expect_lod_rejects(dir_, dir_ / "huge.vdb", "more than the limit");
}

TEST_F(VolumeTest, LodOutputProblems) {
  const CliResult dir_out = run_cli({"lod", testimage("sphere_ls.vdb"), dir_.string(), "--levels", "1"});
  EXPECT_EQ(dir_out.exit_code, 1);
  expect_has(dir_out.output, "is a directory");
  const CliResult missing =
      run_cli({"lod", testimage("sphere_ls.vdb"), (dir_ / "no" / "o.vdb").string(), "--levels", "1"});
  EXPECT_EQ(missing.exit_code, 1);
  expect_has(missing.output, "does not exist");
  EXPECT_EQ(files_in_dir(), 0u);
}

}  // namespace
}  // namespace pupwave::test
