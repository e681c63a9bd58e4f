#pragma once
// Framing and header of the .pwm file (docs/bitstream.md, Mesh). Internal to codec/mesh.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "transforms/sqrt3/refine.h"

namespace pupwave::mesh {

inline constexpr std::uint8_t kMeshStreamVersion = 1;
inline constexpr std::size_t kMaxStreamVertices = std::size_t(1) << 23;  // bounds decoder memory (~1.3 GiB)
inline constexpr std::size_t kMaxStreamFaces = std::size_t(1) << 27;

enum class MeshCoding : std::uint8_t { float64 = 0, quantised = 1 };

struct MeshHeader {
  MeshCoding coding = MeshCoding::float64;
  std::vector<sqrt3::StepKind> kinds;  // coarsest level first
  std::uint32_t coarse_vertices = 0;
  std::uint32_t coarse_faces = 0;
  std::uint32_t fine_vertices = 0;
  std::vector<double> steps;  // details of each level, coarsest first (quantised)
  double coarse_step = 0;     // coarsest points (quantised)
  double max_error = 0;       // bound the encoder guaranteed (quantised)
};

// Signature of the stream; chunks are framed by codec/format/chunks.h.
inline constexpr char kMeshMagic[5] = "PWMS";
inline constexpr const char* kMeshWhat = "mesh stream";

std::vector<std::uint8_t> write_header(const MeshHeader& h);
MeshHeader parse_header(std::span<const std::uint8_t> payload);

void put_f64(std::vector<std::uint8_t>& out, double v);
double get_f64(std::span<const std::uint8_t> bytes, std::size_t offset);

}  // namespace pupwave::mesh
