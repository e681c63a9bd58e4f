// .pwm decoder: validates everything before use, predicts every level's size from the
// coarsest connectivity before allocating, and reads only the chunks the requested level needs.
#include <zstd.h>

#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "codec/error.h"
#include "codec/format/chunks.h"
#include "codec/mesh/mesh_codec.h"
#include "codec/mesh/mesh_entropy.h"
#include "codec/mesh/mesh_format.h"
#include "codec/mesh/mesh_quantise.h"
#include "transforms/sqrt3/refine.h"

namespace pupwave::mesh {
namespace {

using sqrt3::Face;
using sqrt3::Vec3;

MeshHeader read_header(std::span<const std::uint8_t> bytes) {
  ChunkReader r(bytes, kMeshMagic, kMeshStreamVersion, kMeshWhat);
  return parse_header(r.expect("MHED").payload);
}

std::vector<Face> parse_connectivity(std::span<const std::uint8_t> payload, const MeshHeader& h) {
  const std::size_t expected = 12 * std::size_t(h.coarse_faces);
  const unsigned long long size = ZSTD_getFrameContentSize(payload.data(), payload.size());
  require_stream(size == expected, "mesh stream: connectivity size does not match the face count");
  std::vector<std::uint8_t> raw(expected);
  const std::size_t n = ZSTD_decompress(raw.data(), raw.size(), payload.data(), payload.size());
  require_stream(!ZSTD_isError(n) && n == expected, "mesh stream: connectivity does not decompress");
  std::vector<Face> faces(h.coarse_faces);
  for (std::size_t i = 0; i < 3 * faces.size(); ++i) {
    std::uint32_t v = 0;
    for (int b = 0; b < 4; ++b) v |= std::uint32_t(raw[4 * i + std::size_t(b)]) << (8 * b);
    faces[i / 3][i % 3] = v;
  }
  return faces;
}

// Vertex count of every level (coarsest first), from the connectivity alone: a plain step adds
// a point per face, a trisect step one per interior face and two per boundary edge.
std::vector<std::size_t> level_sizes(const std::vector<Face>& faces, const MeshHeader& h) {
  const sqrt3::Topology t(h.coarse_vertices, faces);
  std::size_t V = h.coarse_vertices, F = faces.size(), B = t.boundary_edge_count();
  std::vector<std::size_t> sizes{V};
  for (sqrt3::StepKind k : h.kinds) {
    if (k == sqrt3::StepKind::plain) {
      V += F;
    } else {
      V += F + B;
      B *= 3;
    }
    F *= 3;
    require_stream(V <= kMaxStreamVertices && F <= kMaxStreamFaces,
                   "mesh stream: levels exceed the size limit");
    sizes.push_back(V);
  }
  require_stream(V == h.fine_vertices, "mesh stream: finest vertex count does not match the connectivity");
  return sizes;
}

std::vector<Vec3> float_points(std::span<const std::uint8_t> payload, std::size_t points) {
  require_stream(payload.size() == 24 * points, "mesh stream: float64 chunk has the wrong size");
  std::vector<Vec3> p(points);
  for (std::size_t i = 0; i < points; ++i) {
    for (int a = 0; a < 3; ++a) {
      const double v = get_f64(payload, 24 * i + 8 * std::size_t(a));
      require_stream(std::isfinite(v), "mesh stream: coordinate is not finite");
      p[i][a] = v;
    }
  }
  return p;
}

std::vector<std::int64_t> coded_values(std::span<const std::uint8_t> payload, std::size_t points,
                                       bool delta) {
  std::vector<std::int64_t> v = decode_triples(payload, 3 * points);
  if (!delta) return v;
  for (std::size_t i = 3; i < v.size(); ++i) {
    require_stream(std::abs(v[i]) <= kMaxQuantised && std::abs(v[i - 3]) <= kMaxQuantised,
                   "mesh stream: coarsest point out of range");
    v[i] += v[i - 3];
  }
  return v;
}

}  // namespace

bool is_mesh_stream(std::span<const std::uint8_t> bytes) { return has_signature(bytes, kMeshMagic); }

int mesh_stream_levels(std::span<const std::uint8_t> bytes) { return int(read_header(bytes).kinds.size()); }

sqrt3::TriMesh decode_mesh(std::span<const std::uint8_t> bytes, int coarser) {
  const MeshHeader h = read_header(bytes);
  const int L = int(h.kinds.size());
  if (coarser < 0 || coarser > L) {
    throw std::invalid_argument("--level " + std::to_string(coarser) + " out of range 0.." +
                                std::to_string(L));
  }
  const std::size_t used = std::size_t(L - coarser);
  ChunkReader reader(bytes, kMeshMagic, kMeshStreamVersion, kMeshWhat);
  reader.expect("MHED");
  const Chunk conn = reader.expect("CONN");
  const Chunk base = reader.expect("BASE");
  std::vector<Chunk> detail;
  for (std::size_t j = 0; j < used; ++j) detail.push_back(reader.expect("DETL"));
  if (used == std::size_t(L)) require_stream(reader.at_end(), "mesh stream: data after the last chunk");
  const std::vector<Face> faces = parse_connectivity(conn.payload, h);
  std::vector<std::size_t> sizes;
  try {
    sizes = level_sizes(faces, h);
  } catch (const std::invalid_argument& e) {
    throw DecodeError(std::string("mesh stream: coarsest connectivity: ") + e.what());
  }
  sqrt3::TriMesh m;
  m.faces = faces;
  const bool quantised = h.coding == MeshCoding::quantised;
  if (quantised) {
    QuantisedLevels q;
    q.coarsest = coded_values(base.payload, sizes[0], true);
    for (std::size_t j = 0; j < used; ++j)
      q.levels.push_back(coded_values(detail[j].payload, sizes[j + 1] - sizes[j], false));
    const std::vector<sqrt3::StepKind> kinds(h.kinds.begin(), h.kinds.begin() + std::ptrdiff_t(used));
    const sqrt3::Multiresolution mr = dequantise(
        q, faces, kinds, std::vector<double>(h.steps.begin(), h.steps.begin() + std::ptrdiff_t(used)),
        h.coarse_step);
    try {
      return sqrt3::reconstruct(mr, 0);
    } catch (const std::invalid_argument& e) {
      throw DecodeError(std::string("mesh stream: ") + e.what());
    }
  }
  m.points = float_points(base.payload, sizes[0]);
  for (std::size_t j = 0; j < used; ++j) {
    sqrt3::Sqrt3Level level{h.kinds[j], float_points(detail[j].payload, sizes[j + 1] - sizes[j])};
    try {
      m = sqrt3::reconstruct_level(m, level);
    } catch (const std::invalid_argument& e) {
      throw DecodeError(std::string("mesh stream: ") + e.what());
    }
  }
  return m;
}

std::string describe_mesh_stream(std::span<const std::uint8_t> bytes) {
  const MeshHeader h = read_header(bytes);
  ChunkReader reader(bytes, kMeshMagic, kMeshStreamVersion, kMeshWhat);
  std::vector<Chunk> chunks;
  while (!reader.at_end()) chunks.push_back(reader.next());
  std::ostringstream out;
  out << "pupwave mesh multiresolution (.pwm version " << int(kMeshStreamVersion) << ")\n"
      << "  levels: " << h.kinds.size() << " (coarsest first:";
  for (sqrt3::StepKind k : h.kinds) out << ' ' << sqrt3::to_string(k);
  out << ")\n  coarsest mesh: " << h.coarse_vertices << " vertices, " << h.coarse_faces << " faces\n"
      << "  finest mesh: " << h.fine_vertices << " vertices\n";
  if (h.coding == MeshCoding::quantised) {
    out << "  coding: quantised + range coded, max vertex error <= " << h.max_error
        << "\n  steps: coarsest points " << h.coarse_step << ", details (coarsest level first)";
    for (double st : h.steps) out << ' ' << st;
    out << "\n";
  } else {
    out << "  coding: float64 details (exact to rounding)\n";
  }
  for (const Chunk& c : chunks) out << "  chunk " << c.name() << ": " << c.payload.size() << " bytes\n";
  return out.str();
}

}  // namespace pupwave::mesh
