#pragma once
// Shared by the fuzz targets of the native image file readers (fuzz_png, fuzz_exr, fuzz_tiff,
// fuzz_jpeg): the input goes to a per-process file in /dev/shm or the temp directory and is read
// row by row, so a header promising a large image costs one row of memory, not the image.
// Invariant: every strip has the header's width, channels and type, the rows add up to its
// height, and integer samples lie within the type's range. std::runtime_error (a bad file) is an
// expected result.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "fuzz_check.h"
#include "tools/image_io.h"

namespace pupwave::fuzz {

// The per-process input file (named with the format's extension), removed when the process ends.
class InputFile {
 public:
  explicit InputFile(const std::string& extension) {
    const std::filesystem::path shm = "/dev/shm";
    const auto dir = std::filesystem::is_directory(shm) ? shm : std::filesystem::temp_directory_path();
    path_ = dir / ("pupwave_fuzz_" + std::to_string(::getpid()) + extension);
  }
  ~InputFile() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  // Writes the input; false if the file cannot be written.
  bool put(const std::uint8_t* data, std::size_t size) const {
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    if (f == nullptr) return false;
    if (size > 0) std::fwrite(data, 1, size, f);  // an empty input may come with a null pointer
    return std::fclose(f) == 0;
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Runs `open` (a native reader's open_*_rows) on the input and checks its rows.
template <class Open>
int fuzz_rows(const InputFile& file, const std::uint8_t* data, std::size_t size, Open open) {
  if (!file.put(data, size)) return 0;
  try {
    const std::unique_ptr<cli::ImageRowReader> rows = open(file.path());
    if (!rows) return 0;
    const float top = rows->type() == SampleType::u8 ? 255.0f : 65535.0f;
    const bool integer = is_integer(rows->type());
    std::size_t height = 0;
    for (Image strip = rows->next(16); strip.height > 0; strip = rows->next(16)) {
      FUZZ_CHECK(strip.width == rows->width() && strip.channels == rows->channels());
      FUZZ_CHECK(strip.type == rows->type());
      FUZZ_CHECK(strip.samples.size() == strip.width * strip.height * strip.channels);
      if (integer)
        for (float v : strip.samples) FUZZ_CHECK(v >= 0.0f && v <= top);
      height += strip.height;
    }
    FUZZ_CHECK(height == rows->height());
  } catch (const std::runtime_error&) {
  }
  return 0;
}

}  // namespace pupwave::fuzz
