// fuzz_png: the libpng reader (tools/png_io.cpp) through its row reader (fuzz_rows.h: the input
// file, the invariants).
#include "fuzz_rows.h"
#include "tools/png_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const pupwave::fuzz::InputFile file(".png");
  return pupwave::fuzz::fuzz_rows(file, data, size, pupwave::cli::open_png_rows);
}
