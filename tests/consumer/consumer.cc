// Downstream use of the installed C++ API: `consumer IMAGE.pgm VOLUME.f32 NX NY NZ` compresses
// the image at 1 bpp and the volume with a max-error bound, decodes both and checks them.
#include <pupwave/pupwave.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

static std::vector<unsigned char> read_file(const char* path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

int main(int argc, char** argv) {
  if (argc != 6) return std::fprintf(stderr, "usage: consumer IMAGE.pgm VOLUME.f32 NX NY NZ\n"), 2;
  try {
    const auto pgm = read_file(argv[1]);  // binary PGM as `pupwave convert` writes it
    std::istringstream header(std::string(pgm.begin(), pgm.begin() + std::min<std::size_t>(pgm.size(), 64)));
    std::string magic;
    std::size_t w = 0, h = 0, maxval = 0;
    header >> magic >> w >> h >> maxval;
    if (magic != "P5" || maxval != 255) return std::fprintf(stderr, "not an 8-bit P5 PGM\n"), 1;
    const unsigned char* px = pgm.data() + std::size_t(header.tellg()) + 1;
    const auto bytes = pupwave::api::compress_image(
        pupwave::api::interleaved_view(px, w, h, 1, pupwave::api::SampleType::u8),
        {.rate = pupwave::api::ImageRate::bpp, .target = 1.0});
    const pupwave::api::Image back = pupwave::api::decompress_image(bytes);
    double se = 0;
    for (std::size_t i = 0; i < w * h; ++i) se += std::pow(double(std::uint8_t(back.data[i])) - px[i], 2);
    const double psnr = 10 * std::log10(255.0 * 255.0 / (se / double(w * h)));
    std::printf("image %zux%zu: %zu bytes (%.3f bpp), PSNR %.2f dB\n", w, h, bytes.size(),
                8.0 * bytes.size() / (w * h), psnr);

    const auto raw = read_file(argv[2]);
    const std::size_t n[3] = {std::stoul(argv[3]), std::stoul(argv[4]), std::stoul(argv[5])};
    if (raw.size() != n[0] * n[1] * n[2] * 4) return std::fprintf(stderr, "volume size mismatch\n"), 1;
    const auto* v = reinterpret_cast<const float*>(raw.data());
    const auto vbytes =
        pupwave::api::compress_volume({v, {n[0], n[1], n[2]}, pupwave::api::VoxelType::f32},
                                      {.rate = pupwave::api::VolumeRate::max_error, .target = 0.1});
    const auto grids = pupwave::api::decompress_volume(vbytes);
    const auto* vb = reinterpret_cast<const float*>(grids.at(0).data.data());
    double worst = 0;
    for (std::size_t i = 0; i < n[0] * n[1] * n[2]; ++i)
      worst = std::max(worst, std::abs(double(vb[i]) - v[i]));
    std::printf("volume %zux%zux%zu: %zu bytes, max error %.4g (bound 0.1)\n", n[0], n[1], n[2],
                vbytes.size(), worst);
    return psnr > 30 && 8.0 * bytes.size() <= double(w * h) + 64 && worst <= 0.1 ? 0 : 1;
  } catch (const pupwave::api::Error& e) {
    std::fprintf(stderr, "pupwave: error: %s\n", e.what());
    return 1;
  }
}
