// Throughput of the separable engine: forward and inverse transforms of a 4096 x 4096 float
// image (default levels) for every transform make_transform knows, next to a memcpy of the
// same buffer. Run: build/bench/transform_bench --benchmark_min_time=0.5s
#include <benchmark/benchmark.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "transforms/separable.h"
#include "transforms/spec.h"

namespace {

constexpr std::size_t kSide = 4096;
const pupwave::Extent kDims{kSide, kSide, 1};

// A smooth ramp plus noise, so coefficients look like those of an image.
template <class T>
const std::vector<T>& test_image() {
  static const std::vector<T> image = [] {
    std::vector<T> v(kSide * kSide);
    std::mt19937 rng(1);
    std::uniform_int_distribution<int> noise(-8, 8);
    for (std::size_t y = 0; y < kSide; ++y)
      for (std::size_t x = 0; x < kSide; ++x)
        v[y * kSide + x] = static_cast<T>(static_cast<int>((x + y) / 40) + noise(rng));
    return v;
  }();
  return image;
}

void set_bytes(benchmark::State& state, std::size_t bytes) {
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(bytes));
}

void bm_memcpy(benchmark::State& state) {
  const auto& src = test_image<float>();
  std::vector<float> dst(src.size());
  for (auto _ : state) {
    std::memcpy(dst.data(), src.data(), src.size() * sizeof(float));
    benchmark::DoNotOptimize(dst.data());
    benchmark::ClobberMemory();
  }
  set_bytes(state, src.size() * sizeof(float));
}

// One forward (or inverse) transform per iteration; the input is restored outside the timing.
template <class T>
void bm_transform(benchmark::State& state, const std::string& spec, bool inverse) {
  const auto t = pupwave::make_transform(spec);
  const auto executor = pupwave::make_pool_executor(static_cast<unsigned>(state.range(0)));
  const int levels = pupwave::default_levels(kDims);
  std::vector<T> input = test_image<T>();
  if (inverse) pupwave::forward(*t, input.data(), kDims, levels);
  std::vector<T> work(input.size());
  for (auto _ : state) {
    state.PauseTiming();
    std::memcpy(work.data(), input.data(), input.size() * sizeof(T));
    state.ResumeTiming();
    if (inverse) {
      pupwave::inverse(*t, work.data(), kDims, levels, 0, *executor);
    } else {
      pupwave::forward(*t, work.data(), kDims, levels, *executor);
    }
    benchmark::DoNotOptimize(work.data());
  }
  set_bytes(state, input.size() * sizeof(T));
}

// threads = 1 is timed by CPU time (robust on a shared machine); threads = 0 (all hardware
// threads) by wall-clock time, the only meaningful measure of a parallel run.
template <class F>
void register_both(const std::string& name, F body) {
  benchmark::RegisterBenchmark(name.c_str(), body)->Arg(1)->ArgName("threads")->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(name.c_str(), body)
      ->Arg(0)
      ->ArgName("threads")
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
}

void register_all() {
  benchmark::RegisterBenchmark("memcpy/float", bm_memcpy)->Unit(benchmark::kMillisecond);
  for (const auto& spec : pupwave::transform_specs()) {
    for (bool inv : {false, true}) {
      const std::string name = spec + (inv ? "/inverse" : "/forward") + "/float";
      register_both(name, [spec, inv](benchmark::State& s) { bm_transform<float>(s, spec, inv); });
    }
  }
  for (bool inv : {false, true}) {  // the lossless path
    const std::string name = std::string("cdf53") + (inv ? "/inverse" : "/forward") + "/int32";
    register_both(name, [inv](benchmark::State& s) { bm_transform<int32_t>(s, "cdf53", inv); });
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
