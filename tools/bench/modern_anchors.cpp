#include "tools/bench/modern_anchors.h"

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "tools/bench/process.h"
#include "tools/bench/size_search.h"

namespace pupwave::bench {
namespace {

namespace fs = std::filesystem;

std::string integer_text(double v) { return std::to_string(static_cast<long>(v)); }

// ffmpeg as a lossless format converter between PPM/PGM and PNG. `grey` forces one 8-bit plane
// (the luma of an RGB picture, equal to it when R = G = B).
void convert(const fs::path& ffmpeg, const fs::path& in, const fs::path& out, bool grey,
             const fs::path& log) {
  run_checked({ffmpeg.string(), "-hide_banner", "-loglevel", "error", "-y", "-i", in.string(), "-pix_fmt",
               grey ? "gray" : "rgb24", out.string()},
              log, out);
}

bool is_grey(const fs::path& decoded_target) { return decoded_target.extension() == ".pgm"; }

class AvifAnchor final : public RdCodec {
 public:
  AvifAnchor(fs::path enc, fs::path dec, fs::path ffmpeg, int speed)
      : enc_(std::move(enc)),
        dec_(std::move(dec)),
        ffmpeg_(std::move(ffmpeg)),
        speed_(std::to_string(speed)) {}
  std::string name() const override { return speed_ == "4" ? "avif" : "avif-s" + speed_; }
  std::string kind() const override { return "anchor"; }
  std::string extension() const override { return ".avif"; }

  EncodeOutcome encode(const EncodeRequest& q) const override {
    const fs::path png = q.output.string() + ".src.png";
    convert(ffmpeg_, q.input, png, q.channels == 1, q.log);
    const std::string yuv = q.channels == 1 ? "400" : "444";
    const auto trial = [&](double quantiser, const fs::path& product) {
      const std::string qs = integer_text(quantiser);
      return run_checked(
          {enc_.string(), "-s", speed_, "-y", yuv, "--min", qs, "--max", qs, png.string(), product.string()},
          q.log, product);
    };
    EncodeOutcome out = search_parameter(q, {0, 63, true, true, false}, trial, [&](double quantiser) {
      return "-s " + speed_ + " -y " + yuv + " --min/--max " + integer_text(quantiser);
    });
    fs::remove(png);
    return out;
  }

  double decode(const fs::path& compressed, const fs::path& decoded, const fs::path& log) const override {
    const fs::path png = decoded.string() + ".png";
    const double seconds = run_checked({dec_.string(), compressed.string(), png.string()}, log, png);
    convert(ffmpeg_, png, decoded, is_grey(decoded), log);
    fs::remove(png);
    return seconds;
  }

 private:
  fs::path enc_, dec_, ffmpeg_;
  std::string speed_;  // libaom's -s
};

class HevcAnchor final : public RdCodec {
 public:
  explicit HevcAnchor(fs::path ffmpeg) : ffmpeg_(std::move(ffmpeg)) {}
  std::string name() const override { return "hevc"; }
  std::string kind() const override { return "anchor"; }
  std::string extension() const override { return ".hevc"; }

  EncodeOutcome encode(const EncodeRequest& q) const override {
    // Full-range 4:4:4: limited range would cost the anchor about 1 dB at high rates.
    const std::string pix = q.channels == 1 ? "gray" : "yuvj444p";
    const auto trial = [&](double qp, const fs::path& product) {
      return run_checked({ffmpeg_.string(),
                          "-hide_banner",
                          "-loglevel",
                          "error",
                          "-y",
                          "-i",
                          q.input.string(),
                          "-frames:v",
                          "1",
                          "-c:v",
                          "libx265",
                          "-preset",
                          "slow",
                          "-tune",
                          "psnr",
                          "-x265-params",
                          "qp=" + integer_text(qp) + ":info=0:log-level=error",
                          "-pix_fmt",
                          pix,
                          "-f",
                          "hevc",
                          product.string()},
                         q.log, product);
    };
    return search_parameter(q, {0, 51, true, true, false}, trial, [&](double qp) {
      return "libx265 -preset slow -tune psnr " + pix + " qp=" + integer_text(qp);
    });
  }

  double decode(const fs::path& compressed, const fs::path& decoded, const fs::path& log) const override {
    return run_checked(
        {ffmpeg_.string(), "-hide_banner", "-loglevel", "error", "-y", "-i", compressed.string(), "-pix_fmt",
         is_grey(decoded) ? "gray" : "rgb24", decoded.string()},
        log, decoded);
  }

 private:
  fs::path ffmpeg_;
};

class WebpAnchor final : public RdCodec {
 public:
  WebpAnchor(fs::path enc, fs::path dec, fs::path ffmpeg)
      : enc_(std::move(enc)), dec_(std::move(dec)), ffmpeg_(std::move(ffmpeg)) {}
  std::string name() const override { return "webp"; }
  std::string kind() const override { return "anchor"; }
  std::string extension() const override { return ".webp"; }

  EncodeOutcome encode(const EncodeRequest& q) const override {
    const auto trial = [&](double quality, const fs::path& product) {
      return run_checked({enc_.string(), "-quiet", "-m", "6", "-q", integer_text(quality), q.input.string(),
                          "-o", product.string()},
                         q.log, product);
    };
    return search_parameter(q, {0, 100, true, false, false}, trial,
                            [](double quality) { return "-m 6 -q " + integer_text(quality); });
  }

  double decode(const fs::path& compressed, const fs::path& decoded, const fs::path& log) const override {
    if (!is_grey(decoded))
      return run_checked({dec_.string(), compressed.string(), "-ppm", "-o", decoded.string()}, log, decoded);
    const fs::path ppm = decoded.string() + ".ppm";
    const double seconds =
        run_checked({dec_.string(), compressed.string(), "-ppm", "-o", ppm.string()}, log, ppm);
    convert(ffmpeg_, ppm, decoded, true, log);
    fs::remove(ppm);
    return seconds;
  }

 private:
  fs::path enc_, dec_, ffmpeg_;
};

}  // namespace

RdCodecPtr make_avif_anchor(const fs::path& avifenc, const fs::path& avifdec, const fs::path& ffmpeg,
                            int speed) {
  return std::make_shared<AvifAnchor>(avifenc, avifdec, ffmpeg, speed);
}

RdCodecPtr make_hevc_anchor(const fs::path& ffmpeg) { return std::make_shared<HevcAnchor>(ffmpeg); }

RdCodecPtr make_webp_anchor(const fs::path& cwebp, const fs::path& dwebp, const fs::path& ffmpeg) {
  return std::make_shared<WebpAnchor>(cwebp, dwebp, ffmpeg);
}

}  // namespace pupwave::bench
