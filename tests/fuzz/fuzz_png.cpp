// fuzz_png: the libpng reader (tools/png_io.cpp) through its row reader, so a header promising a
// large image costs one row of memory, not the image (the input goes to a per-process file in
// /dev/shm or the temp directory). Invariant: every strip has the header's width and channels,
// the rows add up to its height, and values lie within the sample type's range.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "fuzz_check.h"
#include "tools/png_io.h"

using namespace pupwave;

namespace {

std::filesystem::path input_path() {
  const std::filesystem::path shm = "/dev/shm";
  const auto dir = std::filesystem::is_directory(shm) ? shm : std::filesystem::temp_directory_path();
  return dir / ("pupwave_fuzz_png_" + std::to_string(::getpid()) + ".png");
}

// The per-process input file, removed when the process ends.
struct InputFile {
  std::filesystem::path path = input_path();
  ~InputFile() {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const InputFile file;
  std::FILE* f = std::fopen(file.path.c_str(), "wb");
  if (f == nullptr) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  try {
    const auto rows = cli::open_png_rows(file.path);
    if (!rows) return 0;
    const float top = rows->type() == SampleType::u8 ? 255.0f : 65535.0f;
    std::size_t height = 0;
    for (Image strip = rows->next(16); strip.height > 0; strip = rows->next(16)) {
      FUZZ_CHECK(strip.width == rows->width() && strip.channels == rows->channels());
      FUZZ_CHECK(strip.samples.size() == strip.width * strip.height * strip.channels);
      for (float v : strip.samples) FUZZ_CHECK(v >= 0.0f && v <= top);
      height += strip.height;
    }
    FUZZ_CHECK(height == rows->height());
  } catch (const std::runtime_error&) {
  }
  return 0;
}
