#include "transforms/sqrt3/refine.h"

#include <stdexcept>
#include <string>

namespace pupwave::sqrt3 {
namespace {

// Counts the boundary half-edges of face f.
int boundary_edges_of_face(const Topology& t, std::size_t f) {
  int n = 0;
  for (std::size_t j = 0; j < 3; ++j) n += t.is_boundary_halfedge(3 * f + j) ? 1 : 0;
  return n;
}

// Numbers the new vertices in canonical order (see refine.h).
void number_new_vertices(const Topology& t, Refinement& r) {
  const std::size_t faces = t.face_count();
  r.face_point.assign(faces, kNone);
  r.edge_point.assign(3 * faces, kNone);
  std::uint32_t next = std::uint32_t(t.vertex_count());
  for (std::size_t f = 0; f < faces; ++f) {
    const int b = boundary_edges_of_face(t, f);
    if (r.kind == StepKind::plain || b == 0) {
      r.face_point[f] = next++;
      ++r.face_points;
      continue;
    }
    if (b > 1) {
      throw std::invalid_argument("face " + std::to_string(f) + " has " + std::to_string(b) +
                                  " boundary edges; a boundary-trisecting sqrt(3) step needs at most one "
                                  "(it follows a plain step)");
    }
    for (std::size_t j = 0; j < 3; ++j) {
      if (t.is_boundary_halfedge(3 * f + j)) r.edge_point[3 * f + j] = next;
    }
    next += 2;
    r.edge_points += 2;
  }
}

// Third vertex of the pre-flip triangle on half-edge h's side (h an old interior edge): the
// face point, or in a trisected boundary face the edge point next to the half-edge's vertex
// on the boundary edge.
std::uint32_t pre_flip_apex(const Topology& t, const Refinement& r, std::size_t h) {
  const std::size_t f = h / 3;
  if (r.face_point[f] != kNone) return r.face_point[f];
  // Boundary face (a, b, X) with a -> b on the boundary: b -> X sees pr, X -> a sees pl.
  for (std::size_t j = 0; j < 3; ++j) {
    const std::size_t b = 3 * f + j;
    if (!t.is_boundary_halfedge(b)) continue;
    if (h == t.next(b)) return r.edge_point[b] + 1;
    return r.edge_point[b];
  }
  throw std::logic_error("pre_flip_apex: face without face point or boundary edge");
}

}  // namespace

const char* to_string(StepKind kind) { return kind == StepKind::plain ? "plain" : "boundary-trisect"; }

Refinement refine(const Topology& t, StepKind kind) {
  Refinement r;
  r.kind = kind;
  r.coarse_vertices = t.vertex_count();
  number_new_vertices(t, r);
  r.faces.reserve(3 * t.face_count());
  for (std::size_t i = 0; i < 3 * t.face_count(); ++i) {
    // Half-edges from each face's smallest vertex on, so the fine face order does not depend
    // on how the coarse faces are rotated (the hierarchy recovers them in another rotation).
    const Face& tri = t.faces()[i / 3];
    const std::size_t first = tri[0] < tri[1] ? (tri[0] < tri[2] ? 0 : 2) : (tri[1] < tri[2] ? 1 : 2);
    const std::size_t h = i - i % 3 + (first + i % 3) % 3;
    const std::uint32_t u = t.from(h);
    const std::uint32_t v = t.to(h);
    const std::size_t f = h / 3;
    if (!t.is_boundary_halfedge(h)) {
      // The flip of edge (u, v) leaves (u, apex(twin), apex(h)) on u's side.
      r.faces.push_back({u, pre_flip_apex(t, r, std::size_t(t.twin(h))), pre_flip_apex(t, r, h)});
    } else if (kind == StepKind::plain) {
      r.faces.push_back({u, v, r.face_point[f]});  // boundary edges are not flipped
    } else {
      const std::uint32_t apex = t.to(t.next(h));
      r.faces.push_back({r.edge_point[h], r.edge_point[h] + 1, apex});
    }
  }
  return r;
}

}  // namespace pupwave::sqrt3
