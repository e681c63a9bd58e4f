#include "tools/commands.h"
namespace pupwave::cli {
void add_info_command(CLI::App& app) { app.add_subcommand("info", "(in progress)"); }
}  // namespace pupwave::cli
