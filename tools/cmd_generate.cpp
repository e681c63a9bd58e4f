// `pupwave generate-volume`: deterministic, physically motivated 3-D float fields for tests and
// benchmarks, so that the repository carries the program rather than only its output.
//
//   gray-scott  Gray-Scott reaction-diffusion (u + 2v -> 3v, v -> P) on a periodic grid, explicit
//               Euler with the 7-point Laplacian; the output is the v concentration.
//   turbulence  a synthetic incompressible velocity field with Kolmogorov's energy spectrum
//               E(k) ~ k^(-5/3) between k = 1 and N/2, random phases, projected onto divergence-
//               free fields, inverse FFT; the output is the x velocity component.
// Every random number comes from std::mt19937's raw output (fixed by the C++ standard) mapped by
// hand, so the fields are the same on every platform and compiler.
#include <cmath>
#include <complex>
#include <iostream>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "tools/atomic_file.h"
#include "tools/cli_stdio.h"
#include "tools/commands.h"
#include "tools/volume_io.h"

namespace pupwave::cli {
namespace {

// Uniform in [0, 1) from the top 24 bits of one mt19937 draw.
double uniform(std::mt19937& rng) { return double(rng() >> 8) * (1.0 / 16777216.0); }

// Diffusion rates in voxels^2 per unit time (Pearson's 2:1 ratio); dt keeps explicit Euler
// stable for the 7-point Laplacian (dt * 6 * du < 1).
struct GrayScottParams {
  double du = 0.2, dv = 0.1, feed = 0.030, kill = 0.055, dt = 0.5;
};

// One explicit Euler step of Gray-Scott on the periodic n^3 grid.
void gray_scott_step(std::vector<double>& u, std::vector<double>& v, std::vector<double>& u2,
                     std::vector<double>& v2, std::size_t n, const GrayScottParams& p) {
  const auto at = [n](std::size_t x, std::size_t y, std::size_t z) { return x + n * (y + n * z); };
  for (std::size_t z = 0; z < n; ++z)
    for (std::size_t y = 0; y < n; ++y)
      for (std::size_t x = 0; x < n; ++x) {
        const std::size_t i = at(x, y, z);
        const std::size_t xm = at((x + n - 1) % n, y, z), xp = at((x + 1) % n, y, z);
        const std::size_t ym = at(x, (y + n - 1) % n, z), yp = at(x, (y + 1) % n, z);
        const std::size_t zm = at(x, y, (z + n - 1) % n), zp = at(x, y, (z + 1) % n);
        const double lap_u = u[xm] + u[xp] + u[ym] + u[yp] + u[zm] + u[zp] - 6.0 * u[i];
        const double lap_v = v[xm] + v[xp] + v[ym] + v[yp] + v[zm] + v[zp] - 6.0 * v[i];
        const double uvv = u[i] * v[i] * v[i];
        u2[i] = u[i] + p.dt * (p.du * lap_u - uvv + p.feed * (1.0 - u[i]));
        v2[i] = v[i] + p.dt * (p.dv * lap_v + uvv - (p.feed + p.kill) * v[i]);
      }
  u.swap(u2);
  v.swap(v2);
}

// Gray-Scott from u = 1, v = 0 with v seeded in random small cubes; returns v after `steps`.
Volume gray_scott(std::size_t n, int steps, unsigned seed, const GrayScottParams& params) {
  std::vector<double> u(n * n * n, 1.0), v(n * n * n, 0.0), u2(u.size()), v2(v.size());
  std::mt19937 rng(seed);
  const std::size_t side = std::max<std::size_t>(4, n / 8);  // smaller seeds die out
  const int seeds = 12;
  for (int s = 0; s < seeds; ++s) {
    std::size_t c[3];
    for (auto& ci : c) ci = std::size_t(uniform(rng) * double(n));
    for (std::size_t dz = 0; dz < side; ++dz)
      for (std::size_t dy = 0; dy < side; ++dy)
        for (std::size_t dx = 0; dx < side; ++dx) {
          const std::size_t i = (c[0] + dx) % n + n * ((c[1] + dy) % n + n * ((c[2] + dz) % n));
          u[i] = 0.5;
          v[i] = 0.25;
        }
  }
  for (int t = 0; t < steps; ++t) gray_scott_step(u, v, u2, v2, n, params);
  Volume out({n, n, n}, VoxelType::f32);
  for (std::size_t i = 0; i < v.size(); ++i) out.samples[i] = double(float(v[i]));
  return out;
}

using Complex = std::complex<double>;

// In-place radix-2 FFT of a line of power-of-two length (sign -1 forward, +1 inverse, unscaled).
void fft_line(std::vector<Complex>& a, int sign) {
  const std::size_t n = a.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {  // bit-reversal permutation
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j |= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double angle = sign * 2.0 * std::numbers::pi / double(len);
    const Complex w_len(std::cos(angle), std::sin(angle));
    for (std::size_t i = 0; i < n; i += len) {
      Complex w(1.0);
      for (std::size_t k = 0; k < len / 2; ++k, w *= w_len) {
        const Complex even = a[i + k], odd = a[i + k + len / 2] * w;
        a[i + k] = even + odd;
        a[i + k + len / 2] = even - odd;
      }
    }
  }
}

// 3-D inverse FFT of an n^3 array, one axis at a time through a line buffer.
void inverse_fft_3d(std::vector<Complex>& f, std::size_t n) {
  std::vector<Complex> line(n);
  const std::size_t stride[3] = {1, n, n * n};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const std::size_t s = stride[axis], o1 = stride[(axis + 1) % 3], o2 = stride[(axis + 2) % 3];
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = 0; b < n; ++b) {
        const std::size_t base = a * o1 + b * o2;
        for (std::size_t k = 0; k < n; ++k) line[k] = f[base + k * s];
        fft_line(line, +1);
        for (std::size_t k = 0; k < n; ++k) f[base + k * s] = line[k];
      }
  }
}

// Signed wavenumber of FFT index i on a line of n samples.
double wavenumber(std::size_t i, std::size_t n) { return i <= n / 2 ? double(i) : double(i) - double(n); }

// x velocity of a random divergence-free field with E(k) ~ k^(-5/3), scaled to unit RMS.
Volume turbulence(std::size_t n, unsigned seed) {
  if (n < 4 || (n & (n - 1)) != 0)
    throw std::invalid_argument("--kind turbulence needs a power-of-two --size >= 4");
  std::vector<Complex> ux(n * n * n);
  std::mt19937 rng(seed);
  const auto gaussian = [&rng] {  // Box-Muller on our own uniforms
    const double r = std::sqrt(-2.0 * std::log(1.0 - uniform(rng)));
    const double phi = 2.0 * std::numbers::pi * uniform(rng);
    return Complex(r * std::cos(phi), r * std::sin(phi));
  };
  for (std::size_t i = 0; i < ux.size(); ++i) {
    const double k[3] = {wavenumber(i % n, n), wavenumber(i / n % n, n), wavenumber(i / (n * n), n)};
    Complex a[3] = {gaussian(), gaussian(), gaussian()};
    const double k2 = k[0] * k[0] + k[1] * k[1] + k[2] * k[2], kk = std::sqrt(k2);
    if (kk < 1.0 || kk > double(n / 2)) continue;
    // Shell energy E(k) = 4 pi k^2 |a(k)|^2 ~ k^(-5/3) gives |a(k)| ~ k^(-11/6).
    const double amplitude = std::pow(kk, -11.0 / 6.0);
    const Complex k_dot_a = k[0] * a[0] + k[1] * a[1] + k[2] * a[2];
    ux[i] = amplitude * (a[0] - k[0] * k_dot_a / k2);  // Leray projection: no divergence
  }
  inverse_fft_3d(ux, n);
  double sum2 = 0.0;
  for (const Complex& c : ux) sum2 += c.real() * c.real();
  const double rms = std::sqrt(sum2 / double(ux.size()));
  Volume out({n, n, n}, VoxelType::f32);
  for (std::size_t i = 0; i < ux.size(); ++i) out.samples[i] = double(float(ux[i].real() / rms));
  return out;
}

// Wraps a dense field as a VDB grid: every voxel active, unit cube in world space.
VolumeGrid as_grid(Volume volume, const std::string& name) {
  VolumeGrid g;
  g.name = name;
  const double voxel = 1.0 / double(volume.dims[0]);
  for (int a = 0; a < 3; ++a) g.index_to_world[std::size_t(5 * a)] = voxel;
  g.metadata["creator"] = MetaValue{MetaValue::Kind::string, "pupwave generate-volume", 0, {}};
  g.volume = std::move(volume);
  return g;
}

}  // namespace

void add_generate_volume_command(CLI::App& app) {
  struct Options {
    std::string kind = "gray-scott", output;
    std::size_t size = 64;
    int steps = 3000;
    unsigned seed = 1;
    GrayScottParams gs;
    Verbosity verbosity;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("generate-volume",
                                 "Generate a deterministic 3-D float test field (size^3, x fastest) as\n"
                                 "raw float32 little endian (OUT.raw) or an OpenVDB FloatGrid (OUT.vdb).");
  cmd->add_option("--kind", opt->kind,
                  "gray-scott (reaction-diffusion, v field) or turbulence (-5/3 spectrum)")
      ->check(CLI::IsMember({"gray-scott", "turbulence"}));
  cmd->add_option("--size", opt->size, "voxels per axis (turbulence: a power of two)")
      ->check(CLI::Range(std::size_t(4), std::size_t(1024)));
  cmd->add_option("--steps", opt->steps, "gray-scott time steps")->check(CLI::Range(0, 1000000));
  cmd->add_option("--seed", opt->seed, "random seed");
  cmd->add_option("--feed", opt->gs.feed, "gray-scott feed rate F")->check(CLI::Range(0.0, 0.2));
  cmd->add_option("--kill", opt->gs.kill, "gray-scott kill rate k")->check(CLI::Range(0.0, 0.2));
  cmd->add_option("OUT", opt->output, "output file, .raw or .vdb, or - for raw on stdout")->required();
  add_verbosity_flags(*cmd, opt->verbosity);
  cmd->callback([opt] {
    check_output_path(opt->output);
    opt->verbosity.to_stderr = is_stdio(opt->output);
    Volume v = opt->kind == "turbulence" ? turbulence(opt->size, opt->seed)
                                         : gray_scott(opt->size, opt->steps, opt->seed, opt->gs);
    if (is_vdb_path(opt->output))
      write_vdb({as_grid(std::move(v), opt->kind == "turbulence" ? "velocity_x" : "v")}, opt->output);
    else
      write_raw_volume(v, opt->output);
    opt->verbosity.out() << opt->output << ": " << opt->kind << ' ' << opt->size << '^' << 3 << " float32\n";
  });
}

}  // namespace pupwave::cli
