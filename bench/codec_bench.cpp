// Image codec speed on a 4096 x 4096 RGB mosaic of the bundled photographs, 1 bpp, cdf97, all
// threads: in-process encode and decode throughput (input megapixels per second).
// Run: build/bench/codec_bench --benchmark_min_time=2s
// `codec_bench --write-mosaic OUT.ppm` writes the mosaic instead, so the whole-process
// comparison with OpenJPEG (bench/codec_speed.sh) codes exactly the same pixels;
// `--write-grey-mosaic OUT.pgm` writes its luma.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "codec/image/image_codec.h"
#include "tools/image_io.h"

namespace {

constexpr std::size_t kSide = 4096;
constexpr std::size_t kCell = 512;

// Cells of 512 x 512 cycle through the four photographs; each cell shows the photograph from
// its top-left corner, wrapping around where the photograph is smaller; grey becomes R=G=B.
pupwave::Image make_mosaic() {
  std::vector<pupwave::Image> photos;
  for (const char* name : {"astronaut.png", "coffee.png", "chelsea.png", "camera.png"})
    photos.push_back(pupwave::cli::read_image(std::string(PUPWAVE_TESTIMAGES_DIR) + "/" + name));
  pupwave::Image mosaic(kSide, kSide, 3, pupwave::SampleType::u8);
  for (std::size_t y = 0; y < kSide; ++y) {
    for (std::size_t x = 0; x < kSide; ++x) {
      const auto& p = photos[(y / kCell * (kSide / kCell) + x / kCell + y / kCell) % photos.size()];
      const std::size_t px = (x % kCell) % p.width, py = (y % kCell) % p.height;
      for (std::size_t c = 0; c < 3; ++c) mosaic.at(c, x, y) = p.at(p.channels == 3 ? c : 0, px, py);
    }
  }
  return mosaic;
}

// The mosaic in grey (Rec. 601 luma, rounded), for the grey rows of bench/codec_speed.sh.
pupwave::Image grey_mosaic() {
  const pupwave::Image rgb = make_mosaic();
  pupwave::Image grey(kSide, kSide, 1, pupwave::SampleType::u8);
  for (std::size_t y = 0; y < kSide; ++y)
    for (std::size_t x = 0; x < kSide; ++x)
      grey.at(0, x, y) =
          std::round(0.299f * rgb.at(0, x, y) + 0.587f * rgb.at(1, x, y) + 0.114f * rgb.at(2, x, y));
  return grey;
}

const pupwave::Image& mosaic() {
  static const pupwave::Image image = make_mosaic();
  return image;
}

pupwave::EncodeOptions one_bpp() {
  pupwave::EncodeOptions options;
  options.transform = "cdf97";
  options.mode = pupwave::RateMode::bpp;
  options.target = 1.0;
  options.measure_psnr = false;  // as `pupwave compress` without --report-psnr
  return options;
}

void set_pixels(benchmark::State& state) {
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kSide * kSide));
}

void bm_encode(benchmark::State& state) {
  const auto& image = mosaic();
  for (auto _ : state) benchmark::DoNotOptimize(pupwave::encode_image(image, one_bpp()));
  set_pixels(state);
}
BENCHMARK(bm_encode)->Unit(benchmark::kMillisecond)->UseRealTime();

void bm_decode(benchmark::State& state) {
  auto options = one_bpp();
  options.measure_psnr = true;
  const auto stream = pupwave::encode_image(mosaic(), options);
  state.counters["bpp"] = stream.bpp;
  state.counters["psnr_dB"] = stream.psnr;
  for (auto _ : state) benchmark::DoNotOptimize(pupwave::decode_image(stream.bytes));
  set_pixels(state);
}
BENCHMARK(bm_decode)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::strcmp(argv[1], "--write-mosaic") == 0) {
    pupwave::cli::write_image(mosaic(), argv[2]);
    return 0;
  }
  if (argc == 3 && std::strcmp(argv[1], "--write-grey-mosaic") == 0) {
    pupwave::cli::write_image(grey_mosaic(), argv[2]);
    return 0;
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
