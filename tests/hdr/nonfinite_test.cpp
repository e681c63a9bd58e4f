// NaN and infinite samples: refused by default with a message that says how to keep them;
// with keep_nonfinite / --keep-nonfinite coded exactly through the NFIN side list.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "codec/error.h"
#include "codec/image/image_codec.h"
#include "hdr/hdr_test_util.h"
#include "tools/image_io.h"

namespace pupwave {
namespace {

std::uint32_t bits(float v) {
  std::uint32_t b = 0;
  std::memcpy(&b, &v, 4);
  return b;
}

// The real HDR photograph with a few NaN and infinite samples dropped in.
Image forest_with_holes() {
  Image img = cli::read_image(test::testimage("forest_hdr.exr"));
  img.at(0, 3, 4) = std::numeric_limits<float>::quiet_NaN();
  img.at(1, 100, 200) = std::numeric_limits<float>::infinity();
  img.at(2, 511, 255) = -std::numeric_limits<float>::infinity();
  img.at(2, 0, 0) = std::numeric_limits<float>::quiet_NaN();
  return img;
}

TEST(NonFinite, RefusedByDefaultWithAClearMessage) {
  try {
    encode_image(forest_with_holes(), EncodeOptions{});
    FAIL() << "non-finite samples were accepted";
  } catch (const EncodeError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("4 non-finite"), std::string::npos) << m;
    EXPECT_NE(m.find("--keep-nonfinite"), std::string::npos) << m;
  }
}

TEST(NonFinite, KeptExactlyOnRequest) {
  const Image img = forest_with_holes();
  EncodeOptions o;
  o.keep_nonfinite = true;
  const EncodeResult r = encode_image(img, o);
  EXPECT_EQ(r.nonfinite, 4u);
  const Image dec = decode_image(r.bytes);
  std::size_t nonfinite = 0;
  for (std::size_t i = 0; i < img.samples.size(); ++i) {
    if (std::isfinite(img.samples[i])) {
      EXPECT_TRUE(std::isfinite(dec.samples[i])) << i;
      continue;
    }
    ++nonfinite;
    EXPECT_EQ(bits(dec.samples[i]), bits(img.samples[i])) << i;
  }
  EXPECT_EQ(nonfinite, 4u);
  // Reduced resolution still decodes (without the side list, whose positions are full-size).
  EXPECT_EQ(decode_image(r.bytes, 1).width, img.width / 2);
}

TEST(NonFinite, CliRefusesThenKeeps) {
  const auto dir = test::hdr_temp_dir();
  const std::string in = (dir / "holes.exr").string(), pw = (dir / "holes.pw").string(),
                    out = (dir / "holes_out.exr").string();
  cli::write_image(forest_with_holes(), in);
  auto r = test::run_cli({"compress", in, pw});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("pupwave: error:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--keep-nonfinite"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(pw));
  r = test::run_cli({"compress", in, pw, "--keep-nonfinite"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("4 non-finite sample(s) kept exactly"), std::string::npos) << r.output;
  EXPECT_NE(test::run_cli({"info", pw}).output.find("NFIN"), std::string::npos);
  ASSERT_EQ(test::run_cli({"decompress", pw, out}).exit_code, 0);
  const Image dec = cli::read_image(out);
  EXPECT_TRUE(std::isnan(dec.at(0, 3, 4)));
  EXPECT_EQ(dec.at(1, 100, 200), std::numeric_limits<float>::infinity());
  EXPECT_EQ(dec.at(2, 511, 255), -std::numeric_limits<float>::infinity());
}

}  // namespace
}  // namespace pupwave
