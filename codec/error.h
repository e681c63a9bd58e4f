#pragma once
// Errors the codec reports. They are exceptions caught at the CLI boundary and turned into a
// message and a non-zero exit there; the library never prints or exits.

#include <concepts>
#include <stdexcept>
#include <string>

namespace pupwave {

// Bad parameters or unsupported input given to an encoder.
class EncodeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A compressed stream that is truncated, corrupted or not a pupwave file.
class DecodeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws DecodeError("corrupt or truncated stream: " + what).
[[noreturn]] void throw_corrupt_stream(const std::string& what);

// Throws DecodeError(what) unless condition holds; used for every field and length check.
// The message is a literal, or a callable that builds it: either way nothing is allocated on
// the success path, which runs once per field of every stream.
inline void require_stream(bool condition, const char* what) {
  if (!condition) [[unlikely]]
    throw_corrupt_stream(what);
}
template <std::invocable F>
inline void require_stream(bool condition, F&& what) {
  if (!condition) [[unlikely]]
    throw_corrupt_stream(std::string(what()));
}

}  // namespace pupwave
