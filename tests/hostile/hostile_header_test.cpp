// Hostile headers with valid checksums: each runs the release CLI
// under a 1 GiB address-space limit and a few seconds of CPU time (a 60 s wall-clock guard), and must end
// with a clear error or a correct small output. Unbounded, these would take up to 10 GiB and minutes
// (docs/bitstream.md, Decoder bounds).
#include <gtest/gtest.h>
#include <zstd.h>

#include <bit>
#include <filesystem>
#include <fstream>
#include <limits>

#include "bounded_child.h"
#include "codec/entropy/codeblocks.h"
#include "codec/format/byte_io.h"
#include "codec/format/chunks.h"
#include "codec/image/image_stream.h"
#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_format.h"
#include "tools/volume_io.h"
#include "transforms/separable.h"

namespace pupwave {
namespace {

namespace fs = std::filesystem;
using testing::run_cli_bounded;

fs::path scratch_dir() {
  return fs::temp_directory_path() / ("pupwave_hostile_" + std::to_string(::getpid()));
}

fs::path scratch(const std::string& name) {
  fs::create_directories(scratch_dir());
  return scratch_dir() / name;
}

// Removes the scratch files when the program ends.
class ScratchCleanup : public ::testing::Environment {
 public:
  void TearDown() override { fs::remove_all(scratch_dir()); }
};
[[maybe_unused]] const auto* const kCleanup = ::testing::AddGlobalTestEnvironment(new ScratchCleanup);

void save(const fs::path& p, const std::vector<std::uint8_t>& bytes) {
  std::ofstream(p, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// A consistent grey image stream in which every code-block is empty (a few hundred bytes
// whatever the size), with transform `spec`.
std::vector<std::uint8_t> empty_image_stream(std::size_t width, std::size_t height, int levels,
                                             const std::string& spec = "cdf97") {
  StreamHeader h;
  h.dims = {width, height, 1};
  h.levels = levels;
  h.spec = spec;
  const auto bands = subbands(h.dims, levels);
  h.steps.assign(bands.size(), 1.0f);
  const auto blocks = partition_blocks(bands, levels, 1, h.block_size());
  const std::vector<BlockEntry> index(blocks.size());
  return write_container(h, index, std::vector<std::vector<std::uint8_t>>(std::size_t(levels) + 1));
}

void put_f64(ByteWriter& w, double v) {
  const auto bits = std::bit_cast<std::uint64_t>(v);
  w.u32(std::uint32_t(bits));
  w.u32(std::uint32_t(bits >> 32));
}

VolumeStreamHeader volume_header(const Extent& dims, bool sparse, std::uint32_t bricks) {
  VolumeStreamHeader h;
  h.spec = "cdf97";
  h.levels = 2;
  h.brick_chunks = bricks;
  VolumeGrid g;
  g.name = "density";
  g.volume.dims = dims;
  if (sparse) g.volume.active.assign(1, 1);  // the header's sparse marker
  h.grids.push_back(g);
  return h;
}

// zstd frame of `count` bytes `fill` but the last (`last`), compressed in pieces (the test
// never holds them all).
std::vector<std::uint8_t> zero_frame(std::size_t count, std::uint8_t last = 0, std::uint8_t fill = 0) {
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
  ZSTD_CCtx_setPledgedSrcSize(cctx, count);
  const std::vector<std::uint8_t> zeros(std::size_t(1) << 20, fill);
  std::vector<std::uint8_t> out, buf(ZSTD_CStreamOutSize());
  for (std::size_t done = 0; done < count;) {
    std::size_t n = std::min(zeros.size(), count - done);
    if (done + n == count && n > 1) --n;  // the last byte goes alone
    done += n;
    ZSTD_inBuffer in{done == count ? &last : zeros.data(), n, 0};
    const auto mode = done == count ? ZSTD_e_end : ZSTD_e_continue;
    for (bool finished = false; !finished;) {
      ZSTD_outBuffer o{buf.data(), buf.size(), 0};
      const std::size_t left = ZSTD_compressStream2(cctx, &o, &in, mode);
      out.insert(out.end(), buf.begin(), buf.begin() + std::ptrdiff_t(o.pos));
      finished = mode == ZSTD_e_end ? left == 0 : in.pos == in.size;
    }
  }
  ZSTD_freeCCtx(cctx);
  return out;
}

void expect_refused(const testing::ChildResult& r, const std::string& message) {
  EXPECT_FALSE(r.timed_out) << r.output;
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("pupwave: error:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
  EXPECT_LT(r.cpu_seconds, 5.0);
}

TEST(HostileHeader, HugeEmptyImageIsRefusedByTheDecodeLimit) {
  // 65536 x 32768 grey, every block empty: unbounded, 262 s, 8.1 GiB and a 2 GiB PGM.
  const auto bytes = empty_image_stream(65536, 32768, 8);
  EXPECT_LT(bytes.size(), 1000u);
  save(scratch("huge.pw"), bytes);
  const auto r = run_cli_bounded({"decompress", scratch("huge.pw"), scratch("huge.pgm"), "--threads", "2"});
  expect_refused(r, "exceeds the decode limit of 268435456");
  EXPECT_FALSE(fs::exists(scratch("huge.pgm")));
  // info makes no output: it describes the stream within the bounds, without a limit.
  const auto info = run_cli_bounded({"info", scratch("huge.pw")});
  EXPECT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("65536 x 32768"), std::string::npos) << info.output;
  EXPECT_LT(info.cpu_seconds, 5.0);
  // --max-pixels raises the limit; a lower one refuses a smaller image.
  save(scratch("small.pw"), empty_image_stream(300, 200, 3));
  expect_refused(
      run_cli_bounded({"decompress", scratch("small.pw"), scratch("s.pgm"), "--max-pixels", "59999"}),
      "pixels of 60000 exceeds the decode limit of 59999");
  EXPECT_EQ(run_cli_bounded({"decompress", scratch("small.pw"), scratch("s.pgm"), "--max-pixels", "60000"})
                .exit_code,
            0);
}

TEST(HostileHeader, ReducedLevelDecodeAllocatesOnlyItsLevel) {
  // 16384^2 empty at --level 5: full-size planes would be 2.0 GiB for a 512^2 output.
  save(scratch("big.pw"), empty_image_stream(16384, 16384, 6));
  const auto r = run_cli_bounded(
      {"decompress", scratch("big.pw"), scratch("big5.pgm"), "--level", "5", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_LT(r.cpu_seconds, 5.0);
  std::ifstream in(scratch("big5.pgm"), std::ios::binary);
  std::string magic, w, h;
  in >> magic >> w >> h;
  EXPECT_EQ(magic + " " + w + " " + h, "P5 512 512");
  // The full size is exactly the default limit: accepted by the header check (not run here).
  EXPECT_EQ(std::size_t(16384) * 16384, kDefaultMaxDecodePixels);
}

TEST(HostileHeader, BrickBlockCountsAreCheckedBeforeTheIndexIsStored) {
  // 100 BRIK chunks each claiming 2^20 code-blocks: unchecked, 37 s and 2.8 GiB.
  std::vector<std::uint8_t> bytes;
  write_volume_signature(bytes);
  write_header_chunk(bytes, volume_header({256, 256, 256}, false, 100));
  for (std::uint32_t b = 0; b < 100; ++b) {
    std::vector<std::uint8_t> p;
    ByteWriter w(p);
    w.u32(0);
    w.u32(b);
    put_f64(w, 1.0);
    w.u32(1u << 20);
    w.u32(4);
    w.u32(0);
    w.u32(0);
    write_chunk(bytes, "BRIK", p);
  }
  save(scratch("bricks.pw"), bytes);
  expect_refused(
      run_cli_bounded({"decompress", scratch("bricks.pw"), scratch("bricks.raw"), "--threads", "2"}),
      "block count does not match the brick geometry");
}

// A sparse box grid of n^3 voxels (`type`) whose MASK holds every voxel inactive background but
// the last (state `last`), with the BRIK chunks `bricks` (each a framed-ready payload).
std::vector<std::uint8_t> sparse_box_stream(std::size_t n, VoxelType type, std::uint8_t last = 0,
                                            const VolumeStreamHeader* like = nullptr,
                                            const std::vector<std::vector<std::uint8_t>>& bricks = {},
                                            std::uint8_t fill = 0) {
  VolumeStreamHeader h = like != nullptr ? *like : volume_header({n, n, n}, true, 0);
  h.grids[0].volume.dims = {n, n, n};
  h.grids[0].volume.type = type;
  h.brick_chunks = std::uint32_t(bricks.size());
  std::vector<std::uint8_t> bytes;
  write_volume_signature(bytes);
  write_header_chunk(bytes, h);
  std::vector<std::uint8_t> p;
  ByteWriter w(p);
  const auto frame = zero_frame(n * n * n, last, fill);
  w.u32(0);
  w.u32(std::uint32_t(frame.size()));
  w.bytes(frame);
  w.u32(0);  // no inactive_other values: an empty zstd frame of them (version 7)
  std::vector<std::uint8_t> none(ZSTD_compressBound(0));
  none.resize(ZSTD_compress(none.data(), none.size(), nullptr, 0, 1));
  w.u32(std::uint32_t(none.size()));
  w.bytes(none);
  write_chunk(bytes, "MASK", p);
  for (const auto& b : bricks) write_chunk(bytes, "BRIK", b);
  return bytes;
}

TEST(HostileHeader, EmptySparseRegionsCostNothing) {
  // The unbounded cost shows in memory (over the 1 GiB address-space limit), not only in time; wall
  // time is recorded, not asserted (a loaded machine makes it vary), and a hang is killed after a
  // minute.
  constexpr double kGuard = 60.0;
  // Sparse 512^3 and 1024^3, every voxel inactive (4.4 KB, 33 KB): unbounded, 27 s and 2.8 GiB,
  // and std::bad_alloc after 35 s and 10 GiB. To .vdb they decode to empty grids; info reads them.
  for (const std::size_t n : {512, 1024}) {
    const std::string name = "empty" + std::to_string(n);
    const auto bytes = sparse_box_stream(n, VoxelType::f32);
    EXPECT_LT(bytes.size(), 100'000u);
    save(scratch(name + ".pw"), bytes);
    const auto r = run_cli_bounded(
        {"decompress", scratch(name + ".pw"), scratch(name + ".vdb"), "--threads", "2"}, kGuard);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // The stream, one mask batch and the program (unbounded: 2.8 GiB at 512^3).
    EXPECT_LT(r.max_rss_kb, 200 * 1024) << n;
    ::testing::Test::RecordProperty(
        name + "_vdb", std::to_string(r.seconds) + " s, " + std::to_string(r.max_rss_kb) + " KiB resident");
    const auto grids = cli::read_vdb(scratch(name + ".vdb"));
    ASSERT_EQ(grids.size(), 1u);
    EXPECT_EQ(grids[0].active_voxels(), 0u);
    const auto info = run_cli_bounded({"info", scratch(name + ".pw")}, kGuard);
    EXPECT_EQ(info.exit_code, 0) << info.output;
    EXPECT_NE(info.output.find("0 active voxels"), std::string::npos) << info.output;
  }
  // Raw output is the dense box: the limit counts its voxels, so 1024^3 is refused before anything
  // is allocated or written, and 512^3 u8 (a 128 MiB file) is decoded.
  expect_refused(run_cli_bounded({"decompress", scratch("empty1024.pw"), scratch("empty1024.raw")}),
                 "voxels of all grids of 1073741824 exceeds the decode limit");
  EXPECT_FALSE(fs::exists(scratch("empty1024.raw")));
  save(scratch("u8.pw"), sparse_box_stream(512, VoxelType::u8, 2));  // last voxel: -background
  const auto raw =
      run_cli_bounded({"decompress", scratch("u8.pw"), scratch("u8.raw"), "--threads", "2"}, kGuard);
  ASSERT_EQ(raw.exit_code, 0) << raw.output;
  EXPECT_EQ(fs::file_size(scratch("u8.raw")), std::size_t(512) * 512 * 512);
  fs::remove(scratch("u8.raw"));
  // A mask whose every voxel is inactive with value -background (a level set's inside) is not
  // empty: its .vdb output holds 2^30 voxels, over the limit, refused while the mask is read.
  save(scratch("inside.pw"), sparse_box_stream(1024, VoxelType::f32, 2, nullptr, {}, 2));
  for (const char* cmd : {"decompress", "info"}) {
    std::vector<std::string> args{cmd, scratch("inside.pw")};
    if (std::string(cmd) == "decompress") args.push_back(scratch("inside.vdb"));
    expect_refused(run_cli_bounded(args), "voxels to decode of 268697600 exceeds the decode limit");
  }
  EXPECT_FALSE(fs::exists(scratch("inside.vdb")));
}

TEST(HostileHeader, OneActiveVoxelInTheCornerOfAHugeSparseBox) {
  // A 1024^3 box whose only active voxel is its last one: the .vdb decode allocates that brick.
  VolumeGrid g;
  g.name = "corner";
  g.volume = Volume({64, 64, 64}, VoxelType::f32);
  g.volume.active.assign(g.volume.count(), 0);
  g.volume.active.back() = 1;
  g.volume.samples.back() = 1.5;
  VolumeEncodeOptions o;
  o.target = 1e-3;
  o.brick = 64;
  const auto small = encode_volumes({g}, o).bytes;
  const ParsedVolumeStream parsed = parse_volume_stream(small);
  ASSERT_EQ(parsed.bricks.size(), 1u);
  std::vector<std::uint8_t> brick;
  ChunkReader chunks(small, kVolumeSignature, kVolumeStreamVersion, "volume stream");
  while (!chunks.at_end())
    if (const Chunk c = chunks.next(); c.is("BRIK")) brick.assign(c.payload.begin(), c.payload.end());
  const std::uint32_t last = 16 * 16 * 16 - 1;  // the brick index is the payload's second u32
  for (int i = 0; i < 4; ++i) brick[std::size_t(4 + i)] = std::uint8_t(last >> (8 * i));
  save(scratch("corner.pw"), sparse_box_stream(1024, VoxelType::f32, 1, &parsed.header, {brick}));
  const auto r =
      run_cli_bounded({"decompress", scratch("corner.pw"), scratch("corner.vdb"), "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_LT(r.cpu_seconds, 5.0);
  EXPECT_LT(r.max_rss_kb, 200 * 1024);
  ::testing::Test::RecordProperty(
      "corner_vdb", std::to_string(r.seconds) + " s, " + std::to_string(r.max_rss_kb) + " KiB resident");
  const auto grids = cli::read_vdb(scratch("corner.vdb"));
  ASSERT_EQ(grids.size(), 1u);
  EXPECT_EQ(grids[0].active_voxels(), 1u);
  ASSERT_EQ(grids[0].blocks.size(), 1u);
  const VolumeBlock& b = grids[0].blocks[0];
  bool found = false;
  for (std::size_t i = 0; i < b.volume.count(); ++i)
    if (b.volume.is_active(i)) {
      const std::size_t x = i % b.volume.dims[0], y = i / b.volume.dims[0] % b.volume.dims[1],
                        z = i / b.volume.dims[0] / b.volume.dims[1];
      EXPECT_EQ(b.origin[0] + std::int64_t(x), 1023);
      EXPECT_EQ(b.origin[1] + std::int64_t(y), 1023);
      EXPECT_EQ(b.origin[2] + std::int64_t(z), 1023);
      EXPECT_NEAR(b.volume.samples[i], 1.5, 1e-3);
      found = true;
    }
  EXPECT_TRUE(found);
  // Raw output would be the 1 GiB box: refused by the limit, nothing written.
  expect_refused(run_cli_bounded({"decompress", scratch("corner.pw"), scratch("corner.raw")}),
                 "exceeds the decode limit");
  EXPECT_FALSE(fs::exists(scratch("corner.raw")));
}

TEST(HostileHeader, TransformSpecsInAStreamAreBoundedBeforeDesign) {
  // cinpact c=200 with 2e6 samples: unbounded, 289 s and 12 GiB designing before any data is read.
  save(scratch("cinpact.pw"), empty_image_stream(64, 64, 2, "pups:cinpact(c=200,sigma=4,samples=2000000)"));
  expect_refused(run_cli_bounded({"decompress", scratch("cinpact.pw"), scratch("c.pgm")}),
                 "support 400 over 64");
  // `info` on bspline degree 20 with 5e7 samples: unbounded, still running at 300 s.
  save(scratch("bspline.pw"), empty_image_stream(64, 64, 2, "pups:bspline(degree=20,samples=50000000)"));
  expect_refused(run_cli_bounded({"info", scratch("bspline.pw")}), "samples outside 1..1000000");
  // Kin: a long polynomial, a large extension.
  std::string coeffs = "1";
  for (int i = 0; i < 64; ++i) coeffs += ":1";  // 65 coefficients
  save(scratch("poly.pw"),
       empty_image_stream(64, 64, 2, "pups:polynomial(coeffs=" + coeffs + ",domain=-2:2)"));
  expect_refused(run_cli_bounded({"info", scratch("poly.pw")}), "more than 64 polynomial coefficients");
  save(scratch("ext.pw"), empty_image_stream(64, 64, 2, "pups:bspline(degree=3,l=200)"));
  expect_refused(run_cli_bounded({"info", scratch("ext.pw")}), "extension l outside 0..64");
}

TEST(HostileHeader, InfoDescribesAStreamWithoutDesigningItsBank) {
  // A custom bank within the stream bounds: info parses and checks the spec, designs nothing.
  const std::string spec = "pups:bspline(degree=20,samples=380000)";
  save(scratch("custom.pw"), empty_image_stream(64, 64, 2, spec));
  const auto r = run_cli_bounded({"info", scratch("custom.pw")});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(spec), std::string::npos) << r.output;
  EXPECT_LT(r.cpu_seconds, 1.0);  // a decode designs the bank: about 1.5 s of CPU here
}

TEST(HostileHeader, NonAffineGridTransformIsRefusedBeforeWriting) {
  // Unchecked, the stream decodes and then writing .vdb fails with OpenVDB's ArithmeticError.
  auto grids = cli::read_vdb(fs::path(PUPWAVE_TESTIMAGES_DIR) / "sphere_ls.vdb");
  ASSERT_FALSE(grids.empty());
  grids.resize(1);
  grids[0].index_to_world[3] = 0.25;  // a projective term: valid 4x4 matrix, not affine
  VolumeEncodeOptions o;
  o.target = 1e-2;
  save(scratch("proj.pw"), encode_volumes(grids, o).bytes);
  expect_refused(run_cli_bounded({"decompress", scratch("proj.pw"), scratch("proj.vdb"), "--threads", "2"}),
                 "grid transform is not affine");
  EXPECT_FALSE(fs::exists(scratch("proj.vdb")));
}

TEST(HostileHeader, GridOriginOutsideTheIndexRangeIsRefused) {
  // A grid origin of -2^63 (found by fuzz_volume) would overflow the level placement's negation
  // at --level 1 (undefined behaviour). Origins are OpenVDB int32 coordinates.
  auto h = volume_header({8, 8, 8}, false, 0);
  h.grids[0].origin = {std::numeric_limits<std::int64_t>::min(), 0, 0};
  std::vector<std::uint8_t> bytes;
  write_volume_signature(bytes);
  write_header_chunk(bytes, h);
  save(scratch("origin.pw"), bytes);
  expect_refused(run_cli_bounded({"decompress", scratch("origin.pw"), scratch("origin.raw"), "--level", "1"}),
                 "coordinate out of range");
  EXPECT_FALSE(fs::exists(scratch("origin.raw")));
  // The encoder refuses what the decoder would: no stream it writes is unreadable.
  VolumeGrid g;
  g.name = "far";
  g.volume = Volume({4, 4, 4}, VoxelType::f32);
  g.origin = {std::int64_t(1) << 40, 0, 0};
  VolumeEncodeOptions o;
  o.target = 1e-2;
  EXPECT_THROW(encode_volumes({g}, o), EncodeError);
}

}  // namespace
}  // namespace pupwave
