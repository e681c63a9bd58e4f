#pragma once
// Triangle meshes for the sqrt(3) multiresolution: an indexed face list and the half-edge
// topology derived from it. Our own small structure rather than OpenMesh's TriMesh because the
// multiresolution needs strict validation (OpenMesh skips non-manifold faces with a warning),
// a deterministic vertex and face order (the hierarchy is recovered from it), and no
// dependency below tools/. OpenMesh serves only as an independent check in the tests.

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace pupwave::sqrt3 {

using Vec3 = Eigen::Vector3d;
using Face = std::array<std::uint32_t, 3>;

// A triangle mesh: vertex positions and counter-clockwise (consistently oriented) faces.
struct TriMesh {
  std::vector<Vec3> points;
  std::vector<Face> faces;
};

inline constexpr std::int64_t kNoHalfedge = -1;

// Half-edge view of a validated manifold triangle mesh. Half-edge h = 3 f + j runs from
// faces[f][j] to faces[f][(j + 1) % 3]; twin(h) is kNoHalfedge on a boundary.
class Topology {
 public:
  // Builds and validates: indices in range, no repeated vertex in a face, every directed edge
  // used once (orientable, at most two faces per edge), one fan per vertex (manifold), every
  // vertex used. Throws std::invalid_argument naming the offending vertex, edge or face.
  Topology(std::size_t vertex_count, const std::vector<Face>& faces);

  std::size_t vertex_count() const { return first_out_.size(); }
  std::size_t face_count() const { return faces_.size(); }
  const std::vector<Face>& faces() const { return faces_; }

  std::uint32_t from(std::size_t h) const { return faces_[h / 3][h % 3]; }
  std::uint32_t to(std::size_t h) const { return faces_[h / 3][(h + 1) % 3]; }
  std::size_t next(std::size_t h) const { return h - h % 3 + (h + 1) % 3; }
  std::size_t prev(std::size_t h) const { return h - h % 3 + (h + 2) % 3; }
  std::int64_t twin(std::size_t h) const { return twin_[h]; }
  bool is_boundary_halfedge(std::size_t h) const { return twin_[h] == kNoHalfedge; }
  bool is_boundary_vertex(std::size_t v) const { return boundary_[v] != 0; }

  // Out-going half-edges of v in fan order (h, then twin(prev(h)), ...); for a boundary
  // vertex the first is its boundary half-edge, so the fan is walked in one piece.
  std::vector<std::size_t> out_halfedges(std::size_t v) const;
  // Neighbours of v in fan order (for a boundary vertex both boundary neighbours included).
  std::vector<std::uint32_t> neighbours(std::size_t v) const;
  // Number of neighbours (Kobbelt's n for alpha_n).
  std::size_t valence(std::size_t v) const;

  // Boundary loops, each the list of its boundary half-edges in order (to(h) = from(next)).
  const std::vector<std::vector<std::size_t>>& boundary_loops() const { return loops_; }
  std::size_t boundary_edge_count() const;

 private:
  void link_twins();
  void check_fans();
  void collect_loops();

  std::vector<Face> faces_;
  std::vector<std::int64_t> twin_;
  std::vector<std::size_t> first_out_;  // boundary half-edge for boundary vertices
  std::vector<std::uint8_t> boundary_;
  std::vector<std::vector<std::size_t>> loops_;
};

// Largest absolute coordinate of a mesh (its size, for relative tolerances); 1 when empty.
double mesh_scale(const std::vector<Vec3>& points);

}  // namespace pupwave::sqrt3
