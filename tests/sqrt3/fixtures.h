#pragma once
// Small synthetic meshes for the sqrt(3) math tests (real meshes come from testimages/).

#include <cmath>
#include <numbers>
#include <random>

#include "transforms/sqrt3/mesh.h"

namespace pupwave::sqrt3::test {

// Double cone over an n-gon: two apexes of valence n, ring vertices of valence 4.
inline TriMesh bipyramid(std::uint32_t n) {
  TriMesh m;
  for (std::uint32_t i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    m.points.push_back({std::cos(a), std::sin(a), 0.1 * std::sin(3 * a)});
  }
  m.points.push_back({0, 0, 1.2});
  m.points.push_back({0.1, -0.05, -0.9});
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    m.faces.push_back({i, j, n});
    m.faces.push_back({j, i, n + 1});
  }
  return m;
}

// Torus sampled from its parametric equation (seed Section 9): radii R > r, nu x nv grid.
inline Vec3 torus_point(double R, double r, double u, double v) {
  return {(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)};
}
inline TriMesh torus(double R, double r, std::uint32_t nu, std::uint32_t nv) {
  TriMesh m;
  for (std::uint32_t i = 0; i < nu; ++i)
    for (std::uint32_t j = 0; j < nv; ++j)
      m.points.push_back(torus_point(R, r, 2 * std::numbers::pi * i / nu, 2 * std::numbers::pi * j / nv));
  auto id = [&](std::uint32_t i, std::uint32_t j) { return (i % nu) * nv + (j % nv); };
  for (std::uint32_t i = 0; i < nu; ++i) {
    for (std::uint32_t j = 0; j < nv; ++j) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

// Open fan of n triangles around a centre vertex (a disk with one boundary loop of n edges).
inline TriMesh disk(std::uint32_t n) {
  TriMesh m;
  m.points.push_back({0, 0, 0.3});
  for (std::uint32_t i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    m.points.push_back({std::cos(a), std::sin(a), 0.2 * std::cos(2 * a)});
  }
  for (std::uint32_t i = 0; i < n; ++i) m.faces.push_back({0, 1 + i, 1 + (i + 1) % n});
  return m;
}

// Open triangulated grid patch of nx x ny quads (boundary vertices of valence 2 to 4).
inline TriMesh grid(std::uint32_t nx, std::uint32_t ny) {
  TriMesh m;
  for (std::uint32_t j = 0; j <= ny; ++j)
    for (std::uint32_t i = 0; i <= nx; ++i)
      m.points.push_back({double(i), double(j), 0.3 * std::sin(0.7 * i) * std::cos(0.5 * j)});
  auto id = [&](std::uint32_t i, std::uint32_t j) { return j * (nx + 1) + i; };
  for (std::uint32_t j = 0; j < ny; ++j) {
    for (std::uint32_t i = 0; i < nx; ++i) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

// Every point moved by a uniform random offset in [-amount, amount]^3 (Fig. 22).
inline void perturb(std::vector<Vec3>& points, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  for (Vec3& p : points) p += Vec3(u(rng), u(rng), u(rng));
}

inline double max_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).norm());
  return d;
}

}  // namespace pupwave::sqrt3::test
