// PSNR targets on 256 x 256 crops of two photographs (camera: grey, astronaut: RGB) land in
// the window the --psnr help promises, [T, T + 0.15] dB, with the default coder (pc on crops
// this size) and the bit-plane coder; and no lossy target of the default coder gives a file
// larger than its lossless stream (lc, what --lossless writes).
//
// ctest checks a grid of targets (every 0.7 dB from 20 dB, and targets near jumps of the default
// coder's PSNR); bench/psnr_crop_sweep.sh runs the fine sweep (every 0.1 dB) through the same code with
// PUPWAVE_WINDOW_STEP=0.1 PUPWAVE_WINDOW_CODERS=default,ebcot,ht PUPWAVE_WINDOW_OUT=<table.md>.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "codec/image/image_codec.h"
#include "codec/image/image_metrics.h"
#include "tests/cli_codec/photo_crops.h"

namespace pupwave::test {
namespace {

constexpr double kWithin = 0.15;  // dB above the target at most (the --psnr help)
constexpr double kLowest = 20.0, kHighest = 55.0;

struct Crop {
  const char* name;
  Image image;
};

const std::vector<Crop>& crops() {
  static const std::vector<Crop> all = {{"camera.png", crop(photo("camera.png"), 256, 256)},
                                        {"astronaut.png", crop(photo("astronaut.png"), 256, 256)}};
  return all;
}

double env_number(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v != nullptr ? std::atof(v) : fallback;
}

// The targets checked: a grid from kLowest by `step`, with (for the coarse ctest grid) targets
// where plain passes of the default coder jump over the window on the camera crop (20.1-23.0 dB:
// a band turning on moves the PSNR by up to 0.5 dB) and three more low ones.
std::vector<double> targets(double step) {
  std::vector<double> t;
  for (int k = 0;; ++k) {
    const double target = std::round((kLowest + step * k) * 10.0) / 10.0;
    if (target > kHighest + 1e-9) break;
    t.push_back(target);
  }
  if (step > 0.1 + 1e-9)
    for (double extra : {20.1, 20.3, 20.4, 23.0, 25.0, 27.8, 28.5}) t.push_back(extra);
  return t;
}

// The library call of coder `name`: "default" (encode_image_default_coder) or an entropy coder.
EncodeResult encode_with(const std::string& name, const Image& image, EncodeOptions o) {
  if (name == "default") return encode_image_default_coder(view_of(image), o);
  if (name != "ebcot" && name != "ht") throw std::invalid_argument("no coder named " + name);
  o.entropy = name == "ebcot" ? EntropyCoder::ebcot : EntropyCoder::ht;
  return encode_image(image, o);
}

EncodeOptions psnr_target(double target) {
  EncodeOptions o;
  o.mode = RateMode::psnr;
  o.target = target;
  return o;
}

// Every target of the grid on both crops lands in the window (or gives the coder's lossless
// stream, PSNR infinite); the reported PSNR is the decoded stream's. Returns a table row per crop.
std::string check_window(const std::string& coder, double step) {
  std::ostringstream rows;
  for (const Crop& c : crops()) {
    SCOPED_TRACE(std::string(c.name) + " (" + coder + ")");
    int misses = 0, lossy = 0;
    double worst = 0.0;
    for (const double target : targets(step)) {
      const EncodeResult r = encode_with(coder, c.image, psnr_target(target));
      if (r.switched_to_lossless) {
        EXPECT_TRUE(std::isinf(r.psnr)) << target;
        continue;
      }
      ++lossy;
      worst = std::max(worst, r.psnr - target);
      const bool in = r.psnr >= target && r.psnr <= target + kWithin;
      misses += in ? 0 : 1;
      EXPECT_TRUE(in) << "target " << target << " dB gave " << r.psnr << " dB (" << r.bytes.size()
                      << " bytes)";
      // The reported PSNR is the decoder's (streams with a band at a step of its own included).
      EXPECT_NEAR(compare_images(c.image, decode_image(r.bytes)).overall.psnr, r.psnr, 1e-9) << target;
    }
    rows << "| " << c.name << " 256x256 | " << coder << " | " << targets(step).size() << " | " << lossy
         << " | " << misses << " | " << worst << " |\n";
  }
  return rows.str();
}

// Optional markdown rows (PUPWAVE_WINDOW_OUT): the bench sweep's table.
void report(const std::string& rows) {
  const char* path = std::getenv("PUPWAVE_WINDOW_OUT");
  if (path == nullptr) return;
  std::ofstream out(path, std::ios::app);
  out << rows;
}

TEST(PsnrWindow, DefaultCoderLandsInTheWindowOnCrops) {
  report(check_window("default", env_number("PUPWAVE_WINDOW_STEP", 0.7)));
}

TEST(PsnrWindow, BitPlaneCoderLandsInTheWindowOnCrops) {
  report(check_window("ebcot", env_number("PUPWAVE_WINDOW_STEP", 0.7)));
}

// The other coder, ht (or those named in PUPWAVE_WINDOW_CODERS, comma-separated: the bench
// sweep names them all; default and ebcot have their own tests above).
TEST(PsnrWindow, OtherCodersLandInTheWindowOnCrops) {
  const char* list = std::getenv("PUPWAVE_WINDOW_CODERS");
  std::stringstream names(list != nullptr ? list : "ht");
  for (std::string name; std::getline(names, name, ',');)
    if (name != "default" && name != "ebcot")
      report(check_window(name, env_number("PUPWAVE_WINDOW_STEP", 0.7)));
}

// The lossless stream of the default coder: lc's, what --lossless writes.
std::vector<std::uint8_t> lossless_stream(const Image& image) {
  EncodeOptions o;
  o.mode = RateMode::lossless;
  o.transform = "cdf53";
  return encode_image_default_coder(view_of(image), o).bytes;
}

// `in` at twice its size, each sample repeated 2 x 2 (nearest-neighbour upscaling): smooth where
// lc's predictor codes the exact stream in a third less than the bit-plane coder's.
Image doubled(const Image& in) {
  Image out(2 * in.width, 2 * in.height, in.channels, in.type);
  for (std::size_t c = 0; c < in.channels; ++c)
    for (std::size_t y = 0; y < out.height; ++y)
      for (std::size_t x = 0; x < out.width; ++x) out.at(c, x, y) = in.at(c, x / 2, y / 2);
  return out;
}

// High PSNR targets and large byte budgets never give a lossy file larger than the lossless
// one; a result that says it switched to lossless is that very stream. Besides the crops, the
// camera's sky (its top-left 128 x 128) upscaled to 256 x 256, whose lossy files pass its
// lossless one at about 58 dB while still under a quarter of its raw size.
TEST(PsnrWindow, NoLossyFileLargerThanLossless) {
  std::vector<Crop> images = crops();
  images.push_back({"camera.png sky doubled", doubled(crop(photo("camera.png"), 128, 128))});
  for (const Crop& c : images) {
    SCOPED_TRACE(c.name);
    const std::vector<std::uint8_t> exact = lossless_stream(c.image);
    std::vector<std::pair<RateMode, double>> asks;
    for (double t = 50.0; t <= 60.0 + 1e-9; t += 0.5) asks.emplace_back(RateMode::psnr, t);
    for (double t = 4.0; t <= 8.0 + 1e-9; t += 0.5) asks.emplace_back(RateMode::bpp, t);
    for (const auto& [mode, target] : asks) {
      EncodeOptions o = psnr_target(target);
      o.mode = mode;
      const EncodeResult r = encode_image_default_coder(view_of(c.image), o);
      EXPECT_LE(r.bytes.size(), exact.size()) << (mode == RateMode::psnr ? "PSNR " : "bpp ") << target;
      if (r.switched_to_lossless) {
        EXPECT_TRUE(r.bytes == exact) << target;
      } else if (mode == RateMode::psnr) {
        EXPECT_GE(r.psnr, target);
      }
    }
  }
}

}  // namespace
}  // namespace pupwave::test
