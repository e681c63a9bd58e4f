// fuzz_jpeg: the libjpeg reader (tools/jpeg_io.cpp) through its row reader (fuzz_rows.h: the input
// file, the invariants).
#include "fuzz_rows.h"
#include "tools/jpeg_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const pupwave::fuzz::InputFile file(".jpg");
  return pupwave::fuzz::fuzz_rows(file, data, size, pupwave::cli::open_jpeg_rows);
}
