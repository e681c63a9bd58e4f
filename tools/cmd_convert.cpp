// `pupwave convert IN OUT`: re-encode an image in another file format through the library's
// planar buffers (the same path compress and decompress use), a strip of rows at a time, e.g.
// PNG to PPM for anchors.
#include <cstdio>
#include <memory>
#include <string>

#include "tools/atomic_file.h"
#include "tools/cli_stdio.h"
#include "tools/commands.h"
#include "tools/image_io.h"

namespace pupwave::cli {

void add_convert_command(CLI::App& app) {
  struct Options {
    std::string input, output, format;
    Verbosity verbosity;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "convert",
      "Convert an image to the format of OUT's extension or --format (png, jpg, tif, ppm/pgm, exr, ...).\n"
      "Samples are kept exactly when OUT's format can store their type, else converted to the\n"
      "closest type it can store (e.g. float to 16-bit PNG) through the nominal range.");
  cmd->add_option("IN", opt->input, "input image, or - for stdin")
      ->required()
      ->check(existing_file_or_stdin());
  cmd->add_option("OUT", opt->output,
                  "output image, or - for stdout (PNG, EXR for float images; status then goes to stderr)")
      ->required();
  cmd->add_option(
      "--format", opt->format,
      "output format, overriding OUT's extension (png, tif, exr, ppm, pgm, jpg, ...): for outputs "
      "whose name tells none, as - or a FIFO");
  add_verbosity_flags(*cmd, opt->verbosity);
  cmd->callback([opt] {
    Options o = *opt;
    o.verbosity.to_stderr = is_stdio(o.output);
    // stdout without --format: PNG or EXR by the sample type (stdout_image_format).
    const bool by_type = is_stdio(o.output) && o.format.empty();
    const std::filesystem::path format_as =
        by_type ? std::filesystem::path() : format_name_path(o.output, o.format);
    check_output_path(o.output);
    if (!by_type) check_image_format(o.output, format_as);  // before reading: a bad name costs nothing
    const InputPath in(o.input);
    const auto rows = open_image_rows(in.path);  // by strips: neither image is ever whole in memory
    const SampleType stored =
        write_image_rows(*rows, o.output, by_type ? stdout_image_format(rows->type()) : format_as);
    if (std::FILE* status = o.verbosity.stream())
      std::fprintf(
          status, "%s: %zu x %zu, %zu channel(s), %s%s\n", o.output.c_str(), rows->width(), rows->height(),
          rows->channels(), to_string(stored).c_str(),
          stored == rows->type() ? "" : (" (converted from " + to_string(rows->type()) + ")").c_str());
  });
}

}  // namespace pupwave::cli
