// fuzz_mesh: a multiresolution mesh stream (.pwm) decoded at every level. Invariants: faces
// index existing points; a decode twice gives the same mesh.
#include <cstring>
#include <stdexcept>

#include "codec/error.h"
#include "codec/mesh/mesh_codec.h"
#include "fuzz_check.h"

using namespace pupwave;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto bytes = fuzz::as_span(data, size);
  int levels = 0;
  try {
    levels = mesh::mesh_stream_levels(bytes);
  } catch (const DecodeError&) {
    return 0;
  }
  for (int coarser = 0; coarser <= levels; ++coarser) {
    sqrt3::TriMesh mesh;
    try {
      mesh = mesh::decode_mesh(bytes, coarser);
    } catch (const DecodeError&) {
      return 0;
    }
    for (const auto& f : mesh.faces)
      for (auto v : f) FUZZ_CHECK(std::size_t(v) < mesh.points.size());
    if (coarser == 0) {
      const sqrt3::TriMesh again = mesh::decode_mesh(bytes, 0);
      FUZZ_CHECK(again.points.size() == mesh.points.size() && again.faces == mesh.faces);
      FUZZ_CHECK(std::memcmp(again.points.data(), mesh.points.data(),
                             mesh.points.size() * sizeof(sqrt3::Vec3)) == 0);
    }
  }
  return 0;
}
