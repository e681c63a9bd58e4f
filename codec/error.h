#pragma once
// Errors the codec reports. They are exceptions caught at the CLI boundary and turned into a
// message and a non-zero exit there; the library never prints or exits.

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

// Throws DecodeError(what) unless condition holds; used for every field and length check.
void require_stream(bool condition, const std::string& what);

}  // namespace pupwave
