// Before/after timing of the separable engine on volume bricks (the lift helper's check):
// `brick_transform_timer SPEC REPS [wmag91.float]` transforms the 64^3 corner brick of wmag91
// forward and back REPS times (serial, default levels, as the volume codec does per brick) and
// prints the CPU milliseconds per brick of each direction, then FNV-1a hashes of the forward
// coefficients and the reconstruction of that brick and of the whole 91^3 volume (odd
// extents), so two builds can be checked bit-identical by comparing the hash lines.
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include "transforms/separable.h"
#include "transforms/spec.h"

namespace {

std::uint64_t fnv1a(const std::vector<float>& v) {
  std::uint64_t h = 1469598103934665603ull;
  const auto* p = reinterpret_cast<const unsigned char*>(v.data());
  for (std::size_t i = 0; i < v.size() * sizeof(float); ++i) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

double cpu_seconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) return std::fprintf(stderr, "usage: brick_transform_timer SPEC REPS [wmag91.float]\n"), 2;
  const auto t = pupwave::make_transform(argv[1]);
  const int reps = std::stoi(argv[2]);
  const std::string path = argc > 3 ? argv[3] : PUPWAVE_TESTIMAGES_DIR "/wmag91.float";
  constexpr std::size_t kN = 91, kB = 64;
  std::vector<float> volume(kN * kN * kN);
  std::ifstream in(path, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(volume.data()), std::streamsize(volume.size() * sizeof(float))))
    return std::fprintf(stderr, "cannot read %s\n", path.c_str()), 1;
  std::vector<float> brick(kB * kB * kB);
  for (std::size_t z = 0; z < kB; ++z)
    for (std::size_t y = 0; y < kB; ++y)
      for (std::size_t x = 0; x < kB; ++x) brick[(z * kB + y) * kB + x] = volume[(z * kN + y) * kN + x];
  const pupwave::Extent bd{kB, kB, kB}, vd{kN, kN, kN};
  const int bl = pupwave::default_levels(bd), vl = pupwave::default_levels(vd);
  std::vector<float> work = brick;
  double fwd = 0, inv = 0;
  for (int r = 0; r < reps; ++r) {
    work = brick;
    const double t0 = cpu_seconds();
    pupwave::forward(*t, work.data(), bd, bl);
    const double t1 = cpu_seconds();
    pupwave::inverse(*t, work.data(), bd, bl);
    inv += cpu_seconds() - t1;
    fwd += t1 - t0;
  }
  std::printf("%s forward %.3f ms inverse %.3f ms per 64^3 brick (%d reps)\n", t->spec().c_str(),
              1e3 * fwd / reps, 1e3 * inv / reps, reps);
  work = brick;
  pupwave::forward(*t, work.data(), bd, bl);
  const std::uint64_t hb = fnv1a(work);
  pupwave::inverse(*t, work.data(), bd, bl);
  const std::uint64_t hbi = fnv1a(work);
  work = volume;
  pupwave::forward(*t, work.data(), vd, vl);
  const std::uint64_t hv = fnv1a(work);
  pupwave::inverse(*t, work.data(), vd, vl);
  std::printf("hash brick %016llx %016llx volume %016llx %016llx\n", (unsigned long long)hb,
              (unsigned long long)hbi, (unsigned long long)hv, (unsigned long long)fnv1a(work));
}
