#include "transforms/sqrt3/hierarchy.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "transforms/sqrt3/reversal.h"

namespace pupwave::sqrt3 {
namespace {

[[noreturn]] void not_structured(const std::string& why) {
  throw std::invalid_argument("not sqrt(3)-structured: " + why);
}

Face rotated_to_min(Face f) {
  while (f[0] > f[1] || f[0] > f[2]) f = {f[1], f[2], f[0]};
  return f;
}

std::vector<Face> normalised(std::vector<Face> faces) {
  for (Face& f : faces) f = rotated_to_min(f);
  std::sort(faces.begin(), faces.end());
  return faces;
}

// The coarse face of interior introduced vertex v: its three old neighbours in fan order.
Face face_of_face_point(const Topology& t, std::size_t v, std::size_t nc) {
  std::vector<std::uint32_t> old;
  for (std::uint32_t w : t.neighbours(v))
    if (w < nc) old.push_back(w);
  if (old.size() != 3) {
    not_structured("introduced vertex " + std::to_string(v) + " has " + std::to_string(old.size()) +
                   " old neighbours (a face point has 3)");
  }
  return {old[0], old[1], old[2]};
}

struct Candidate {
  StepKind kind;
  std::size_t nc;
};

// A coarse face found from the introduced vertices that belong to it.
struct FoundFace {
  std::uint32_t first_new;  // smallest introduced vertex of the face (orders the coarse faces)
  Face face;
  std::uint32_t a, b;  // its introduced vertices: face point (b = kNone) or edge points a, b
};

// Trisected boundary: each fine boundary half-edge p -> q between two new vertices gives the
// coarse boundary face (u, w, X) of the boundary half-edges u -> p, q -> w and its apex X.
void find_boundary_faces(const Topology& t, std::size_t nc, std::vector<FoundFace>& found) {
  for (std::size_t h = 0; h < 3 * t.face_count(); ++h) {
    if (!t.is_boundary_halfedge(h)) continue;
    const std::uint32_t p = t.from(h), q = t.to(h);
    if (p < nc && q < nc) {
      not_structured("boundary edge (" + std::to_string(p) + ", " + std::to_string(q) +
                     ") joins two old vertices, but a trisecting step splits every boundary edge");
    }
    if (p < nc || q < nc) continue;
    const std::uint32_t u = t.from(t.prev(t.out_halfedges(p).back()));
    const std::uint32_t w = t.to(t.out_halfedges(q).front());
    if (u >= nc || w >= nc) {
      not_structured("boundary vertices " + std::to_string(p) + ", " + std::to_string(q) +
                     " are not two edge points between old vertices");
    }
    found.push_back({std::min(p, q), Face{u, w, t.to(t.next(h))}, p, q});
  }
}

RecoveredLevel try_recover(const TriMesh& fine, const Topology& t, Candidate c) {
  const std::size_t V = fine.points.size();
  std::vector<FoundFace> found;
  for (std::size_t v = c.nc; v < V; ++v) {
    if (!t.is_boundary_vertex(v)) {
      found.push_back({std::uint32_t(v), face_of_face_point(t, v, c.nc), std::uint32_t(v), kNone});
    } else if (c.kind == StepKind::plain) {
      not_structured("introduced vertex " + std::to_string(v) +
                     " lies on the boundary, which a plain step keeps");
    }
  }
  if (c.kind == StepKind::boundary_trisect) find_boundary_faces(t, c.nc, found);
  std::sort(found.begin(), found.end(),
            [](const FoundFace& x, const FoundFace& y) { return x.first_new < y.first_new; });
  RecoveredLevel out;
  out.kind = c.kind;
  out.coarse_vertices = c.nc;
  out.origin_face.assign(V - c.nc, kNone);
  out.origin_slot.assign(V - c.nc, 0);
  for (std::size_t f = 0; f < found.size(); ++f) {
    out.coarse_faces.push_back(found[f].face);
    for (std::uint32_t v : {found[f].a, found[f].b}) {
      if (v == kNone) continue;
      if (out.origin_face[v - c.nc] != kNone)
        not_structured("vertex " + std::to_string(v) + " belongs to two coarse faces");
      out.origin_face[v - c.nc] = std::uint32_t(f);
      out.origin_slot[v - c.nc] = found[f].b == kNone ? 0 : (v == found[f].a ? 1 : 2);
    }
  }
  for (std::uint32_t f : out.origin_face)
    if (f == kNone)
      not_structured("introduced vertices are neither face points nor pairs of boundary edge points");
  const Topology coarse(c.nc, out.coarse_faces);
  const Refinement r = refine(coarse, c.kind);
  out.canonical.assign(V, kNone);
  for (std::size_t v = 0; v < c.nc; ++v) out.canonical[v] = std::uint32_t(v);
  for (std::size_t v = c.nc; v < V; ++v) {
    const std::uint32_t f = out.origin_face[v - c.nc], slot = out.origin_slot[v - c.nc];
    if (slot == 0) {
      out.canonical[v] = r.face_point[f];
    } else {
      if (r.edge_point[3 * f] == kNone)
        not_structured("edge points of vertex " + std::to_string(v) + " lie on no boundary edge");
      out.canonical[v] = r.edge_point[3 * f] + slot - 1;
    }
  }
  std::vector<std::uint8_t> hit(V, 0);
  for (std::uint32_t k : out.canonical) {
    if (k >= V || hit[k])
      not_structured("introduced vertices do not match the refinement of the coarse mesh");
    hit[k] = 1;
  }
  std::vector<Face> mapped = fine.faces;
  for (Face& f : mapped)
    for (std::uint32_t& v : f) v = out.canonical[v];
  if (normalised(mapped) != normalised(r.faces)) {
    not_structured("the faces are not those of a sqrt(3) step of the coarse mesh its old vertices span");
  }
  return out;
}

// Where each vertex of a recovered level's fine mesh goes, given the canonical coarse faces
// C (the recovered faces relabelled by sigma, in the order reconstruction will produce them).
std::vector<std::uint32_t> canonical_fine_order(const RecoveredLevel& rec, std::size_t fine_vertices,
                                                const std::vector<std::uint32_t>& sigma,
                                                const std::vector<Face>& C, const Refinement& r) {
  std::vector<std::pair<Face, std::uint32_t>> index;
  for (std::size_t f = 0; f < C.size(); ++f) index.push_back({rotated_to_min(C[f]), std::uint32_t(f)});
  std::sort(index.begin(), index.end());
  std::vector<std::uint32_t> out(fine_vertices);
  for (std::size_t v = 0; v < rec.coarse_vertices; ++v) out[v] = sigma[v];
  for (std::size_t v = rec.coarse_vertices; v < fine_vertices; ++v) {
    const Face& k = rec.coarse_faces[rec.origin_face[v - rec.coarse_vertices]];
    const Face key = rotated_to_min({sigma[k[0]], sigma[k[1]], sigma[k[2]]});
    const auto it = std::lower_bound(index.begin(), index.end(), std::make_pair(key, std::uint32_t(0)));
    if (it == index.end() || it->first != key) throw std::logic_error("sqrt(3) hierarchy: coarse face lost");
    const std::uint32_t f = it->second;
    const std::uint8_t slot = rec.origin_slot[v - rec.coarse_vertices];
    if (slot == 0) {
      out[v] = r.face_point[f];
      continue;
    }
    std::size_t j = 0;
    while (C[f][j] != sigma[k[0]]) ++j;  // the boundary half-edge starts at k[0]
    out[v] = r.edge_point[3 * f + j] + slot - 1;
  }
  return out;
}

}  // namespace

RecoveredLevel recover_level(const TriMesh& fine) {
  const std::size_t V = fine.points.size(), F = fine.faces.size();
  const Topology t(V, fine.faces);
  if (F % 3 != 0) not_structured(std::to_string(F) + " faces is not a multiple of 3");
  const std::size_t B = t.boundary_edge_count();
  std::vector<Candidate> order;
  if (F / 3 < V) order.push_back({StepKind::plain, V - F / 3});
  if (B > 0 && B % 3 == 0 && F / 3 + B / 3 < V)
    order.push_back({StepKind::boundary_trisect, V - F / 3 - B / 3});
  if (order.empty()) not_structured("too few vertices for " + std::to_string(F) + " faces");
  // A plain step leaves every boundary vertex old; if one is not, try the trisect step first.
  bool new_on_boundary = false;
  for (std::size_t v = order[0].nc; v < V; ++v) new_on_boundary = new_on_boundary || t.is_boundary_vertex(v);
  if (new_on_boundary && order.size() == 2) std::swap(order[0], order[1]);
  std::string first_error;
  for (const Candidate& c : order) {
    try {
      return try_recover(fine, t, c);
    } catch (const std::invalid_argument& e) {
      if (first_error.empty()) first_error = e.what();
    }
  }
  throw std::invalid_argument(first_error);
}

TriMesh reconstruct_level(const TriMesh& coarse, const Sqrt3Level& level) {
  const Topology t(coarse.points.size(), coarse.faces);
  const Refinement r = refine(t, level.kind);
  if (level.details.size() != r.fine_vertices() - r.coarse_vertices) {
    throw std::invalid_argument("sqrt(3) level has " + std::to_string(level.details.size()) +
                                " details, its connectivity needs " +
                                std::to_string(r.fine_vertices() - r.coarse_vertices));
  }
  const LevelFilters f = prepare_filters(t, r);
  TriMesh fine;
  fine.points = synthesise(t, r, f, coarse.points, level.details);
  fine.faces = r.faces;
  return fine;
}

Multiresolution decompose(const TriMesh& fine, int levels) {
  if (levels < 0) throw std::invalid_argument("decompose: levels must be >= 0");
  // Pass 1, finest to coarsest: the connectivity of every level.
  std::vector<RecoveredLevel> rec;
  std::vector<std::size_t> sizes{fine.points.size()};
  TriMesh current = fine;
  for (int j = 0; j < levels; ++j) {
    try {
      rec.push_back(recover_level(current));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("reversal " + std::to_string(j + 1) + " of " + std::to_string(levels) +
                                  ": " + e.what());
    }
    current.points.assign(rec.back().coarse_vertices, Vec3::Zero());
    current.faces = rec.back().coarse_faces;
    sizes.push_back(current.points.size());
  }
  // Pass 2, coarsest to finest: relabel every level in the order reconstruction produces.
  Multiresolution mr;
  mr.coarsest.faces = current.faces;
  std::vector<std::uint32_t> sigma(current.points.size());
  for (std::size_t v = 0; v < sigma.size(); ++v) sigma[v] = std::uint32_t(v);
  std::vector<std::vector<Face>> coarse_faces(static_cast<std::size_t>(levels));
  std::vector<Face> C = current.faces;
  for (int j = levels - 1; j >= 0; --j) {
    const RecoveredLevel& l = rec[std::size_t(j)];
    const Refinement r = refine(Topology(l.coarse_vertices, C), l.kind);
    sigma = canonical_fine_order(l, sizes[std::size_t(j)], sigma, C, r);
    coarse_faces[std::size_t(j)] = std::move(C);
    C = r.faces;
  }
  mr.input_to_canonical = sigma;
  // Analysis, finest to coarsest.
  std::vector<Vec3> g(fine.points.size());
  for (std::size_t v = 0; v < g.size(); ++v) g[sigma[v]] = fine.points[v];
  mr.levels.resize(std::size_t(levels));
  for (int j = 0; j < levels; ++j) {
    const Topology t(sizes[std::size_t(j) + 1], coarse_faces[std::size_t(j)]);
    const Refinement r = refine(t, rec[std::size_t(j)].kind);
    Sqrt3Level& level = mr.levels[std::size_t(levels - 1 - j)];
    level.kind = r.kind;
    std::vector<Vec3> c;
    analyse(t, r, prepare_filters(t, r), g, c, level.details);
    g = std::move(c);
  }
  mr.coarsest.points = std::move(g);
  return mr;
}

TriMesh reconstruct(const Multiresolution& mr, int coarser) {
  const int total = int(mr.levels.size());
  if (coarser < 0 || coarser > total) {
    throw std::invalid_argument("level " + std::to_string(coarser) + " out of range 0.." +
                                std::to_string(total));
  }
  TriMesh m = mr.coarsest;
  for (int j = 0; j < total - coarser; ++j) m = reconstruct_level(m, mr.levels[std::size_t(j)]);
  return m;
}

}  // namespace pupwave::sqrt3
