#include "tools/mesh_render.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>

namespace pupwave::cli {
namespace {

using sqrt3::Vec3;

// 3 x 5 bitmaps of 'L' and the digits, rows top to bottom, bit 2 = left column.
constexpr std::array<std::array<int, 5>, 11> kGlyphs = {{
    {7, 5, 5, 5, 7},
    {2, 6, 2, 2, 7},
    {7, 1, 7, 4, 7},
    {7, 1, 7, 1, 7},
    {5, 5, 7, 1, 1},
    {7, 4, 7, 1, 7},
    {7, 4, 7, 5, 7},
    {7, 1, 1, 1, 1},
    {7, 5, 7, 5, 7},
    {7, 5, 7, 1, 7},
    {4, 4, 4, 4, 7},  // L
}};

struct View {
  Eigen::Matrix3d rotation;
  Vec3 centre;
  double scale;
};

View fit_view(const sqrt3::TriMesh& m, std::size_t tile) {
  View v;
  const double yaw = 0.6, pitch = -0.45;
  v.rotation = Eigen::AngleAxisd(pitch, Vec3::UnitX()).toRotationMatrix() *
               Eigen::AngleAxisd(yaw, Vec3::UnitY()).toRotationMatrix();
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max()), hi = -lo;
  for (const Vec3& p : m.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  v.centre = (lo + hi) / 2;
  double radius = 0;
  for (const Vec3& p : m.points) radius = std::max(radius, (p - v.centre).norm());
  v.scale = radius > 0 ? 0.45 * double(tile) / radius : 1.0;
  return v;
}

struct Canvas {
  Image& image;
  std::vector<double>& depth;
  std::size_t x0, tile;
  void put(std::size_t x, std::size_t y, double shade) {
    const std::array<double, 3> colour = {0.78, 0.82, 0.9};
    for (std::size_t c = 0; c < 3; ++c)
      image.at(c, x0 + x, y) = float(std::clamp(255.0 * shade * colour[c], 0.0, 255.0));
  }
};

// Rasterises one triangle (screen x, y, depth z) with a constant shade and dark edges.
void fill_triangle(Canvas& cv, const std::array<Vec3, 3>& s, double shade) {
  const double area =
      (s[1].x() - s[0].x()) * (s[2].y() - s[0].y()) - (s[2].x() - s[0].x()) * (s[1].y() - s[0].y());
  if (std::abs(area) < 1e-12) return;
  const int xmin = std::max(0, int(std::floor(std::min({s[0].x(), s[1].x(), s[2].x()}))));
  const int xmax = std::min(int(cv.tile) - 1, int(std::ceil(std::max({s[0].x(), s[1].x(), s[2].x()}))));
  const int ymin = std::max(0, int(std::floor(std::min({s[0].y(), s[1].y(), s[2].y()}))));
  const int ymax = std::min(int(cv.tile) - 1, int(std::ceil(std::max({s[0].y(), s[1].y(), s[2].y()}))));
  std::array<double, 3> edge_length;
  for (int i = 0; i < 3; ++i)
    edge_length[std::size_t(i)] =
        (s[std::size_t((i + 1) % 3)] - s[std::size_t((i + 2) % 3)]).head<2>().norm();
  for (int y = ymin; y <= ymax; ++y) {
    for (int x = xmin; x <= xmax; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      std::array<double, 3> w;
      for (int i = 0; i < 3; ++i) {
        const Vec3& a = s[std::size_t((i + 1) % 3)];
        const Vec3& b = s[std::size_t((i + 2) % 3)];
        w[std::size_t(i)] = ((b.x() - a.x()) * (py - a.y()) - (px - a.x()) * (b.y() - a.y())) / area;
      }
      if (w[0] < 0 || w[1] < 0 || w[2] < 0) continue;
      const double z = w[0] * s[0].z() + w[1] * s[1].z() + w[2] * s[2].z();
      double& d = cv.depth[std::size_t(y) * cv.tile + std::size_t(x)];
      if (z >= d) continue;
      d = z;
      double pixels_to_edge = std::numeric_limits<double>::max();
      for (int i = 0; i < 3; ++i)
        pixels_to_edge =
            std::min(pixels_to_edge, w[std::size_t(i)] * std::abs(area) / edge_length[std::size_t(i)]);
      cv.put(std::size_t(x), std::size_t(y), pixels_to_edge < 0.6 ? 0.45 * shade : shade);
    }
  }
}

void draw_label(Image& img, std::size_t x0, int label) {
  std::vector<int> glyphs{10};
  const std::string digits = std::to_string(label);
  for (char c : digits) glyphs.push_back(c - '0');
  const std::size_t px = 4;
  for (std::size_t g = 0; g < glyphs.size(); ++g) {
    for (std::size_t row = 0; row < 5; ++row) {
      for (std::size_t col = 0; col < 3; ++col) {
        if (!((kGlyphs[std::size_t(glyphs[g])][row] >> (2 - col)) & 1)) continue;
        for (std::size_t dy = 0; dy < px; ++dy)
          for (std::size_t dx = 0; dx < px; ++dx)
            for (std::size_t c = 0; c < 3; ++c)
              img.at(c, x0 + 8 + (g * 4 + col) * px + dx, 8 + row * px + dy) = 30.0f;
      }
    }
  }
}

void render_tile(Image& img, std::size_t index, const sqrt3::TriMesh& m, const View& v, std::size_t tile) {
  std::vector<double> depth(tile * tile, std::numeric_limits<double>::max());
  Canvas cv{img, depth, index * tile, tile};
  std::vector<Vec3> screen(m.points.size());
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const Vec3 p = v.rotation * (m.points[i] - v.centre) * v.scale;
    screen[i] = Vec3(double(tile) / 2 + p.x(), double(tile) / 2 - p.y(), -p.z());
  }
  for (const sqrt3::Face& f : m.faces) {
    const Vec3 n = (v.rotation * (m.points[f[1]] - m.points[f[0]]).cross(m.points[f[2]] - m.points[f[0]]));
    const double len = n.norm();
    const double shade = len > 0 ? 0.25 + 0.75 * std::abs(n.z()) / len : 0.25;
    fill_triangle(cv, {screen[f[0]], screen[f[1]], screen[f[2]]}, shade);
  }
}

}  // namespace

Image render_contact_sheet(const std::vector<sqrt3::TriMesh>& tiles, const std::vector<int>& labels,
                           std::size_t tile) {
  if (tiles.empty() || tiles.size() != labels.size()) throw std::invalid_argument("contact sheet: no tiles");
  Image img(tile * tiles.size(), tile, 3, SampleType::u8);
  std::fill(img.samples.begin(), img.samples.end(), 250.0f);
  const View v = fit_view(tiles[0], tile);
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    render_tile(img, i, tiles[i], v, tile);
    draw_label(img, i * tile, labels[i]);
  }
  return img;
}

}  // namespace pupwave::cli
