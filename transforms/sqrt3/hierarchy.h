#pragma once
// The sqrt(3) multiresolution of a mesh: recovering the hierarchy of a fine mesh from its
// vertex order and connectivity, decomposing it level by level into a coarsest mesh plus
// details, and reconstructing any level exactly.
//
// A fine mesh is sqrt(3)-structured for one level when its first n_c vertices are the coarse
// (old) vertices and the rest are the introduced points of one step of refine.h, in any order;
// n_c follows from the counts (docs/sqrt3.md). Reconstruction returns the canonical order of
// refine.h, which is the input's order for meshes written by `pupwave mesh subdivide`.

#include <string>
#include <vector>

#include "transforms/sqrt3/mesh.h"
#include "transforms/sqrt3/refine.h"

namespace pupwave::sqrt3 {

// One level of a fine mesh, recovered: the step kind, the coarse connectivity over its first
// coarse_vertices vertices, and the coarse face each introduced vertex belongs to.
struct RecoveredLevel {
  StepKind kind = StepKind::plain;
  std::size_t coarse_vertices = 0;
  std::vector<Face> coarse_faces;          // ordered by their first introduced vertex
  std::vector<std::uint32_t> origin_face;  // per introduced vertex (index - coarse_vertices)
  std::vector<std::uint8_t> origin_slot;   // 0 face point, 1 / 2 first / second edge point
  std::vector<std::uint32_t> canonical;    // input vertex -> canonical fine index of refine()
};

// Recovers one level, or throws std::invalid_argument saying why the mesh is not the result
// of a sqrt(3) step with old vertices first.
RecoveredLevel recover_level(const TriMesh& fine);

struct Sqrt3Level {
  StepKind kind = StepKind::plain;
  std::vector<Vec3> details;  // one per introduced point, canonical order
};

// coarsest mesh + details; levels[0] refines the coarsest mesh, levels.back() gives the input.
// input_to_canonical[v] is where input vertex v is in reconstruct(mr) (identity for a mesh in
// canonical order, e.g. from `pupwave mesh subdivide`).
struct Multiresolution {
  TriMesh coarsest;
  std::vector<Sqrt3Level> levels;
  std::vector<std::uint32_t> input_to_canonical;
};

// `levels` reversals of a fine mesh. Throws std::invalid_argument for a mesh that is not a
// manifold triangle mesh with sqrt(3) structure at every level asked for.
Multiresolution decompose(const TriMesh& fine, int levels);

// The mesh `coarser` reversals below the finest (0 = the decomposed input itself).
TriMesh reconstruct(const Multiresolution& mr, int coarser = 0);

// One level up: P c + Q d with the filters of the coarse connectivity.
TriMesh reconstruct_level(const TriMesh& coarse, const Sqrt3Level& level);

}  // namespace pupwave::sqrt3
