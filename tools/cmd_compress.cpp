// `pupwave compress IN OUT.pw`: read an image, encode it, write the stream atomically and
// report size, rate, PSNR against the input and time.
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "codec/image_codec.h"
#include "tools/atomic_file.h"
#include "tools/commands.h"
#include "tools/image_io.h"
#include "transforms/separable.h"

namespace pupwave::cli {
namespace {

struct CompressOptions {
  std::string input;
  std::string output;
  std::string transform;
  int levels = -1;
  double bpp = 0.0, psnr = 0.0, step = 0.0;
  bool lossless = false;
  EntropyCoder entropy = EntropyCoder::ebcot;
  unsigned threads = 0;
};

// Turns the mutually exclusive rate flags into the library's mode (default: --psnr 40).
void set_rate(const CompressOptions& opt, EncodeOptions& enc) {
  if (opt.lossless) {
    enc.mode = RateMode::lossless;
    if (opt.transform.empty()) enc.transform = "cdf53";
  } else if (opt.bpp > 0.0) {
    enc.mode = RateMode::bpp;
    enc.target = opt.bpp;
  } else if (opt.step > 0.0) {
    enc.mode = RateMode::step;
    enc.target = opt.step;
  } else {
    enc.mode = RateMode::psnr;
    enc.target = opt.psnr > 0.0 ? opt.psnr : 40.0;
  }
}

void run_compress(const CompressOptions& opt) {
  check_output_path(opt.output);
  const Image image = read_image(opt.input);
  EncodeOptions enc;
  if (!opt.transform.empty()) enc.transform = opt.transform;
  enc.levels = opt.levels;
  enc.entropy = opt.entropy;
  enc.threads = opt.threads;
  set_rate(opt, enc);
  set_transform_threads(opt.threads);
  const auto start = std::chrono::steady_clock::now();
  const EncodeResult r = encode_image(image, enc);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_bytes_atomically(opt.output, r.bytes);
  std::printf("%s: %zu bytes, %.4f bpp, PSNR %.3f dB, %.3f s (%zux%zu, %zu channel(s), %s)\n",
              opt.output.c_str(), r.bytes.size(), r.bpp, r.psnr, seconds, image.width, image.height,
              image.channels, to_string(image.type).c_str());
}

}  // namespace

void add_compress_command(CLI::App& app) {
  auto opt = std::make_shared<CompressOptions>();
  auto* cmd = app.add_subcommand("compress", "Compress an image to a .pw stream (default: cdf97, --psnr 40)");
  cmd->add_option("IN", opt->input, "input image (PNG, TIFF, EXR, PNM, ...)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("OUT", opt->output, "output .pw file")->required();
  cmd->add_option("--transform", opt->transform, "transform spec (cdf97, cdf53, pups:..., kobbelt:...)");
  cmd->add_option("--levels", opt->levels, "decomposition levels (default: from the image size)")
      ->check(CLI::Range(0, 32));
  auto* bpp =
      cmd->add_option("--bpp", opt->bpp, "target bits per pixel (whole file)")->check(CLI::PositiveNumber);
  auto* psnr =
      cmd->add_option("--psnr", opt->psnr, "target PSNR in dB (all channels)")->check(CLI::PositiveNumber);
  auto* step = cmd->add_option("--step", opt->step, "fixed quantizer base step (sample units)")
                   ->check(CLI::PositiveNumber);
  auto* lossless = cmd->add_flag("--lossless", opt->lossless, "bit-exact (cdf53 integer transform, RCT)");
  bpp->excludes(psnr, step, lossless);
  psnr->excludes(step, lossless);
  step->excludes(lossless);
  const std::map<std::string, EntropyCoder> coders{{"ebcot", EntropyCoder::ebcot},
                                                   {"zstd", EntropyCoder::zstd}};
  cmd->add_option("--entropy", opt->entropy, "entropy coder: ebcot (bit-plane, default) or zstd")
      ->transform(CLI::CheckedTransformer(coders, CLI::ignore_case));
  cmd->add_option("--threads", opt->threads, "worker threads (0: all cores)");
  cmd->callback([opt] { run_compress(*opt); });
}

}  // namespace pupwave::cli
