// fuzz_exr: the OpenEXR reader (tools/exr_io.cpp) through its row reader (fuzz_rows.h: the input
// file, the invariants).
#include <OpenEXR/ImfHeader.h>

#include "fuzz_rows.h"
#include "tools/exr_io.h"

namespace {

// OpenEXR sizes its chunk buffers by the header's width, channels and lines per chunk before any
// pixel is read, so a few bytes of header can cost gigabytes; the fuzzer bounds the data window
// and tiles the way OpenEXR's own fuzz targets do, and the reader's own checks run within that.
bool bound_openexr() {
  Imf::Header::setMaxImageSize(512, 512);
  Imf::Header::setMaxTileSize(128, 128);
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool bounded = bound_openexr();
  static const pupwave::fuzz::InputFile file(".exr");
  (void)bounded;
  return pupwave::fuzz::fuzz_rows(file, data, size, pupwave::cli::open_exr_rows);
}
