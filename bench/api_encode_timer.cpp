// The C++ library side of bench/api_overhead.py: `api_encode_timer IMAGE.ppm BPP RUNS` encodes
// a binary PPM with pupwave::api::compress_image (no file I/O inside the timing) and prints one
// line per run: "<seconds> <bytes>". The Python side times pupwave.compress on the same pixels.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "pupwave/pupwave.hpp"

int main(int argc, char** argv) {
  if (argc != 4) return std::fprintf(stderr, "usage: api_encode_timer IMAGE.ppm BPP RUNS\n"), 2;
  std::ifstream in(argv[1], std::ios::binary);
  std::string magic;
  std::size_t w = 0, h = 0, maxval = 0;
  in >> magic >> w >> h >> maxval;
  in.get();
  if (magic != "P6" || maxval != 255) return std::fprintf(stderr, "need an 8-bit binary PPM\n"), 1;
  std::vector<unsigned char> px(w * h * 3);
  if (!in.read(reinterpret_cast<char*>(px.data()), std::streamsize(px.size())))
    return std::fprintf(stderr, "truncated PPM\n"), 1;
  pupwave::api::ImageOptions options;
  options.rate = pupwave::api::ImageRate::bpp;
  options.target = std::stod(argv[2]);
  const auto view = pupwave::api::interleaved_view(px.data(), w, h, 3, pupwave::api::SampleType::u8);
  for (int run = 0; run < std::stoi(argv[3]); ++run) {
    const auto start = std::chrono::steady_clock::now();
    const auto bytes = pupwave::api::compress_image(view, options);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%.4f %zu\n", s, bytes.size());
    std::fflush(stdout);
  }
}
