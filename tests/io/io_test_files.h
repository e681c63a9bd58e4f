#pragma once
// What the image I/O tests share: a scratch folder per test process, the bundled test images,
// whole-file bytes, a JPEG's header segments, random images and the comparison of two read images.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <Imath/half.h>

#include "codec/image/image.h"

namespace pupwave::test {

namespace fs = std::filesystem;

// A folder of this test process's own (ctest runs each test in a process of its own).
inline fs::path scratch_dir() {
  fs::path dir = fs::temp_directory_path() / ("pupwave_io_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

inline fs::path testimage(const std::string& name) { return fs::path(PUPWAVE_TESTIMAGES_DIR) / name; }

inline std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

inline void put_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// The segments of a JPEG file from its first marker after the start of the image up to its first
// quantization table (JFIF, comments, APPn), each with its marker and length bytes.
inline std::vector<std::string> jpeg_header_segments(const fs::path& path) {
  const std::string bytes = file_bytes(path);
  std::vector<std::string> segments;
  for (std::size_t at = 2; at + 4 <= bytes.size() && bytes[at] == '\xff' && bytes[at + 1] != '\xdb';) {
    const std::size_t length = std::uint8_t(bytes[at + 2]) << 8 | std::uint8_t(bytes[at + 3]);
    segments.push_back(bytes.substr(at, 2 + length));
    at += 2 + length;
  }
  return segments;
}

// Random samples covering the whole range of the type (negative and large values for floats).
inline Image random_image(std::size_t w, std::size_t h, std::size_t c, SampleType type, unsigned seed) {
  Image img(w, h, c, type);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-2.0f, 3.0f);
  for (float& v : img.samples) {
    switch (type) {
      case SampleType::u8: v = float(rng() % 256); break;
      case SampleType::u16: v = float(rng() % 65536); break;
      case SampleType::f16: v = float(Imath::half(unit(rng))); break;
      case SampleType::f32: v = unit(rng); break;
    }
  }
  return img;
}

// The same image: size, type, samples, the metadata a stream keeps and what was not kept.
inline void expect_same_image(const Image& a, const Image& b, const std::string& what) {
  EXPECT_EQ(a.width, b.width) << what;
  EXPECT_EQ(a.height, b.height) << what;
  EXPECT_EQ(a.channels, b.channels) << what;
  EXPECT_EQ(a.type, b.type) << what;
  EXPECT_TRUE(a.samples == b.samples) << what;
  EXPECT_TRUE(a.metadata == b.metadata) << what;
  EXPECT_EQ(a.metadata.not_kept, b.metadata.not_kept) << what;
}

}  // namespace pupwave::test
