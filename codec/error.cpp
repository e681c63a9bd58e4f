#include "codec/error.h"

namespace pupwave {

void require_stream(bool condition, const std::string& what) {
  if (!condition) throw DecodeError("corrupt or truncated stream: " + what);
}

}  // namespace pupwave
