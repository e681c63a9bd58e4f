// `pupwave convert IN OUT`: re-encode an image in another file format through the library's
// planar buffers (the same path compress and decompress use), e.g. PNG to PPM for anchors.
#include <iostream>
#include <memory>
#include <string>

#include "tools/commands.h"
#include "tools/image_io.h"

namespace pupwave::cli {

void add_convert_command(CLI::App& app) {
  struct Options {
    std::string input, output;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "convert",
      "Convert an image to the format of OUT's extension (png, jpg, tif, ppm/pgm, exr, ...).\n"
      "Samples are kept exactly when OUT's format can store their type, else converted to the\n"
      "closest type it can store (e.g. float to 16-bit PNG) through the nominal range.");
  cmd->add_option("IN", opt->input, "input image")->required();
  cmd->add_option("OUT", opt->output, "output image (written atomically)")->required();
  cmd->callback([opt] {
    const Image image = read_image(opt->input);
    SampleType stored = image.type;
    write_image(image, opt->output, &stored);
    std::cout << opt->output << ": " << image.width << " x " << image.height << ", " << image.channels
              << " channel(s), " << to_string(stored)
              << (stored == image.type ? "" : " (converted from " + to_string(image.type) + ")") << '\n';
  });
}

}  // namespace pupwave::cli
