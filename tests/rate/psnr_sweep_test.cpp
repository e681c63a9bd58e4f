// Rate control over a sweep of PSNR targets on every test photograph (testimages/*.png), with
// the bit-plane coder and with the default coder (pc on photographs this size, lc lossless):
// each file reaches its target and lands within 0.15 dB of it, or is the lossless file where
// no smaller lossy one reaches the target; no file is larger than the lossless one; sizes
// never fall as the target rises (0.5% noise allowed).
//
// ctest runs a strided sweep (every 1.3 dB, offset per image by a multiple of 0.1 dB so the
// images together hit different tenths) to fit about a minute on two idle cores (an encode
// with its PSNR search takes 0.1-0.6 s there); bench/psnr_sweep.sh runs the full 0.1 dB sweep
// through the same code by setting PUPWAVE_SWEEP_STEP=0.1 and PUPWAVE_SWEEP_OUT=<report.md>
// (and PUPWAVE_SWEEP_IMAGE=<name.png> for one image).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "codec/image/image_codec.h"
#include "codec/image/image_metrics.h"
#include "tools/image_io.h"
#include "transforms/separable.h"

namespace pupwave {
namespace {

constexpr double kLowest = 20.0, kHighest = 70.0;
constexpr double kWithin = 0.15;      // dB above the target at most
constexpr double kSizeNoise = 0.005;  // a higher target may give a file this much smaller

std::vector<std::filesystem::path> photographs() {
  std::vector<std::filesystem::path> paths;
  for (const auto& e : std::filesystem::directory_iterator(PUPWAVE_TESTIMAGES_DIR))
    if (e.path().extension() == ".png") paths.push_back(e.path());
  std::sort(paths.begin(), paths.end());
  return paths;
}

double env_number(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v != nullptr ? std::atof(v) : fallback;
}

struct Point {
  double target = 0.0;
  std::size_t bytes = 0;
  double psnr = 0.0;
  bool lossless = false;
};

// The sweep with the library's default coder (encode_image_default_coder: pc on these photographs,
// lc lossless) or the bit-plane coder (encode_image, ebcot; its own lossless stream).
void sweep(bool default_coder) {
  const double stride = env_number("PUPWAVE_SWEEP_STEP", 1.3);
  const char* report_path = std::getenv("PUPWAVE_SWEEP_OUT");
  std::ofstream report;
  if (report_path != nullptr) {  // both sweeps add their rows to one table
    report.open(report_path, std::ios::app);
    if (report.tellp() == 0)
      report << "| image (coder) | targets | lossless bytes | switched to lossless from | worst excess dB | "
                "largest size drop |\n|---|---|---|---|---|---|\n";
  }
  const auto executor = make_pool_executor(2);
  const auto paths = photographs();
  ASSERT_GE(paths.size(), 4u);
  const char* only = std::getenv("PUPWAVE_SWEEP_IMAGE");  // one image's name (bench runs)
  for (std::size_t n = 0; n < paths.size(); ++n) {
    if (only != nullptr && paths[n].filename().string() != only) continue;
    SCOPED_TRACE(paths[n].filename().string());
    const Image image = cli::read_image(paths[n]);
    EncodeOptions exact;
    exact.mode = RateMode::lossless;
    exact.transform = "cdf53";
    exact.executor = executor.get();
    if (!default_coder) exact.entropy = EntropyCoder::ebcot;
    const std::size_t lossless_bytes =
        (default_coder ? encode_image_default_coder(view_of(image), exact) : encode_image(image, exact))
            .bytes.size();
    std::vector<Point> points;
    // The offset per image makes the strided sweeps together cover the 0.1 dB grid.
    const double offset = stride > 0.1 + 1e-9 ? 0.1 * double((4 * n) % 13) : 0.0;
    for (int k = 0;; ++k) {
      const double target = std::round((kLowest + offset + stride * k) * 10.0) / 10.0;
      if (target > kHighest + 1e-9) break;
      EncodeOptions o;
      o.mode = RateMode::psnr;
      o.target = target;
      o.executor = executor.get();
      const EncodeResult r =
          default_coder ? encode_image_default_coder(view_of(image), o) : encode_image(image, o);
      points.push_back({target, r.bytes.size(), r.psnr, r.switched_to_lossless});
      SCOPED_TRACE("target " + std::to_string(target));
      ASSERT_LE(r.bytes.size(), lossless_bytes);
      if (r.switched_to_lossless) {
        EXPECT_EQ(r.bytes.size(), lossless_bytes);
        EXPECT_TRUE(std::isinf(r.psnr));
      } else {
        EXPECT_GE(r.psnr, target);
        EXPECT_LE(r.psnr, target + kWithin);
      }
      if (k % 40 == 0) {  // the reported PSNR is that of the stream as a decoder sees it
        const Image decoded = decode_image(r.bytes, 0, *executor);
        const double decoded_psnr = compare_images(image, decoded).overall.psnr;
        if (r.switched_to_lossless)
          EXPECT_TRUE(std::isinf(decoded_psnr));
        else
          EXPECT_NEAR(decoded_psnr, r.psnr, 1e-9);
      }
    }
    double worst_excess = 0.0, largest_drop = 0.0;
    double switched_from = std::nan("");
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!points[i].lossless) worst_excess = std::max(worst_excess, points[i].psnr - points[i].target);
      if (points[i].lossless && std::isnan(switched_from)) switched_from = points[i].target;
      if (i == 0) continue;
      const double drop = 1.0 - double(points[i].bytes) / double(points[i - 1].bytes);
      largest_drop = std::max(largest_drop, drop);
      EXPECT_LE(drop, kSizeNoise) << "size falls from " << points[i - 1].bytes << " at "
                                  << points[i - 1].target << " dB to " << points[i].bytes << " at "
                                  << points[i].target << " dB";
    }
    if (report.is_open())
      report << "| " << paths[n].filename().string() << (default_coder ? " (default: pc)" : " (ebcot)")
             << " | " << points.size() << " | " << lossless_bytes << " | "
             << (std::isnan(switched_from) ? std::string("-")
                                           : std::to_string(switched_from).substr(0, 4) + " dB")
             << " | " << worst_excess << " | " << largest_drop * 100.0 << "% |" << std::endl;
  }
}

TEST(PsnrSweep, EveryPhotographMeetsTargetsTightlyAndMonotonically) { sweep(false); }
TEST(PsnrSweep, TheDefaultCoderMeetsTargetsTightlyAndMonotonically) { sweep(true); }

}  // namespace
}  // namespace pupwave
