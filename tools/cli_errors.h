#pragma once
// Command-line parse errors reported like every other error ("pupwave: error: ...", exit
// code 1), with the closest option or subcommand name suggested for a typo.

#include <CLI/CLI.hpp>
#include <string>

#include "codec/error.h"

namespace pupwave::cli {

// The message for a parse error of `app` (not a help or version request), with a
// "did you mean" hint when an unknown argument is close to a known name.
std::string parse_error_message(CLI::App& app, const CLI::ParseError& error);

// Runs `decode`, which reads the stream given as `path`; a DecodeError comes back naming that
// path ("standard input" for -), which the codec's own message cannot know.
template <class F>
decltype(auto) naming_stream(const std::string& path, F&& decode) {
  try {
    return decode();
  } catch (const DecodeError& e) {
    throw DecodeError((path == "-" ? std::string("standard input") : path) + ": " + e.what());
  }
}

}  // namespace pupwave::cli
