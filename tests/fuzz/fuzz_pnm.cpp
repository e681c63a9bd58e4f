// fuzz_pnm: the binary PGM/PPM reader (it reads a path: the input goes to a per-process
// file in /dev/shm or the temp directory). Invariant: an image read has as many samples as
// its header's width x height x channels, and maxval-consistent values.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "fuzz_check.h"
#include "tools/pnm_io.h"

using namespace pupwave;

namespace {

std::filesystem::path input_path() {
  const std::filesystem::path shm = "/dev/shm";
  const auto dir = std::filesystem::is_directory(shm) ? shm : std::filesystem::temp_directory_path();
  return dir / ("pupwave_fuzz_pnm_" + std::to_string(::getpid()) + ".pgm");
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
  const std::filesystem::path& path = file.path;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  std::optional<Image> image;
  try {
    image = cli::read_binary_pnm(path);
  } catch (const std::runtime_error&) {
    return 0;
  }
  if (!image) return 0;
  FUZZ_CHECK(image->samples.size() == image->width * image->height * image->channels);
  FUZZ_CHECK(image->channels == 1 || image->channels == 3);
  const float top = image->type == SampleType::u8 ? 255.0f : 65535.0f;
  for (float v : image->samples) FUZZ_CHECK(v >= 0.0f && v <= top);
  return 0;
}
