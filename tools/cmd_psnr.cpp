// `pupwave psnr A B`: distortion of image B against reference image A.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "codec/image/image_metrics.h"
#include "codec/image/transfer.h"
#include "tools/cli_stdio.h"
#include "tools/commands.h"
#include "tools/image_io.h"

namespace pupwave::cli {
namespace {

struct PsnrOptions {
  std::string reference;
  std::string test;
};

std::string format_psnr(double psnr) {
  if (std::isinf(psnr)) return psnr > 0.0 ? "inf" : "-inf";  // identical, or a sample infinitely off
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f", psnr);
  return buf;
}

void print_row(const std::string& name, const ChannelError& e) {
  std::printf("%-8s %14.6f %10s %12.6g\n", name.c_str(), e.mse, format_psnr(e.psnr).c_str(), e.max_abs);
}

// Relative luminance error per decade: what a log-domain coder keeps even and a linear one does not.
void print_decades(const HdrError& e) {
  std::printf("luminance decade   pixels  median relative error\n");
  for (const DecadeError& d : e.decades)
    std::printf("[1e%+d, 1e%+d) %8.2f%% %10.3f%%\n", d.decade, d.decade + 1, 100.0 * d.share,
                100.0 * d.median_rel);
  std::printf("sign flips (reference >= 0, test < 0): %zu\n", e.sign_flips);
}

void run_psnr(const PsnrOptions& opt) {
  if (is_stdio(opt.reference) && is_stdio(opt.test))
    throw std::runtime_error("A and B cannot both be - (stdin)");
  const Image a = read_image(InputPath(opt.reference).path);
  Image b = read_image(InputPath(opt.test).path);
  if (b.type != a.type) b = convert_sample_type(b, a.type);  // compare in the reference's scale
  const ImageError err = compare_images(a, b);
  static const char* rgba[] = {"R", "G", "B", "A"};
  static const char* grey[] = {"Y", "A"};
  const auto& names = a.metadata.channel_names;
  std::printf("peak %.6g (%s)\n", err.peak, to_string(a.type).c_str());
  std::printf("%-8s %14s %10s %12s\n", "channel", "MSE", "PSNR(dB)", "max_abs_err");
  for (std::size_t c = 0; c < err.channels.size(); ++c)
    print_row(names.size() == a.channels ? names[c]
              : a.channels <= 2          ? grey[c]
              : c < 4                    ? rgba[c]
                                         : "c" + std::to_string(c),
              err.channels[c]);
  print_row("all", err.overall);
  if (err.has_luma) print_row("luma", err.luma);
  // Float images are coded (and their targets stated) in the log domain: the same metric here.
  if (!is_integer(a.type))
    std::printf("%-8s %14s %10s   (log2 domain, peak 1 stop; see docs/bitstream.md)\n", "log-PSNR", "",
                format_psnr(transfer_psnr(a, b, Transfer::log2)).c_str());
  if (!is_integer(a.type)) print_decades(hdr_error(a, b));
}

}  // namespace

void add_psnr_command(CLI::App& app) {
  auto opt = std::make_shared<PsnrOptions>();
  auto* cmd = app.add_subcommand(
      "psnr",
      "Compare image B against reference A: MSE, PSNR and max abs error per channel and overall,\n"
      "and luma (Rec. 601 Y) PSNR for RGB/RGBA. Peak: 2^bits-1 for integer samples, the value\n"
      "range of A's finite samples for float samples. A NaN or infinite sample of A counts as exact\n"
      "where B holds the same value, else as an infinite error (-inf dB). B is converted to A's\n"
      "sample type if they differ.");
  cmd->add_option("A", opt->reference, "reference image, or - for stdin")
      ->required()
      ->check(existing_file_or_stdin());
  cmd->add_option("B", opt->test, "test image, or - for stdin")->required()->check(existing_file_or_stdin());
  add_report_verbosity_flags(*cmd);
  cmd->callback([opt] { run_psnr(*opt); });
}

}  // namespace pupwave::cli
