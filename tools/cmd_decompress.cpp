// `pupwave decompress IN.pw OUT`: decode a stream (optionally at reduced resolution) and
// write the image atomically in the format OUT's extension names.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "codec/image_codec.h"
#include "tools/atomic_file.h"
#include "tools/commands.h"
#include "tools/image_io.h"
#include "transforms/separable.h"

namespace pupwave::cli {
namespace {

struct DecompressOptions {
  std::string input;
  std::string output;
  int level = 0;
  unsigned threads = 0;
};

void run_decompress(const DecompressOptions& opt) {
  check_output_path(opt.output);
  const auto bytes = read_file_bytes(opt.input);
  set_transform_threads(opt.threads);
  const auto start = std::chrono::steady_clock::now();
  const Image image = decode_image(bytes, opt.level, opt.threads);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  SampleType stored = image.type;
  write_image(image, opt.output, &stored);
  std::printf("%s: %zux%zu, %zu channel(s), %s, decoded in %.3f s\n", opt.output.c_str(), image.width,
              image.height, image.channels, to_string(stored).c_str(), seconds);
}

}  // namespace

void add_decompress_command(CLI::App& app) {
  auto opt = std::make_shared<DecompressOptions>();
  auto* cmd = app.add_subcommand("decompress", "Decompress a .pw stream to an image file");
  cmd->add_option("IN", opt->input, "input .pw file")->required()->check(CLI::ExistingFile);
  cmd->add_option("OUT", opt->output, "output image; the format follows the extension")->required();
  cmd->add_option("--level", opt->level, "decode at 1/2^k resolution, reading only what it needs")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--threads", opt->threads, "worker threads (0: all cores)");
  cmd->callback([opt] { run_decompress(*opt); });
}

}  // namespace pupwave::cli
