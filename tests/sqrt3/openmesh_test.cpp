// Cross-check of the sqrt(3) subdivision against OpenMesh's Uniform::Sqrt3T (Kobbelt's scheme
// with its boundary rule), an implementation written independently of ours. OpenMesh also
// appends new vertices after the old ones but numbers them in its own order, so its result is
// matched through our hierarchy recovery, which checks the faces are the same too.
#include <gtest/gtest.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/Sqrt3T.hh>

#include "tests/sqrt3/real_meshes.h"
#include "transforms/sqrt3/hierarchy.h"
#include "transforms/sqrt3/subdivide.h"

namespace pupwave::sqrt3 {
namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
};
using OMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

TriMesh openmesh_sqrt3(const TriMesh& in, int levels) {
  OMesh om;
  std::vector<OMesh::VertexHandle> vh;
  for (const Vec3& p : in.points) vh.push_back(om.add_vertex(OMesh::Point(p.x(), p.y(), p.z())));
  for (const Face& f : in.faces) om.add_face(vh[f[0]], vh[f[1]], vh[f[2]]);
  OpenMesh::Subdivider::Uniform::Sqrt3T<OMesh> sqrt3;
  sqrt3.attach(om);
  sqrt3(std::size_t(levels));
  sqrt3.detach();
  TriMesh out;
  for (auto v : om.vertices()) {
    const auto& p = om.point(v);
    out.points.push_back({p[0], p[1], p[2]});
  }
  for (auto f : om.faces()) {
    Face t{};
    int i = 0;
    for (auto v : om.fv_range(f)) t[std::size_t(i++)] = std::uint32_t(v.idx());
    out.faces.push_back(t);
  }
  return out;
}

// Our subdivision and OpenMesh's agree vertex by vertex after matching by connectivity.
void expect_same_as_openmesh(const TriMesh& base, int levels, const std::string& what) {
  const TriMesh ours = subdivide(base, levels);
  const TriMesh theirs = openmesh_sqrt3(base, levels);
  ASSERT_EQ(theirs.points.size(), ours.points.size()) << what;
  ASSERT_EQ(theirs.faces.size(), ours.faces.size()) << what;
  // decompose() recovers OpenMesh's hierarchy (checking its faces) and says where each of its
  // vertices is in the canonical order, which is the order of our own subdivision.
  const Multiresolution mr = decompose(theirs, levels);
  double worst = 0;
  for (std::size_t v = 0; v < theirs.points.size(); ++v) {
    worst = std::max(worst, (theirs.points[v] - ours.points[mr.input_to_canonical[v]]).norm());
  }
  EXPECT_LT(worst, 1e-12 * mesh_scale(base.points)) << what;
  std::printf("%-14s %d steps, %zu vertices: max |ours - OpenMesh| = %.3g\n", what.c_str(), levels,
              ours.points.size(), worst);
}

TEST(Sqrt3OpenMesh, ClosedMeshesMatchSqrt3T) {
  for (const char* name : test::kClosedMeshes) expect_same_as_openmesh(test::real_mesh(name), 3, name);
}

TEST(Sqrt3OpenMesh, OpenMeshesMatchSqrt3TBoundaryRule) {
  for (const char* name : test::kOpenMeshes) expect_same_as_openmesh(test::real_mesh(name), 3, name);
}

}  // namespace
}  // namespace pupwave::sqrt3
