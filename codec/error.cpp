#include "codec/error.h"

namespace pupwave {

void throw_corrupt_stream(const std::string& what) {
  throw DecodeError("corrupt or truncated stream: " + what);
}

}  // namespace pupwave
