#include "transforms/sqrt3/mesh.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

namespace pupwave::sqrt3 {
namespace {

std::string edge_name(std::uint32_t u, std::uint32_t v) {
  return "(" + std::to_string(u) + ", " + std::to_string(v) + ")";
}

}  // namespace

Topology::Topology(std::size_t vertex_count, const std::vector<Face>& faces)
    : faces_(faces), first_out_(vertex_count, std::size_t(-1)), boundary_(vertex_count, 0) {
  if (vertex_count >= (std::size_t(1) << 32) || faces.size() >= (std::size_t(1) << 31) / 3) {
    throw std::invalid_argument("mesh too large (" + std::to_string(vertex_count) + " vertices, " +
                                std::to_string(faces.size()) + " faces)");
  }
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const Face& t = faces_[f];
    for (std::uint32_t v : t) {
      if (v >= vertex_count) {
        throw std::invalid_argument("face " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                                    ", but the mesh has " + std::to_string(vertex_count) + " vertices");
      }
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      throw std::invalid_argument("face " + std::to_string(f) + " repeats a vertex (degenerate triangle)");
    }
  }
  link_twins();
  check_fans();
  collect_loops();
}

// Pairs each directed edge with its reverse; a directed edge used twice means the edge has
// more than two faces or the faces are not consistently oriented.
void Topology::link_twins() {
  const std::size_t n = 3 * faces_.size();
  std::vector<std::tuple<std::uint32_t, std::uint32_t, std::size_t>> keys(n);
  for (std::size_t h = 0; h < n; ++h) keys[h] = {from(h), to(h), h};
  std::sort(keys.begin(), keys.end());
  for (std::size_t i = 1; i < n; ++i) {
    if (std::get<0>(keys[i]) == std::get<0>(keys[i - 1]) &&
        std::get<1>(keys[i]) == std::get<1>(keys[i - 1])) {
      throw std::invalid_argument("edge " + edge_name(std::get<0>(keys[i]), std::get<1>(keys[i])) +
                                  " is used twice in the same direction: it has more than two faces "
                                  "(non-manifold) or the faces are not consistently oriented");
    }
  }
  twin_.assign(n, kNoHalfedge);
  for (std::size_t h = 0; h < n; ++h) {
    const auto key = std::make_tuple(to(h), from(h), std::size_t(0));
    const auto it = std::lower_bound(keys.begin(), keys.end(), key);
    if (it != keys.end() && std::get<0>(*it) == to(h) && std::get<1>(*it) == from(h)) {
      twin_[h] = std::int64_t(std::get<2>(*it));
    }
  }
  for (std::size_t h = 0; h < n; ++h) {
    const std::uint32_t v = from(h);
    if (twin_[h] == kNoHalfedge) {
      if (boundary_[v]) {
        throw std::invalid_argument("vertex " + std::to_string(v) +
                                    " is non-manifold: two boundary fans meet there");
      }
      boundary_[v] = 1;
      first_out_[v] = h;
    } else if (first_out_[v] == std::size_t(-1)) {
      first_out_[v] = h;
    }
  }
}

// Every vertex must be used, and walking its fan from first_out_ must reach all its faces.
void Topology::check_fans() {
  std::vector<std::size_t> corners(vertex_count(), 0);
  for (const Face& t : faces_)
    for (std::uint32_t v : t) ++corners[v];
  for (std::size_t v = 0; v < vertex_count(); ++v) {
    if (corners[v] == 0) {
      throw std::invalid_argument("vertex " + std::to_string(v) + " is not used by any face");
    }
    if (out_halfedges(v).size() != corners[v]) {
      throw std::invalid_argument("vertex " + std::to_string(v) +
                                  " is non-manifold: its faces form more than one fan");
    }
  }
}

void Topology::collect_loops() {
  std::vector<std::uint8_t> seen(twin_.size(), 0);
  for (std::size_t h = 0; h < twin_.size(); ++h) {
    if (twin_[h] != kNoHalfedge || seen[h]) continue;
    std::vector<std::size_t> loop;
    for (std::size_t g = h; !seen[g]; g = first_out_[to(g)]) {
      seen[g] = 1;
      loop.push_back(g);
    }
    loops_.push_back(std::move(loop));
  }
}

std::vector<std::size_t> Topology::out_halfedges(std::size_t v) const {
  std::vector<std::size_t> out;
  const std::size_t start = first_out_[v];
  std::size_t h = start;
  // A fan of a valid vertex is at most all half-edges; the bound stops a corrupt walk.
  for (std::size_t guard = 0; guard <= twin_.size(); ++guard) {
    out.push_back(h);
    const std::int64_t t = twin_[prev(h)];
    if (t == kNoHalfedge || std::size_t(t) == start) break;
    h = std::size_t(t);
  }
  return out;
}

std::vector<std::uint32_t> Topology::neighbours(std::size_t v) const {
  const std::vector<std::size_t> out = out_halfedges(v);
  std::vector<std::uint32_t> n;
  n.reserve(out.size() + 1);
  for (std::size_t h : out) n.push_back(to(h));
  if (is_boundary_vertex(v)) n.push_back(from(prev(out.back())));
  return n;
}

std::size_t Topology::valence(std::size_t v) const {
  return out_halfedges(v).size() + (is_boundary_vertex(v) ? 1 : 0);
}

std::size_t Topology::boundary_edge_count() const {
  std::size_t n = 0;
  for (const auto& loop : loops_) n += loop.size();
  return n;
}

double mesh_scale(const std::vector<Vec3>& points) {
  double s = 0;
  for (const Vec3& p : points) s = std::max(s, p.cwiseAbs().maxCoeff());
  return s > 0 ? s : 1.0;
}

}  // namespace pupwave::sqrt3
