#include "transforms/sqrt3/subdivide.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "transforms/sqrt3/boundary_curve.h"

namespace pupwave::sqrt3 {

double alpha(std::size_t n) { return (4.0 - 2.0 * std::cos(2.0 * std::numbers::pi / double(n))) / 9.0; }

namespace {

// Boundary loop vertices (from(h) of each boundary half-edge) in loop order.
std::vector<std::uint32_t> loop_vertices(const Topology& t, const std::vector<std::size_t>& loop) {
  std::vector<std::uint32_t> v;
  v.reserve(loop.size());
  for (std::size_t h : loop) v.push_back(t.from(h));
  return v;
}

void relax_interior_vertices(const Topology& t, std::span<const Vec3> c, std::vector<Vec3>& fine) {
  for (std::size_t v = 0; v < t.vertex_count(); ++v) {
    if (t.is_boundary_vertex(v)) {
      fine[v] = c[v];  // plain step; a trisect step overwrites it with the curve rule
      continue;
    }
    const std::vector<std::uint32_t> ring = t.neighbours(v);
    Vec3 sum = Vec3::Zero();
    for (std::uint32_t w : ring) sum += c[w];
    const double a = alpha(ring.size());
    fine[v] = (1.0 - a) * c[v] + (a / double(ring.size())) * sum;
  }
}

// Trisected boundary: each loop refined by the ternary cubic B-spline rule.
void refine_boundary(const Topology& t, const Refinement& r, std::span<const Vec3> c,
                     std::vector<Vec3>& fine) {
  for (const auto& loop : t.boundary_loops()) {
    const std::vector<std::uint32_t> ids = loop_vertices(t, loop);
    std::vector<Vec3> coarse(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) coarse[i] = c[ids[i]];
    const std::vector<Vec3> f = curve_subdivide(coarse);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      fine[ids[i]] = f[3 * i];
      fine[r.edge_point[loop[i]]] = f[3 * i + 1];
      fine[r.edge_point[loop[i]] + 1] = f[3 * i + 2];
    }
  }
}

}  // namespace

std::vector<Vec3> subdivide_points(const Topology& t, const Refinement& r, std::span<const Vec3> c) {
  if (c.size() != t.vertex_count()) throw std::invalid_argument("subdivide_points: point count mismatch");
  std::vector<Vec3> fine(r.fine_vertices(), Vec3::Zero());
  relax_interior_vertices(t, c, fine);
  for (std::size_t f = 0; f < t.face_count(); ++f) {
    if (r.face_point[f] == kNone) continue;
    const Face& tri = t.faces()[f];
    fine[r.face_point[f]] = (c[tri[0]] + c[tri[1]] + c[tri[2]]) / 3.0;
  }
  if (r.kind == StepKind::boundary_trisect) refine_boundary(t, r, c, fine);
  return fine;
}

TriMesh subdivide(const TriMesh& mesh, int levels, int first_step) {
  if (levels < 0) throw std::invalid_argument("subdivide: levels must be >= 0");
  TriMesh m = mesh;
  for (int i = 0; i < levels; ++i) {
    const Topology t(m.points.size(), m.faces);
    const Refinement r = refine(t, kobbelt_step_kind(first_step + i));
    TriMesh fine;
    fine.points = subdivide_points(t, r, m.points);
    fine.faces = r.faces;
    try {
      const Topology check(fine.points.size(), fine.faces);
    } catch (const std::invalid_argument& e) {
      // Only tiny degenerate inputs (two faces glued along all edges) get here.
      throw std::invalid_argument("sqrt(3) step " + std::to_string(i + 1) +
                                  " gives a non-manifold mesh: " + e.what());
    }
    m = std::move(fine);
  }
  return m;
}

}  // namespace pupwave::sqrt3
