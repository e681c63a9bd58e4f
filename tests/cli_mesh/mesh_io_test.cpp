// The mesh readers and writers: exact round trips, OBJ/PLY variants, and refusal of what the
// mesh cannot hold.
#include <gtest/gtest.h>

#include <filesystem>

#include "tools/mesh_io.h"

namespace pupwave::cli {
namespace {

TEST(MeshIo, RoundTripIsExactInEveryFormat) {
  const sqrt3::TriMesh m = read_mesh(std::string(PUPWAVE_TESTIMAGES_DIR) + "/pig.off");
  sqrt3::TriMesh odd = m;
  odd.points[0] = {0.1, 1.0 / 3.0, -1e-300};
  for (const char* ext : {".obj", ".off", ".ply"}) {
    const auto p = std::filesystem::temp_directory_path() / ("pupwave_mesh_io" + std::string(ext));
    write_mesh(odd, p);
    const sqrt3::TriMesh back = read_mesh(p);
    std::filesystem::remove(p);
    EXPECT_EQ(back.faces, odd.faces) << ext;
    ASSERT_EQ(back.points.size(), odd.points.size()) << ext;
    for (std::size_t i = 0; i < odd.points.size(); ++i) ASSERT_EQ(back.points[i], odd.points[i]) << ext << i;
  }
}

TEST(MeshIo, ObjNegativeIndicesAndComments) {
  const sqrt3::TriMesh m = parse_obj("# c\nv 0 0 0\nv 1 0 0\r\nv 0 1 0\n\nf -3 -2 -1\n", "t.obj");
  ASSERT_EQ(m.faces.size(), 1u);
  EXPECT_EQ(m.faces[0], (sqrt3::Face{0, 1, 2}));
}

TEST(MeshIo, AsciiAndBigEndianPly) {
  const sqrt3::TriMesh a = parse_ply(
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float y\nproperty float x\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n1 0 0\n0 1 0\n1 1 1\n3 0 1 2\n",
      "a.ply");
  EXPECT_EQ(a.points[0], sqrt3::Vec3(0, 1, 0));  // properties in y, x, z order
  std::string big =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  const double coords[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0.5};
  for (double c : coords) {
    unsigned char b[8];
    std::memcpy(b, &c, 8);
    for (int i = 7; i >= 0; --i) big.push_back(char(b[i]));
  }
  big += std::string("\x03\0\0\0\0\0\0\0\x01\0\0\0\x02", 13);
  const sqrt3::TriMesh b = parse_ply(big, "b.ply");
  EXPECT_EQ(b.points[2], sqrt3::Vec3(0, 1, 0.5));
  EXPECT_EQ(b.faces[0], (sqrt3::Face{0, 1, 2}));
  EXPECT_THROW(parse_ply(big.substr(0, big.size() - 1), "b.ply"), std::runtime_error);  // truncated
}

TEST(MeshIo, RefusesWhatItCannotKeep) {
  const char* bad_obj[] = {"v 0 0 0 1 0 0\n", "vn 0 0 1\n", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/2 3/3\n",
                           "v 0 0 0\nf 0 1 2\n", "usemtl x\n"};
  for (const char* t : bad_obj) EXPECT_THROW(parse_obj(t, "x.obj"), std::runtime_error) << t;
  const char* bad_off[] = {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 0 0\n",  // face colour
                           "OFF\n3 1 0\n0 0 0 1\n1 0 0\n0 1 0\n3 0 1 2\n",        // extra vertex value
                           "OFF\n99999999 1 0\n0 0 0\n",                          // counts beyond the file
                           "COFF\n3 1 0\n"};
  for (const char* t : bad_off) EXPECT_THROW(parse_off(t, "x.off"), std::runtime_error) << t;
  EXPECT_THROW(parse_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                         "property float z\nproperty uchar red\nend_header\n0 0 0 1\n",
                         "c.ply"),
               std::runtime_error);
}

}  // namespace
}  // namespace pupwave::cli
