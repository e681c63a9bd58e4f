#pragma once
// The .pwm mesh multiresolution file (docs/bitstream.md, Mesh): the coarsest mesh, its
// connectivity and the sqrt(3) details of every level, either as float64 values (exact to
// rounding) or quantised with one step and range coded, under a guaranteed maximum vertex
// error. Any level can be decoded without reading the finer levels' data.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "transforms/sqrt3/hierarchy.h"

namespace pupwave::mesh {

struct MeshEncodeOptions {
  int levels = 1;                   // sqrt(3) reversals, 0 .. kMaxMeshLevels
  std::optional<double> max_error;  // none: float64 details; else max |v - v'| (Euclidean) per vertex
};

struct MeshEncodeResult {
  std::vector<std::uint8_t> bytes;
  double step = 0;                         // step of the finest details (0 for float64)
  double measured_error = 0;               // max Euclidean vertex error of the decoded finest mesh
  sqrt3::Multiresolution multiresolution;  // what was coded (before quantisation)
};

inline constexpr int kMaxMeshLevels = 16;

// Decomposes and codes a sqrt(3)-structured mesh. Throws EncodeError with the reason (not a
// manifold triangle mesh, not sqrt(3)-structured, bad options).
MeshEncodeResult encode_mesh(const sqrt3::TriMesh& fine, const MeshEncodeOptions& options);

// The mesh `coarser` reversals below the finest (0 = the coded mesh), in the canonical vertex
// order of the hierarchy. Reads only the chunks that level needs. Throws DecodeError for a
// corrupt or hostile stream, std::invalid_argument when `coarser` exceeds the levels.
sqrt3::TriMesh decode_mesh(std::span<const std::uint8_t> bytes, int coarser = 0);

// Number of levels of a stream (reads the header only).
int mesh_stream_levels(std::span<const std::uint8_t> bytes);

// Human-readable description of a .pwm stream (for `pupwave info`-style output).
std::string describe_mesh_stream(std::span<const std::uint8_t> bytes);

// True when bytes start with the .pwm signature.
bool is_mesh_stream(std::span<const std::uint8_t> bytes);

}  // namespace pupwave::mesh
