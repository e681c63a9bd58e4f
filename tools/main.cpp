// `pupwave`: one binary, many subcommands; a thin layer over the library.
#include <exception>
#include <iostream>

#include "tools/cli_errors.h"
#include "tools/cli_numbers.h"
#include "tools/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"pupwave: wavelet image and volume codec (PUPs, Kobbelt and CDF filter banks)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "pupwave 0.1.0");
  pupwave::cli::add_info_command(app);
  pupwave::cli::add_psnr_command(app);
  pupwave::cli::add_convert_command(app);
  pupwave::cli::add_compress_command(app);
  pupwave::cli::add_decompress_command(app);
  pupwave::cli::add_bench_command(app);
  pupwave::cli::add_generate_volume_command(app);
  pupwave::cli::add_lod_command(app);
  pupwave::cli::add_convert_volume_command(app);
  pupwave::cli::add_filters_command(app);
  pupwave::cli::add_subdivide_command(app);
  pupwave::cli::add_mesh_command(app);
  pupwave::cli::require_finite_numbers(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version
  } catch (const CLI::ParseError& e) {
    // Parse errors read and exit like every other error.
    std::cerr << "pupwave: error: " << pupwave::cli::parse_error_message(app, e) << '\n';
    return 1;
  } catch (const std::exception& e) {
    // Library and I/O errors carry a complete message; print it and fail.
    std::cerr << "pupwave: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
