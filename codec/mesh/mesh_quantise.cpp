#include "codec/mesh/mesh_quantise.h"

#include <cmath>
#include <stdexcept>

#include "codec/mesh/mesh_entropy.h"

namespace pupwave::mesh {
namespace {

void quantise_points(const std::vector<sqrt3::Vec3>& points, double step, std::vector<std::int64_t>& out) {
  out.clear();
  out.reserve(3 * points.size());
  const double limit = double(kMaxQuantised / 4);  // room for the coarsest points' differences
  for (const sqrt3::Vec3& p : points) {
    for (int a = 0; a < 3; ++a) {
      const double q = std::nearbyint(p[a] / step);
      if (!(std::abs(q) <= limit))
        throw std::invalid_argument("mesh quantiser step too small for these coordinates");
      out.push_back(std::int64_t(q));
    }
  }
}

std::vector<sqrt3::Vec3> points_of(const std::vector<std::int64_t>& q, double step) {
  std::vector<sqrt3::Vec3> p(q.size() / 3);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p[i] = sqrt3::Vec3(double(q[3 * i]), double(q[3 * i + 1]), double(q[3 * i + 2])) * step;
  }
  return p;
}

}  // namespace

QuantisedLevels quantise(const sqrt3::Multiresolution& mr, const std::vector<double>& steps,
                         double coarse_step) {
  QuantisedLevels q;
  quantise_points(mr.coarsest.points, coarse_step, q.coarsest);
  q.levels.resize(mr.levels.size());
  for (std::size_t j = 0; j < mr.levels.size(); ++j)
    quantise_points(mr.levels[j].details, steps[j], q.levels[j]);
  return q;
}

sqrt3::Multiresolution dequantise(const QuantisedLevels& q, const std::vector<sqrt3::Face>& faces,
                                  const std::vector<sqrt3::StepKind>& kinds, const std::vector<double>& steps,
                                  double coarse_step) {
  sqrt3::Multiresolution mr;
  mr.coarsest.points = points_of(q.coarsest, coarse_step);
  mr.coarsest.faces = faces;
  mr.levels.resize(q.levels.size());
  for (std::size_t j = 0; j < q.levels.size(); ++j) {
    mr.levels[j].kind = kinds[j];
    mr.levels[j].details = points_of(q.levels[j], steps[j]);
  }
  return mr;
}

std::vector<std::int64_t> delta_encode(const std::vector<std::int64_t>& v) {
  std::vector<std::int64_t> d(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) d[i] = i < 3 ? v[i] : v[i] - v[i - 3];
  return d;
}

std::vector<std::int64_t> delta_decode(const std::vector<std::int64_t>& d) {
  std::vector<std::int64_t> v(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) v[i] = i < 3 ? d[i] : d[i] + v[i - 3];
  return v;
}

}  // namespace pupwave::mesh
