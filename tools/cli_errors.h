#pragma once
// Command-line parse errors reported like every other error ("pupwave: error: ...", exit
// code 1), with the closest option or subcommand name suggested for a typo.

#include <CLI/CLI.hpp>
#include <string>

namespace pupwave::cli {

// The message for a parse error of `app` (not a help or version request), with a
// "did you mean" hint when an unknown argument is close to a known name.
std::string parse_error_message(CLI::App& app, const CLI::ParseError& error);

}  // namespace pupwave::cli
