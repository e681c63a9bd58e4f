// EXR structure survives compress + decompress: data and display windows, custom attributes,
// channel names, more than 4 channels (up to 64); CMYK is refused, never turned into RGB;
// a float image written as .ppm is written with the type the CLI reports.
// Inputs are made with oiiotool from the real photographs in testimages/.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "hdr/hdr_test_util.h"
#include "tools/image_io.h"

namespace pupwave {
namespace {
namespace fs = std::filesystem;

class ImageStructure : public ::testing::Test {
 protected:
  fs::path dir = test::hdr_temp_dir();
  std::string tmp(const std::string& name) const { return (dir / name).string(); }

  // compress + decompress through the CLI; the decoded file's image.
  // `rate`: a fixed step is quicker than a PSNR target (no decode per trial) for many channels.
  Image round_trip(const std::string& in, const std::string& name, const std::string& rate = "--psnr=45") {
    const auto c = test::run_cli({"compress", in, tmp(name + ".pw"), rate});
    EXPECT_EQ(c.exit_code, 0) << c.output;
    const auto d = test::run_cli({"decompress", tmp(name + ".pw"), tmp(name + "_out.exr")});
    EXPECT_EQ(d.exit_code, 0) << d.output;
    return cli::read_image(tmp(name + "_out.exr"));
  }
};

TEST_F(ImageStructure, WindowsAndAttributesSurvive) {
  const std::string in = tmp("win.exr");
  ASSERT_EQ(test::run_shell("oiiotool " + test::testimage("chelsea.png") +
                            " -d half --origin +100+50 --fullsize 800x600+0+0"
                            " --attrib myshow:shot sh010 --attrib:type=int myshow:take 7"
                            " --attrib:type=float myshow:gain 1.5 -o " +
                            in),
            0);
  const Image out = round_trip(in, "win");
  EXPECT_EQ(out.metadata.x, 100);
  EXPECT_EQ(out.metadata.y, 50);
  EXPECT_EQ(out.metadata.full_width, 800u);
  EXPECT_EQ(out.metadata.full_height, 600u);
  auto find = [&](const std::string& n) -> const ImageAttribute* {
    for (const auto& a : out.metadata.attributes)
      if (a.name == n) return &a;
    return nullptr;
  };
  ASSERT_TRUE(find("myshow:shot"));
  EXPECT_EQ(find("myshow:shot")->text, "sh010");
  ASSERT_TRUE(find("myshow:take"));
  EXPECT_EQ(find("myshow:take")->integer, 7);
  ASSERT_TRUE(find("myshow:gain"));
  EXPECT_FLOAT_EQ(float(find("myshow:gain")->real), 1.5f);
  const auto info = test::run_cli({"info", tmp("win.pw")}).output;
  EXPECT_NE(info.find("myshow:shot = \"sh010\""), std::string::npos) << info;
  EXPECT_NE(info.find("display window 800x600+0+0"), std::string::npos) << info;
  EXPECT_NE(info.find("data window 451x300+100+50"), std::string::npos) << info;
}

// Attributes the stream cannot hold (vectors, matrices) are never dropped silently: compress
// names them in a warning, and the scalar ones beside them are still kept.
TEST_F(ImageStructure, AttributesNotKeptAreNamed) {
  const std::string in = tmp("vec.exr");
  ASSERT_EQ(
      test::run_shell("oiiotool " + test::testimage("camera.png") +
                      " -d half --attrib:type=vector myshow:up 0,1,0 --attrib myshow:shot sh020 -o " + in),
      0);
  const auto c = test::run_cli({"compress", in, tmp("vec.pw"), "--psnr=40"});
  ASSERT_EQ(c.exit_code, 0) << c.output;
  EXPECT_NE(c.output.find("warning: 1 attribute(s)"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("myshow:up"), std::string::npos) << c.output;
  EXPECT_EQ(c.output.find("myshow:shot ("), std::string::npos) << c.output;  // kept, so not named
  // --quiet keeps warnings (a dropped attribute is never silent) and nothing else.
  const auto q = test::run_cli({"compress", in, tmp("vec_q.pw"), "--psnr=40", "--quiet"});
  EXPECT_EQ(q.output.rfind("warning: 1 attribute(s)", 0), 0u) << q.output;
  EXPECT_EQ(q.output.find('\n'), q.output.size() - 1) << q.output;
}

TEST_F(ImageStructure, ChannelNamesSurvive) {
  const std::string in = tmp("yd.exr");
  ASSERT_EQ(test::run_shell("oiiotool " + test::testimage("camera.png") +
                            " --ch 0,0 --chnames Y,depth -d half -o " + in),
            0);
  const Image out = round_trip(in, "yd");
  ASSERT_EQ(out.channels, 2u);
  EXPECT_EQ(out.metadata.channel_names, (std::vector<std::string>{"Y", "depth"}));
}

TEST_F(ImageStructure, FiveAndSixtyFourChannels) {
  for (int n : {5, 64}) {
    std::string ch, names;
    for (int c = 0; c < n; ++c) {
      ch += (c ? "," : "") + std::to_string(c % 3);
      names += (c ? "," : "") + (c < 3 ? std::string(1, "RGB"[c]) : "extra" + std::to_string(c));
    }
    const std::string in = tmp("multi" + std::to_string(n) + ".exr");
    // A 160x120 cut of the photograph keeps 64 planes quick to code.
    ASSERT_EQ(test::run_shell("oiiotool " + test::testimage("chelsea.png") + " --cut 160x120+150+60 --ch " +
                              ch + " --chnames " + names + " -d half -o " + in),
              0);
    const Image ref = cli::read_image(in);
    const Image out = round_trip(in, "multi" + std::to_string(n), "--step=0.01");
    ASSERT_EQ(out.channels, std::size_t(n));
    EXPECT_EQ(out.metadata.channel_names, ref.metadata.channel_names);
    // Channel n-1 repeats channel (n-1) % 3 of the photograph: it is coded as its own plane.
    double err = 0.0;
    for (std::size_t i = 0; i < ref.plane_size(); ++i)
      err = std::max(err,
                     double(std::abs(out.plane(std::size_t(n - 1))[i] - ref.plane(std::size_t(n - 1))[i])));
    EXPECT_LT(err, 0.2) << n;
  }
}

TEST_F(ImageStructure, CmykTiffIsRefused) {
  const std::string in = tmp("cmyk.tif");
  ASSERT_EQ(test::run_shell("oiiotool " + test::testimage("chelsea.png") +
                            " --attrib tiff:ColorSpace CMYK -o " + in),
            0);
  const auto r = test::run_cli({"compress", in, tmp("cmyk.pw")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("CMYK"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(tmp("cmyk.pw")));
}

TEST_F(ImageStructure, FloatToPpmWritesWhatItSays) {
  ASSERT_EQ(test::run_cli({"compress", test::testimage("forest_hdr.exr"), tmp("f.pw")}).exit_code, 0);
  const auto d = test::run_cli({"decompress", tmp("f.pw"), tmp("f.ppm")});
  ASSERT_EQ(d.exit_code, 0) << d.output;
  EXPECT_NE(d.output.find("uint16"), std::string::npos) << d.output;
  std::ifstream f(tmp("f.ppm"), std::ios::binary);
  std::string magic, w, h, maxval;
  f >> magic >> w >> h >> maxval;
  EXPECT_EQ(magic, "P6");
  EXPECT_EQ(maxval, "65535");
}

}  // namespace
}  // namespace pupwave
