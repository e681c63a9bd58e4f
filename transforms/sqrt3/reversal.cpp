#include "transforms/sqrt3/reversal.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "transforms/sqrt3/local_lsq.h"
#include "transforms/sqrt3/subdivide.h"

namespace pupwave::sqrt3 {

double reversal_a(std::size_t n) { return -2.0 / (3.0 * alpha(n) - 2.0); }
double reversal_h(std::size_t n) { return 3.0 / double(n) * alpha(n) / (3.0 * alpha(n) - 2.0); }

namespace {

bool has_boundary_neighbour(const Topology& t, std::size_t v) {
  for (std::uint32_t w : t.neighbours(v))
    if (t.is_boundary_vertex(w)) return true;
  return false;
}

ReversalRow closed_form_row(const Topology& t, const Refinement& r, std::size_t v) {
  ReversalRow row;
  const std::size_t n = t.valence(v);
  row.home = reversal_a(n);
  for (std::size_t h : t.out_halfedges(v)) {
    row.face_points.push_back(r.face_point[h / 3]);
    row.weights.push_back(reversal_h(n));
  }
  return row;
}

bool face_has_vertex(const Face& f, std::uint32_t v) { return f[0] == v || f[1] == v || f[2] == v; }

}  // namespace

ReversalRow local_reversal_row(const Topology& t, const Refinement& r, std::size_t v) {
  const std::size_t n = t.valence(v);
  const double a = alpha(n);
  std::vector<std::size_t> faces;  // coarse faces around v that have a face point
  for (std::size_t h : t.out_halfedges(v))
    if (r.face_point[h / 3] != kNone) faces.push_back(h / 3);
  std::vector<std::uint32_t> columns;  // interior coarse vertices whose P column meets the row
  for (std::uint32_t w : t.neighbours(v))
    if (!t.is_boundary_vertex(w)) columns.push_back(w);
  // Row system x M = u: unknown i = (home, face points...), equation j = (v, columns...).
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(Eigen::Index(1 + faces.size()), Eigen::Index(1 + columns.size()));
  M(0, 0) = 1.0 - a;
  for (std::size_t j = 0; j < columns.size(); ++j) M(0, Eigen::Index(1 + j)) = a / double(n);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    M(Eigen::Index(1 + i), 0) = 1.0 / 3.0;
    for (std::size_t j = 0; j < columns.size(); ++j)
      if (face_has_vertex(t.faces()[faces[i]], columns[j]))
        M(Eigen::Index(1 + i), Eigen::Index(1 + j)) = 1.0 / 3.0;
  }
  Eigen::RowVectorXd u = Eigen::RowVectorXd::Zero(M.cols());
  u(0) = 1.0;
  double residual = 0;
  const Eigen::RowVectorXd x = min_norm_row(M, u, &residual);
  if (residual > 1e-11 || std::abs(x(0)) < 1e-12) {
    throw std::logic_error("sqrt(3) reversal: no local A row for vertex " + std::to_string(v));
  }
  ReversalRow row;
  row.home = x(0);
  row.closed_form = columns.size() == n;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    row.face_points.push_back(r.face_point[faces[i]]);
    row.weights.push_back(x(Eigen::Index(1 + i)));
  }
  return row;
}

LevelFilters prepare_filters(const Topology& t, const Refinement& r) {
  LevelFilters f;
  f.rows.resize(t.vertex_count());
  for (std::size_t v = 0; v < t.vertex_count(); ++v) {
    if (t.is_boundary_vertex(v)) continue;
    f.rows[v] = has_boundary_neighbour(t, v) ? local_reversal_row(t, r, v) : closed_form_row(t, r, v);
  }
  for (const auto& loop : t.boundary_loops()) {
    std::vector<std::uint32_t> coarse, fine;
    for (std::size_t h : loop) {
      coarse.push_back(t.from(h));
      if (r.kind == StepKind::boundary_trisect) {
        fine.insert(fine.end(), {t.from(h), r.edge_point[h], r.edge_point[h] + 1});
      }
    }
    if (r.kind == StepKind::boundary_trisect) f.curves.emplace_back(coarse.size());
    f.loop_coarse.push_back(std::move(coarse));
    f.loop_fine.push_back(std::move(fine));
  }
  return f;
}

namespace {

// Boundary coarse points from the boundary alone: kept (plain step) or the curve reversal.
void analyse_boundary(const Refinement& r, const LevelFilters& f, std::span<const Vec3> g,
                      std::vector<Vec3>& c, std::vector<Vec3>& d) {
  for (std::size_t l = 0; l < f.loop_coarse.size(); ++l) {
    const std::vector<std::uint32_t>& ids = f.loop_coarse[l];
    if (r.kind == StepKind::plain) {
      for (std::uint32_t v : ids) c[v] = g[v];
      continue;
    }
    const std::vector<std::uint32_t>& fine = f.loop_fine[l];
    std::vector<Vec3> gl(fine.size()), cl(ids.size()), dl(2 * ids.size());
    for (std::size_t i = 0; i < fine.size(); ++i) gl[i] = g[fine[i]];
    f.curves[l].analyse(gl, cl, dl);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      c[ids[i]] = cl[i];
      d[fine[3 * i + 1] - r.coarse_vertices] = dl[2 * i];
      d[fine[3 * i + 2] - r.coarse_vertices] = dl[2 * i + 1];
    }
  }
}

}  // namespace

void analyse(const Topology& t, const Refinement& r, const LevelFilters& f, std::span<const Vec3> g,
             std::vector<Vec3>& c, std::vector<Vec3>& d) {
  if (g.size() != r.fine_vertices()) throw std::invalid_argument("sqrt(3) analyse: point count mismatch");
  c.assign(t.vertex_count(), Vec3::Zero());
  d.assign(r.fine_vertices() - r.coarse_vertices, Vec3::Zero());
  analyse_boundary(r, f, g, c, d);
  // The part of P c that the (already known) boundary coarse points contribute.
  const std::vector<Vec3> known = subdivide_points(t, r, c);
  for (std::size_t v = 0; v < t.vertex_count(); ++v) {
    if (t.is_boundary_vertex(v)) continue;
    const ReversalRow& row = f.rows[v];
    Vec3 x = row.home * (g[v] - known[v]);
    for (std::size_t i = 0; i < row.face_points.size(); ++i) {
      x += row.weights[i] * (g[row.face_points[i]] - known[row.face_points[i]]);
    }
    c[v] = x;
  }
  for (std::size_t fc = 0; fc < t.face_count(); ++fc) {
    const std::uint32_t p = r.face_point[fc];
    if (p == kNone) continue;
    const Face& tri = t.faces()[fc];
    d[p - r.coarse_vertices] = g[p] - (c[tri[0]] + c[tri[1]] + c[tri[2]]) / 3.0;  // Fig. 16
  }
}

std::vector<Vec3> synthesise(const Topology& t, const Refinement& r, const LevelFilters& f,
                             std::span<const Vec3> c, std::span<const Vec3> d) {
  if (c.size() != t.vertex_count() || d.size() != r.fine_vertices() - r.coarse_vertices) {
    throw std::invalid_argument("sqrt(3) synthesise: size mismatch");
  }
  std::vector<Vec3> g = subdivide_points(t, r, c);
  const std::size_t base = r.coarse_vertices;
  for (std::uint32_t p : r.face_point)
    if (p != kNone) g[p] += d[p - base];  // Eq. 6.4
  for (std::size_t l = 0; l < f.curves.size(); ++l) {
    const std::vector<std::uint32_t>& ids = f.loop_coarse[l];
    const std::vector<std::uint32_t>& fine = f.loop_fine[l];
    std::vector<Vec3> cl(ids.size()), dl(2 * ids.size()), gl(fine.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
      cl[i] = c[ids[i]];
      dl[2 * i] = d[fine[3 * i + 1] - base];
      dl[2 * i + 1] = d[fine[3 * i + 2] - base];
    }
    f.curves[l].synthesise(cl, dl, gl);
    for (std::size_t i = 0; i < fine.size(); ++i) g[fine[i]] = gl[i];
  }
  for (std::size_t v = 0; v < t.vertex_count(); ++v) {
    if (t.is_boundary_vertex(v)) continue;
    const ReversalRow& row = f.rows[v];
    Vec3 e = Vec3::Zero();
    for (std::size_t i = 0; i < row.face_points.size(); ++i)
      e += row.weights[i] * d[row.face_points[i] - base];
    g[v] -= e / row.home;  // Eq. 6.5: A (g - P c) = 0 on row v
  }
  return g;
}

}  // namespace pupwave::sqrt3
