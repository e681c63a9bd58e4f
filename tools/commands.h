#pragma once
// Registration of the `pupwave` subcommands. Each subcommand lives in its own cmd_*.cpp file
// and adds itself to the application; main() only parses and turns errors into exit codes.

#include <CLI/CLI.hpp>

namespace pupwave::cli {

void add_info_command(CLI::App& app);
void add_psnr_command(CLI::App& app);
void add_convert_command(CLI::App& app);
void add_compress_command(CLI::App& app);
void add_decompress_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_generate_volume_command(CLI::App& app);
void add_lod_command(CLI::App& app);
void add_convert_volume_command(CLI::App& app);
void add_filters_command(CLI::App& app);
void add_subdivide_command(CLI::App& app);
void add_mesh_command(CLI::App& app);

}  // namespace pupwave::cli
