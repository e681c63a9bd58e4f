// The parent-context coder (`--entropy pc`, entropy coder 4) on the test photographs: the
// decoder gets exactly the encoder's indices (its reported PSNR is the decoded image's), reduced
// levels are the lower levels of a full decode and read only their own chunks, byte budgets
// and PSNR targets are met, streams do not depend on the thread count, bands over 1024 split.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "codec/entropy/pc_blocks.h"
#include "codec/error.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_components.h"
#include "codec/image/image_metrics.h"
#include "codec/image/image_stream.h"
#include "codec/image/pc_decoder.h"
#include "photo_crops.h"
#include "tools/atomic_file.h"
#include "tools/image_io.h"
#include "transforms/executor.h"
#include "transforms/separable.h"
#include "transforms/spec.h"

namespace pupwave {
namespace {

using test::crop;
using test::photo;

// A pc encode's options (photo_crops.h).
EncodeOptions pc(RateMode mode, double target) { return test::pc_options(mode, target); }

double decoded_psnr(const Image& img, const std::vector<std::uint8_t>& bytes) {
  return compare_images(img, decode_image(bytes)).overall.psnr;
}

// The grey image of an RGB one: its first channel.
Image first_channel(const Image& in) {
  Image out(in.width, in.height, 1, in.type);
  for (std::size_t y = 0; y < in.height; ++y)
    for (std::size_t x = 0; x < in.width; ++x) out.at(0, x, y) = in.at(0, x, y);
  return out;
}

TEST(PcPhotos, DecodedImageIsTheEncodersOnEveryPhotograph) {
  for (const char* name : {"astronaut.png", "camera.png", "chelsea.png", "coffee.png"}) {
    const Image img = photo(name);
    const EncodeResult r = encode_image(img, pc(RateMode::bpp, 0.5));
    const StreamHeader h = parse_container(r.bytes).header;
    EXPECT_EQ(h.entropy, EntropyCoder::pc) << name;
    EXPECT_FALSE(h.reversible);
    EXPECT_EQ(h.delta, 3277.0 / 65536.0);  // the encoder's RDOQ offset, 0.05
    // The encoder's PSNR comes from its own indices: equal only if the decoder gets them all.
    EXPECT_NEAR(decoded_psnr(img, r.bytes), r.psnr, 1e-9) << name;
    EXPECT_GT(r.psnr, 25.0) << name;
  }
}

TEST(PcPhotos, ByteBudgetsAreMetFromBelowOnRgbAndGrey) {
  const Image rgb = photo("coffee.png");
  for (const Image& img : {rgb, first_channel(rgb), photo("camera.png")})
    for (double bpp : {0.125, 0.5, 2.0}) {
      const EncodeResult r = encode_image(img, pc(RateMode::bpp, bpp));
      const double budget = std::floor(bpp * double(img.plane_size()) / 8.0);
      EXPECT_LE(double(r.bytes.size()), budget) << img.channels << " channels at " << bpp;
      EXPECT_GE(double(r.bytes.size()), 0.98 * budget) << img.channels << " channels at " << bpp;
      EXPECT_NEAR(decoded_psnr(img, r.bytes), r.psnr, 1e-9);
    }
}

TEST(PcPhotos, PsnrTargetsAreReachedJustAbove) {
  for (const char* name : {"camera.png", "astronaut.png"})
    for (double target : {30.0, 40.0}) {
      const Image img = photo(name);
      const EncodeResult r = encode_image(img, pc(RateMode::psnr, target));
      const double got = decoded_psnr(img, r.bytes);
      EXPECT_NEAR(got, r.psnr, 1e-9) << name;
      EXPECT_GE(got, target) << name;
      EXPECT_LE(got, target + 0.1) << name;
    }
}

TEST(PcPhotos, FixedStepCodesOncePerStepAndFinerStepsCostMore) {
  const Image img = photo("chelsea.png");
  const EncodeResult fine = encode_image(img, pc(RateMode::step, 4.0));
  const EncodeResult coarse = encode_image(img, pc(RateMode::step, 16.0));
  EXPECT_GT(fine.bytes.size(), coarse.bytes.size());
  EXPECT_GT(fine.psnr, coarse.psnr + 3.0);
  EXPECT_NEAR(decoded_psnr(img, fine.bytes), fine.psnr, 1e-9);
}

// Level k of a full decode: every block decoded, dequantized, the inverse stopped at level k.
Image lower_level_of_full_decode(const std::vector<std::uint8_t>& bytes, int k) {
  const ParsedStream s = parse_container(bytes);
  const StreamHeader& h = s.header;
  std::vector<std::vector<float>> planes(h.channels, std::vector<float>(h.dims[0] * h.dims[1], 0.0f));
  std::vector<float*> pointers;
  for (auto& p : planes) pointers.push_back(p.data());
  decode_pc_into(s, h.dims, serial_executor(), pointers);
  const auto t = make_stream_transform(h);
  for (auto& p : planes) inverse(*t, p.data(), h.dims, h.levels, k);
  return image_from_components(planes, h.dims, level_extent(h.dims, k), h.type, h.colour,
                               coarse_gain(*t, h.dims, k));
}

// The stream cut after the DATA chunk of resolution `last` (chunks: 5-byte signature, then
// 12 bytes of framing + payload each).
std::vector<std::uint8_t> cut_after_resolution(const std::vector<std::uint8_t>& bytes, int last) {
  std::size_t pos = 5;
  int data = -1;
  while (pos + 12 <= bytes.size()) {
    const std::string tag(bytes.begin() + std::ptrdiff_t(pos), bytes.begin() + std::ptrdiff_t(pos) + 4);
    const std::size_t length =
        bytes[pos + 4] | (bytes[pos + 5] << 8) | (bytes[pos + 6] << 16) | (std::size_t(bytes[pos + 7]) << 24);
    pos += 12 + length;
    if (tag == "DATA" && ++data == last) break;
  }
  return {bytes.begin(), bytes.begin() + std::ptrdiff_t(pos)};
}

TEST(PcPhotos, ReducedLevelsAreTheLowerLevelsOfAFullDecodeAndReadOnlyTheirChunks) {
  const Image img = crop(photo("coffee.png"), 451, 299);  // odd sizes: every level's line ends
  const EncodeResult r = encode_image(img, pc(RateMode::bpp, 1.0));
  const int levels = parse_container(r.bytes).header.levels;
  for (int k = 1; k <= 3; ++k) {
    const Image reduced = decode_image(r.bytes, k);
    EXPECT_EQ(reduced.width, level_extent({451, 299, 1}, k)[0]);
    EXPECT_EQ(reduced.samples, lower_level_of_full_decode(r.bytes, k).samples) << "level " << k;
    // The finer resolutions' chunks are not needed at all.
    EXPECT_EQ(decode_image(cut_after_resolution(r.bytes, levels - k), k).samples, reduced.samples);
    EXPECT_THROW(decode_image(cut_after_resolution(r.bytes, levels - k), 0), DecodeError);
  }
}

TEST(PcPhotos, StreamsAndImagesDoNotDependOnTheThreadCount) {
  const Image img = photo("astronaut.png");
  const auto two = make_pool_executor(2), four = make_pool_executor(4);
  for (RateMode mode : {RateMode::bpp, RateMode::psnr}) {
    EncodeOptions o = pc(mode, mode == RateMode::bpp ? 0.75 : 33.0);
    o.executor = &serial_executor();
    const auto serial = encode_image(img, o).bytes;
    o.executor = two.get();
    EXPECT_EQ(encode_image(img, o).bytes, serial);
    o.executor = four.get();
    EXPECT_EQ(encode_image(img, o).bytes, serial);
    EXPECT_EQ(decode_image(serial, 0, serial_executor()).samples, decode_image(serial, 0, *four).samples);
  }
}

// Bands wider than 1024 split into 1024-blocks, each reading its parent at its offset.
TEST(PcPhotos, BandsOverTheBlockSizeSplitAndStillRoundTrip) {
  const Image camera = photo("camera.png");
  Image wide(2200, 40, 1, camera.type);
  for (std::size_t y = 0; y < 40; ++y)
    for (std::size_t x = 0; x < 2200; ++x) wide.at(0, x, y) = camera.at(0, (x * 7) % 512, 200 + y);
  const EncodeResult r = encode_image(wide, pc(RateMode::bpp, 1.5));
  const ParsedStream s = parse_container(r.bytes);
  EXPECT_GT(s.blocks.size(), s.bands.size());  // the first level's bands hold two blocks each
  EXPECT_NEAR(decoded_psnr(wide, r.bytes), r.psnr, 1e-9);
  EXPECT_EQ(decode_image(r.bytes, 1).samples, lower_level_of_full_decode(r.bytes, 1).samples);
}

// A budget under the header's own size gives the smallest stream (every index zero), as the
// other coders do, not an error.
TEST(PcPhotos, BudgetUnderTheSmallestStreamGivesTheSmallestStream) {
  const Image img = crop(photo("astronaut.png"), 24, 20);
  const EncodeResult r = encode_image(img, pc(RateMode::bpp, 1.0));
  EXPECT_GT(double(r.bytes.size()), 1.0 * 24 * 20 / 8);
  const ParsedStream s = parse_container(r.bytes);
  for (const BlockEntry& e : s.index) EXPECT_EQ(e.passes, 0);
  EXPECT_NEAR(decoded_psnr(img, r.bytes), r.psnr, 1e-9);
}

// Versions 5 and 6 changed only the pc coder: a version 4 or 5 pc stream is refused by name, a
// version 4 or 5 stream of another coder (same syntax) still decodes, and anything older is
// unsupported.
TEST(PcPhotos, StreamsOfAnOlderVersionAreRefusedByName) {
  const Image img = crop(photo("chelsea.png"), 64, 48);
  auto bytes = encode_image(img, pc(RateMode::bpp, 1.0)).bytes;
  ASSERT_EQ(bytes[4], kStreamVersion);
  // pc streams of version 4 had other contexts, of 5 no CfL and flat starts
  for (const std::uint8_t version : {std::uint8_t(4), std::uint8_t(5)}) {
    bytes[4] = version;
    try {
      (void)decode_image(bytes);
      ADD_FAILURE() << "a version " << int(version) << " pc stream decoded";
    } catch (const std::exception& e) {
      EXPECT_NE(
          std::string(e.what()).find("version " + std::to_string(version) + " with entropy coder 4 (pc)"),
          std::string::npos)
          << e.what();
    }
  }
  EncodeOptions plain;
  plain.mode = RateMode::bpp;
  plain.target = 1.0;
  auto other = encode_image(img, plain).bytes;
  const auto current = decode_image(other).samples;
  for (const std::uint8_t version : {std::uint8_t(4), std::uint8_t(5)}) {
    other[4] = version;
    EXPECT_EQ(decode_image(other).samples, current);
  }
  other[4] = 3;
  try {
    (void)decode_image(other);
    ADD_FAILURE() << "a version 3 stream decoded";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("unsupported version 3"), std::string::npos) << e.what();
  }
}

// One band's coding with RDOQ at `step` (neighbour term `neighbour_bits`): log of its
// codeword's bytes and of its squared error in coefficient units.
std::pair<double, double> coded_band(const std::vector<float>& coef, std::size_t w, std::size_t h,
                                     double step, double neighbour_bits) {
  std::vector<float> u(coef.size());
  for (std::size_t k = 0; k < u.size(); ++k) u[k] = float(coef[k] / step);
  PcRdoq rdoq{u};
  rdoq.neighbour_bits = neighbour_bits;
  std::vector<std::int32_t> q(u.size());
  const CoefCodeword word = pc_encode_block(q, w, h, LcParent{}, &rdoq);
  double error = 0.0;
  for (std::size_t k = 0; k < u.size(); ++k) {
    const double r = q[k] == 0 ? 0.0 : std::abs(q[k]) + rdoq.delta;
    error += (std::fabs(double(u[k])) - r) * (std::fabs(double(u[k])) - r) * step * step;
  }
  return {std::log(double(word.bytes.size())), std::log(error)};
}

// RDOQ's neighbour term (pc_neighbour_bits: what a non-zero index does to the contexts coded
// after it) pays on a real band: camera's finest horizontal details coded with it have less
// error than the plain greedy choice at the same bytes (the plain curve interpolated in log
// bytes between steps 2^(1/8) apart).
TEST(PcPhotos, RdoqNeighbourTermLowersTheErrorAtEqualBytesOnAPhotoBand) {
  const Image img = photo("camera.png");
  const Extent dims{img.width, img.height, 1};
  std::vector<float> plane(img.plane_size());
  for (std::size_t y = 0; y < img.height; ++y)
    for (std::size_t x = 0; x < img.width; ++x) plane[y * img.width + x] = img.at(0, x, y) - 128.0f;
  forward(*make_transform("cdf97"), plane.data(), dims, 1);
  const Subband band = subbands(dims, 1)[1];  // level 1, high-pass along x
  ASSERT_EQ(band.level, 1);
  std::vector<float> coef(band.count());
  for (std::size_t y = 0; y < band.size[1]; ++y)
    for (std::size_t x = 0; x < band.size[0]; ++x)
      coef[y * band.size[0] + x] = plane[(band.offset[1] + y) * img.width + band.offset[0] + x];
  std::vector<std::pair<double, double>> plain;  // falling bytes
  for (int k = 0; k <= 32; ++k)
    plain.push_back(coded_band(coef, band.size[0], band.size[1], 2.0 * std::exp2(k / 8.0), 0.0));
  for (double step : {3.0, 6.0, 12.0}) {
    const auto [bytes, error] = coded_band(coef, band.size[0], band.size[1], step, PcRdoq{}.neighbour_bits);
    std::size_t k = 1;
    while (k + 1 < plain.size() && plain[k].first > bytes) ++k;
    const auto [b0, e0] = plain[k - 1];
    const auto [b1, e1] = plain[k];
    ASSERT_TRUE(b0 >= bytes && bytes >= b1) << "step " << step;
    const double plain_error = e0 + (e1 - e0) * (bytes - b0) / (b1 - b0);
    EXPECT_LT(error, plain_error) << "step " << step;
  }
}

TEST(PcPhotos, LosslessIsRefusedAndTheCliNamesTheCoder) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("pupwave_pc_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::create_directories(dir);
  const std::string cli = PUPWAVE_CLI, src = std::string(PUPWAVE_TESTIMAGES_DIR) + "/camera.png";
  const std::string pw = (dir / "c.pw").string(), png = (dir / "c.png").string();
  EXPECT_NE(
      std::system((cli + " compress " + src + " " + pw + " --entropy pc --lossless 2>/dev/null").c_str()), 0);
  ASSERT_EQ(std::system((cli + " compress " + src + " " + pw + " --entropy pc --bpp 1 >/dev/null").c_str()),
            0);
  EXPECT_EQ(parse_container(cli::read_file_bytes(pw)).header.entropy, EntropyCoder::pc);
  ASSERT_EQ(std::system((cli + " decompress " + pw + " " + png + " --level 1 >/dev/null").c_str()), 0);
  EXPECT_EQ(cli::read_image(png).width, 256u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace pupwave
