#include "tools/commands.h"
namespace pupwave::cli {
void add_psnr_command(CLI::App& app) { app.add_subcommand("psnr", "(in progress)"); }
}  // namespace pupwave::cli
