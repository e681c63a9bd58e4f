#include "tools/commands.h"
namespace pupwave::cli {
void add_compress_command(CLI::App& app) { app.add_subcommand("compress", "(in progress)"); }
}  // namespace pupwave::cli
