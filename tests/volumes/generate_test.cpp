// `pupwave generate-volume`: the committed Gray-Scott test volume is reproduced byte for byte, runs
// are deterministic, and the turbulence field has the Kolmogorov -5/3 energy spectrum.
#include <cmath>
#include <complex>
#include <fstream>
#include <iterator>
#include <numbers>

#include "tools/volume_io.h"
#include "volumes/volume_test_util.h"

namespace pupwave::test {
namespace {

std::vector<char> file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST_F(VolumeTest, GrayScottReproducesCommittedTestVolume) {
  const fs::path out = dir_ / "gs.raw";
  const CliResult r =
      run_cli({"generate-volume", "--kind", "gray-scott", "--size", "64", "--steps", "4000", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(file_bytes(out) == file_bytes(testimage("gray_scott64.raw")));
}

TEST_F(VolumeTest, GrayScottDeterministicAndStructured) {
  const auto run = [&](const std::string& name, const std::string& seed) {
    const CliResult r = run_cli(
        {"generate-volume", "--size", "24", "--steps", "1000", "--seed", seed, (dir_ / name).string()});
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return cli::read_raw_volume(dir_ / name, {24, 24, 24}, VoxelType::f32);
  };
  const Volume a = run("a.raw", "1"), b = run("b.raw", "1"), c = run("c.raw", "2");
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_NE(a.samples, c.samples);
  double mean = 0, var = 0;
  for (double v : a.samples) mean += v / double(a.count());
  for (double v : a.samples) var += (v - mean) * (v - mean) / double(a.count());
  EXPECT_GT(std::sqrt(var), 0.01);                                    // a pattern, not a uniform state
  for (double v : a.samples) ASSERT_TRUE(v >= 0.0 && v <= 1.0) << v;  // concentrations
}

// Shell-summed power spectrum |F(k)|^2 of an n^3 field by separable direct DFTs.
std::vector<double> shell_spectrum(const std::vector<double>& f, std::size_t n) {
  using C = std::complex<double>;
  std::vector<C> a(f.begin(), f.end()), line(n);
  const std::size_t stride[3] = {1, n, n * n};
  for (std::size_t axis = 0; axis < 3; ++axis)
    for (std::size_t i = 0; i < a.size(); ++i) {
      if ((i / stride[axis]) % n != 0) continue;  // once per line
      for (std::size_t k = 0; k < n; ++k) {
        line[k] = 0;
        for (std::size_t x = 0; x < n; ++x)
          line[k] += a[i + x * stride[axis]] *
                     std::polar(1.0, -2.0 * std::numbers::pi * double(k * x % n) / double(n));
      }
      for (std::size_t k = 0; k < n; ++k) a[i + k * stride[axis]] = line[k];
    }
  std::vector<double> shells(n, 0.0);
  const auto wave = [n](std::size_t i) { return i <= n / 2 ? double(i) : double(i) - double(n); };
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double k =
        std::sqrt(std::pow(wave(i % n), 2) + std::pow(wave(i / n % n), 2) + std::pow(wave(i / n / n), 2));
    const auto shell = std::size_t(std::lround(k));
    if (shell < n) shells[shell] += std::norm(a[i]);
  }
  return shells;
}

TEST_F(VolumeTest, TurbulenceHasKolmogorovSpectrum) {
  const std::size_t n = 32;
  const CliResult r =
      run_cli({"generate-volume", "--kind", "turbulence", "--size", "32", (dir_ / "t.raw").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Volume v = cli::read_raw_volume(dir_ / "t.raw", {n, n, n}, VoxelType::f32);
  double mean = 0, sq = 0;
  for (double x : v.samples) mean += x / double(v.count()), sq += x * x / double(v.count());
  EXPECT_NEAR(mean, 0.0, 1e-5);  // no k = 0 mode
  EXPECT_NEAR(sq, 1.0, 1e-5);    // unit RMS
  const std::vector<double> e = shell_spectrum(v.samples, n);
  double sx = 0, sy = 0, sxx = 0, sxy = 0, m = 0;  // least-squares slope of log E over log k
  for (std::size_t k = 2; k <= 12; ++k, ++m) {
    const double lx = std::log(double(k)), ly = std::log(e[k]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  const double slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  EXPECT_NEAR(slope, -5.0 / 3.0, 0.2);
  EXPECT_LT(e[15] / e[14], 1.0);   // energy keeps falling up to the cut-off N/2
  EXPECT_LT(e[17], 1e-6 * e[16]);  // nothing beyond the cut-off
}

TEST_F(VolumeTest, GenerateVdbAndErrors) {
  const CliResult r = run_cli({"generate-volume", "--size", "8", "--steps", "10", (dir_ / "g.vdb").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const openvdb::GridPtrVec grids = read_grids(dir_ / "g.vdb");
  ASSERT_EQ(grids.size(), 1u);
  EXPECT_EQ(grids[0]->getName(), "v");
  EXPECT_EQ(grids[0]->activeVoxelCount(), 512u);
  EXPECT_NEAR(grids[0]->voxelSize()[0], 1.0 / 8.0, 1e-12);
  const CliResult odd =
      run_cli({"generate-volume", "--kind", "turbulence", "--size", "12", (dir_ / "t.raw").string()});
  EXPECT_EQ(odd.exit_code, 1);
  EXPECT_NE(odd.output.find("power-of-two"), std::string::npos) << odd.output;
  EXPECT_FALSE(fs::exists(dir_ / "t.raw"));
}

}  // namespace
}  // namespace pupwave::test
