// In-process encode CPU of the pc coder (`--entropy pc`) against the bit-plane coder (`--entropy
// ebcot`), one thread, each test photograph at 1 bpp (as `pupwave compress --bpp 1 --threads 1`
// without process start-up and image reading, which dominate a whole-process time on 512 x 512).
// Run: build/bench/pc_cpu_bench --benchmark_min_time=1   (CPU column: one thread, so CPU = work)
// build/bench/pc_cpu_bench --passes: the rate search's coding passes per photograph and target
// (0.125-2 bpp, as `pupwave bench rd`, and 30-40 dB) with the size against the budget;
// `--passes IMAGE...` the same for other images.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "codec/image/encode_stats.h"
#include "codec/image/image_codec.h"
#include "tools/image_io.h"
#include "transforms/executor.h"

namespace {

const char* const kPhotos[] = {"astronaut.png", "camera.png", "chelsea.png", "coffee.png"};

pupwave::Image photo(const std::string& name) {
  return pupwave::cli::read_image(
      name.find('/') == std::string::npos ? std::string(PUPWAVE_TESTIMAGES_DIR) + "/" + name : name);
}

void bm_encode(benchmark::State& state, const char* name, pupwave::EntropyCoder coder) {
  const pupwave::Image image = photo(name);
  pupwave::EncodeOptions o;
  o.mode = pupwave::RateMode::bpp;
  o.target = 1.0;
  o.entropy = coder;
  o.measure_psnr = false;  // as `pupwave compress` without --report-psnr
  o.executor = &pupwave::serial_executor();
  for (auto _ : state) benchmark::DoNotOptimize(pupwave::encode_image(image, o));
}

#define PC_CPU(photo, id)                                                         \
  BENCHMARK_CAPTURE(bm_encode, id##_default, photo, pupwave::EntropyCoder::ebcot) \
      ->Unit(benchmark::kMillisecond);                                            \
  BENCHMARK_CAPTURE(bm_encode, id##_pc, photo, pupwave::EntropyCoder::pc)->Unit(benchmark::kMillisecond)
PC_CPU("astronaut.png", astronaut);
PC_CPU("camera.png", camera);
PC_CPU("chelsea.png", chelsea);
PC_CPU("coffee.png", coffee);

// One line per photograph and target: passes, trims, abandoned share (EncodeStats' pc figures), and the size
// as a fraction of the budget (bpp) or the PSNR reached (dB).
int print_passes(std::vector<std::string> names) {
  if (names.empty()) names.assign(std::begin(kPhotos), std::end(kPhotos));
  std::printf("photo target passes trims abandoned result\n");
  int total = 0, trims_total = 0, count = 0;
  double abandoned_total = 0.0;
  for (const std::string& name : names) {
    const pupwave::Image image = photo(name);
    const std::vector<double> rates{0.125, 0.25, 0.5, 1.0, 2.0}, psnrs{30.0, 35.0, 40.0};
    for (const bool bpp : {true, false})
      for (const double target : bpp ? rates : psnrs) {
        pupwave::EncodeOptions o;
        o.mode = bpp ? pupwave::RateMode::bpp : pupwave::RateMode::psnr;
        o.target = target;
        o.entropy = pupwave::EntropyCoder::pc;
        o.measure_psnr = false;
        pupwave::EncodeStats stats;
        o.stats = &stats;
        const auto r = pupwave::encode_image(image, o);
        const int passes = stats.pc_passes;
        const int trims = stats.pc_trims;
        const double abandoned = stats.pc_abandoned_share;
        const double budget = std::floor(target * double(image.plane_size()) / 8.0);
        std::printf("%s %g%s %d %d %.2f %.5f\n", name.c_str(), target, bpp ? "bpp" : "dB", passes, trims,
                    abandoned, bpp ? double(r.bytes.size()) / budget : r.psnr);
        if (bpp) total += passes, trims_total += trims, abandoned_total += abandoned, ++count;
      }
  }
  std::printf("mean passes (bpp) %.2f, trims %.2f, abandoned %.2f\n", double(total) / count,
              double(trims_total) / count, abandoned_total / count);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "--passes") == 0)
    return print_passes(std::vector<std::string>(argv + 2, argv + argc));
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
