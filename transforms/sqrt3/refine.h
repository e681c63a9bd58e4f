#pragma once
// Connectivity of one sqrt(3) step (Kobbelt 2000; seed Section 4 and Section 8): a face point
// in every face, then every old interior edge flipped. Boundaries follow Kobbelt's rule of
// refining them every other step: a `plain` step leaves boundary edges and vertices alone (the
// boundary face gets its face point, its boundary edge is not flipped), a `boundary_trisect`
// step splits every boundary edge into three (two edge points) and fans the boundary face
// from its apex instead of giving it a face point.
//
// Canonical vertex order of the fine mesh (how the hierarchy is recovered, docs/sqrt3.md):
// the coarse vertices first, unchanged; then the introduced points in coarse face order: the
// face's face point, or for a trisected boundary face the two edge points of its boundary
// edge, the one next to the boundary half-edge's start first.

#include <cstdint>
#include <vector>

#include "transforms/sqrt3/mesh.h"

namespace pupwave::sqrt3 {

enum class StepKind : std::uint8_t { plain = 0, boundary_trisect = 1 };
const char* to_string(StepKind kind);

// Kind of step `index` (0 = first) of a subdivision started on a user's mesh: plain first,
// then alternating, as Kobbelt's and OpenMesh's generation counter.
inline StepKind kobbelt_step_kind(int index) {
  return index % 2 == 0 ? StepKind::plain : StepKind::boundary_trisect;
}

inline constexpr std::uint32_t kNone = 0xffffffffu;

// Result of refining a coarse topology: fine faces and where every new vertex came from.
struct Refinement {
  StepKind kind = StepKind::plain;
  std::size_t coarse_vertices = 0;
  std::vector<Face> faces;                // fine faces, canonical order
  std::vector<std::uint32_t> face_point;  // per coarse face: fine index of its face point, or kNone
  std::vector<std::uint32_t> edge_point;  // per coarse half-edge: first of its two edge points, or kNone
  std::size_t face_points = 0;            // number of face points
  std::size_t edge_points = 0;            // number of edge points (2 per boundary edge)
  std::size_t fine_vertices() const { return coarse_vertices + face_points + edge_points; }
};

// Refines the connectivity. A boundary_trisect step needs every boundary face to have exactly
// one boundary edge (true after a plain step); throws std::invalid_argument otherwise.
Refinement refine(const Topology& coarse, StepKind kind);

}  // namespace pupwave::sqrt3
