#include "codec/mesh/mesh_format.h"

#include <cmath>
#include <cstring>

#include "codec/error.h"
#include "codec/format/byte_io.h"

namespace pupwave::mesh {
void put_f64(std::vector<std::uint8_t>& out, double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, 8);
  for (int i = 0; i < 8; ++i) out.push_back(std::uint8_t(bits >> (8 * i)));
}

double get_f64(std::span<const std::uint8_t> bytes, std::size_t offset) {
  require_stream(offset <= bytes.size() && bytes.size() - offset >= 8, "mesh stream: value truncated");
  std::uint64_t bits = 0;
  for (int i = 0; i < 8; ++i) bits |= std::uint64_t(bytes[offset + std::size_t(i)]) << (8 * i);
  double v;
  std::memcpy(&v, &bits, 8);
  return v;
}

std::vector<std::uint8_t> write_header(const MeshHeader& h) {
  std::vector<std::uint8_t> out;
  ByteWriter w(out);
  w.u8(std::uint8_t(h.coding));
  w.u8(std::uint32_t(h.kinds.size()));
  for (sqrt3::StepKind k : h.kinds) w.u8(std::uint8_t(k));
  w.u32(h.coarse_vertices);
  w.u32(h.coarse_faces);
  w.u32(h.fine_vertices);
  put_f64(out, h.max_error);
  put_f64(out, h.coarse_step);
  for (std::size_t j = 0; j < h.kinds.size(); ++j)
    put_f64(out, h.coding == MeshCoding::quantised ? h.steps[j] : 0.0);
  return out;
}

MeshHeader parse_header(std::span<const std::uint8_t> payload) {
  ByteReader r(payload, "mesh header");
  MeshHeader h;
  const std::uint32_t coding = r.u8();
  require_stream(coding <= 1, [&] { return "mesh header: unknown coding " + std::to_string(coding); });
  h.coding = MeshCoding(coding);
  const std::uint32_t levels = r.u8();
  require_stream(levels <= 16,
                 [&] { return "mesh header: " + std::to_string(levels) + " levels (at most 16)"; });
  for (std::uint32_t j = 0; j < levels; ++j) {
    const std::uint32_t k = r.u8();
    require_stream(k <= 1, [&] { return "mesh header: unknown step kind " + std::to_string(k); });
    h.kinds.push_back(sqrt3::StepKind(k));
  }
  h.coarse_vertices = r.u32();
  h.coarse_faces = r.u32();
  h.fine_vertices = r.u32();
  require_stream(h.coarse_vertices >= 3 && h.coarse_vertices <= kMaxStreamVertices,
                 "mesh header: coarsest vertex count out of range");
  require_stream(h.coarse_faces >= 1 && h.coarse_faces <= kMaxStreamFaces,
                 "mesh header: face count out of range");
  require_stream(h.fine_vertices >= h.coarse_vertices && h.fine_vertices <= kMaxStreamVertices,
                 "mesh header: finest vertex count out of range");
  const std::size_t at = r.position();
  r.bytes(16 + 8 * h.kinds.size());
  h.max_error = get_f64(payload, at);
  h.coarse_step = get_f64(payload, at + 8);
  for (std::size_t j = 0; j < h.kinds.size(); ++j) h.steps.push_back(get_f64(payload, at + 16 + 8 * j));
  require_stream(r.remaining() == 0, "mesh header: trailing bytes");
  if (h.coding == MeshCoding::quantised) {
    h.steps.push_back(h.coarse_step);
    for (double s : h.steps) {
      require_stream(std::isfinite(s) && s > 1e-300 && s < 1e250, "mesh header: quantiser step out of range");
    }
    h.steps.pop_back();
  }
  require_stream(std::isfinite(h.max_error) && h.max_error >= 0, "mesh header: bad error bound");
  return h;
}

}  // namespace pupwave::mesh
