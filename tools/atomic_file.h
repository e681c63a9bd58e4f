#pragma once
// Output files are written under a temporary name beside the target and renamed into place,
// so a failure never leaves a partial file or clobbers an existing one.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <vector>

namespace pupwave::cli {

// Checks that `target` can be an output file (not a directory, parent exists); throws
// std::runtime_error with a clear message otherwise. Call before doing expensive work.
void check_output_path(const std::filesystem::path& target);

// Calls write(temp_path) to produce the file under a temporary name in the target's folder,
// then renames it onto `target`. On any exception the temporary file is removed and the
// exception propagates; `target` is untouched.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path&)>& write);

// Writes bytes to `target` atomically (see write_atomically).
void write_bytes_atomically(const std::filesystem::path& target, std::span<const std::uint8_t> bytes);

// Reads a whole file; throws std::runtime_error("cannot read ...") when it cannot, and refuses
// files larger than max_bytes so hostile input cannot exhaust memory.
std::vector<std::uint8_t> read_file_bytes(const std::filesystem::path& path,
                                          std::uintmax_t max_bytes = std::uintmax_t(1) << 34);

}  // namespace pupwave::cli
