// Issue 20: in-process encode CPU of the pc coder (`--entropy pc`) against the default bit-plane
// coder, one thread, each test photograph at 1 bpp (as `pupwave compress --bpp 1 --threads 1`
// without process start-up and image reading, which dominate a whole-process time on 512 x 512).
// Run: build/bench/pc_cpu_bench --benchmark_min_time=1   (CPU column: one thread, so CPU = work)
#include <benchmark/benchmark.h>

#include <string>

#include "codec/image/image_codec.h"
#include "tools/image_io.h"
#include "transforms/executor.h"

namespace {

void bm_encode(benchmark::State& state, const char* name, pupwave::EntropyCoder coder) {
  const pupwave::Image image = pupwave::cli::read_image(std::string(PUPWAVE_TESTIMAGES_DIR) + "/" + name);
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

}  // namespace

BENCHMARK_MAIN();
