#pragma once
// Shared helpers of the volume tests: a scratch folder per test, OpenVDB grids built and read
// directly (independently of tools/volume_io), and the CLI runner.

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>
#include <unistd.h>

#include <filesystem>
#include <random>
#include <string>

#include "cli/run_cli.h"

namespace pupwave::test {
namespace fs = std::filesystem;

// A scratch folder removed after the test; leftovers() counts files other than the inputs.
class VolumeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    openvdb::initialize();
    dir_ = fs::temp_directory_path() / ("pupwave_volumes_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::size_t files_in_dir() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++n;
    return n;
  }
  fs::path dir_;
};

inline std::string testimage(const std::string& name) {
  return std::string(PUPWAVE_TESTIMAGES_DIR) + "/" + name;
}

// Every grid of an OpenVDB file, read with OpenVDB itself.
inline openvdb::GridPtrVec read_grids(const fs::path& path) {
  openvdb::io::File file(path.string());
  file.open();
  openvdb::GridPtrVec grids = *file.getGrids();
  file.close();
  return grids;
}

inline void write_grids(const openvdb::GridPtrVec& grids, const fs::path& path) {
  openvdb::io::File file(path.string());
  file.write(grids);
  file.close();
}

// A sparse grid of random values on an odd-sized box at an odd origin; about `fill` of the
// voxels active, inactive ones holding either the background or a second value.
template <class GridT>
typename GridT::Ptr random_grid(const openvdb::Coord& lo, const openvdb::Coord& size, double fill,
                                unsigned seed) {
  using V = typename GridT::ValueType;
  auto grid = GridT::create(V(0.25));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-3.0, 5.0), coin(0.0, 1.0);
  auto acc = grid->getAccessor();
  for (int z = 0; z < size[2]; ++z)
    for (int y = 0; y < size[1]; ++y)
      for (int x = 0; x < size[0]; ++x) {
        const openvdb::Coord ijk = lo + openvdb::Coord(x, y, z);
        const double c = coin(rng);
        if (c < fill)
          acc.setValueOn(ijk, V(value(rng)));
        else if (c < fill + 0.1)
          acc.setValueOff(ijk, V(-7.5));
      }
  return grid;
}

// Voxel-by-voxel equality of two grids (value and active state) over a's active bounding box
// grown by `margin`, plus background; reports the first difference.
template <class GridT>
::testing::AssertionResult same_voxels(const GridT& a, const GridT& b, int margin = 2) {
  if (a.background() != b.background()) return ::testing::AssertionFailure() << "background differs";
  if (a.activeVoxelCount() != b.activeVoxelCount())
    return ::testing::AssertionFailure()
           << "active voxel count " << a.activeVoxelCount() << " vs " << b.activeVoxelCount();
  openvdb::CoordBBox box = a.evalActiveVoxelBoundingBox();
  box.expand(margin);
  auto ca = a.getConstAccessor();
  auto cb = b.getConstAccessor();
  for (auto it = box.begin(); it; ++it) {
    typename GridT::ValueType va, vb;
    const bool on_a = ca.probeValue(*it, va), on_b = cb.probeValue(*it, vb);
    if (on_a != on_b || va != vb)
      return ::testing::AssertionFailure() << "voxel " << *it << ": " << va << (on_a ? " on" : " off")
                                           << " vs " << vb << (on_b ? " on" : " off");
  }
  return ::testing::AssertionSuccess();
}

// Whole-sample symmetric reflection of coordinate q into [lo, hi] (the extension `lod` uses
// beyond a dense grid's box).
inline int mirror(int q, int lo, int hi) {
  const int n = hi - lo + 1;
  if (n == 1) return lo;
  const int period = 2 * (n - 1);
  int d = (q - lo) % period;
  if (d < 0) d += period;
  return lo + (d < n ? d : period - d);
}

}  // namespace pupwave::test
