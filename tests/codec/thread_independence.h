#pragma once
// The codec's promise across thread counts, shared by the coders' tests: the same stream from a
// serial and a 4-thread encode, and the same pixels from a serial and a 4-thread decode.

#include <gtest/gtest.h>

#include "codec/image/image_codec.h"
#include "transforms/executor.h"

namespace pupwave::testing {

inline void expect_thread_independent(const Image& img, EncodeOptions o) {
  o.executor = &serial_executor();
  const auto serial = encode_image(img, o).bytes;
  const auto four = make_pool_executor(4);
  o.executor = four.get();
  EXPECT_EQ(encode_image(img, o).bytes, serial);
  EXPECT_EQ(decode_image(serial, 0, serial_executor()).samples, decode_image(serial, 0, *four).samples);
}

}  // namespace pupwave::testing
