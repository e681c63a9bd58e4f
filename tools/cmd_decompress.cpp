#include "tools/commands.h"
namespace pupwave::cli {
void add_decompress_command(CLI::App& app) { app.add_subcommand("decompress", "(in progress)"); }
}  // namespace pupwave::cli
