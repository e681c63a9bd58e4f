// `pupwave lod`: geometry and topology against OpenVDB's own tools::MultiResGrid (what vdb_lod
// runs), values against an independent downsampling made here from 1-D analyses only.
#include <openvdb/tools/Count.h>
#include <openvdb/tools/MultiResGrid.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "transforms/spec.h"
#include "volumes/volume_test_util.h"

namespace pupwave::test {
namespace {

openvdb::FloatGrid::Ptr find_grid(const openvdb::GridPtrVec& grids, const std::string& name) {
  for (const auto& g : grids)
    if (g->getName() == name) return openvdb::gridPtrCast<openvdb::FloatGrid>(g);
  return nullptr;
}

// Same active voxels, transform and vdb_lod metadata as MultiResGrid's level k.
void expect_like_vdb_lod(const openvdb::FloatGrid& ours,
                         openvdb::tools::MultiResGrid<openvdb::FloatTree>& mrg, std::size_t k,
                         const openvdb::FloatGrid& input) {
  const openvdb::FloatGrid::Ptr theirs = mrg.grid(k);
  const openvdb::Mat4d mo = ours.transform().baseMap()->getAffineMap()->getMat4();
  const openvdb::Mat4d mt = theirs->transform().baseMap()->getAffineMap()->getMat4();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(mo(r, c), mt(r, c), 1e-14) << "transform (" << r << "," << c << ") level " << k;
  EXPECT_NEAR(ours.voxelSize()[0], input.voxelSize()[0] * double(1 << k), 1e-12);
  EXPECT_EQ(ours.evalActiveVoxelBoundingBox(), theirs->evalActiveVoxelBoundingBox()) << "level " << k;
  EXPECT_EQ(ours.activeVoxelCount(), theirs->activeVoxelCount()) << "level " << k;
  auto a = theirs->getConstAccessor();
  for (auto it = ours.cbeginValueOn(); it; ++it) {
    EXPECT_TRUE(a.isValueOn(it.getCoord())) << it.getCoord();
    if (!a.isValueOn(it.getCoord())) break;
  }
  EXPECT_EQ(ours.background(), input.background());
  EXPECT_EQ(ours.getGridClass(), input.getGridClass());
  ASSERT_TRUE(ours.getMetadata<openvdb::FloatMetadata>("MultiResGrid_Level"));
  EXPECT_EQ(ours.metaValue<float>("MultiResGrid_Level"), float(k));
  EXPECT_EQ(ours.metaValue<openvdb::Int64>("MultiResGrid_Levels"), openvdb::Int64(mrg.numLevels()));
}

// The expected level-k field of a sparse grid, whose outside is its background (tools/cmd_lod.cpp):
// over its active bounding box padded to multiples of 2^top plus five such blocks per side (so
// the symmetric extension at the ends of these finite lines only ever mirrors background), k
// levels of 1-D analysis along x, then y, then z keeping the coarse part, divided by the coarse
// response to a constant line, clamped to the input's value range.
struct Expected {
  openvdb::Coord origin;  // index of sample 0 at level k
  std::array<std::size_t, 3> n{};
  std::vector<double> values;
  double at(const openvdb::Coord& ijk) const {
    const openvdb::Coord j = ijk - origin;
    for (int a = 0; a < 3; ++a)
      if (j[a] < 0 || std::size_t(j[a]) >= n[std::size_t(a)]) return std::nan("");
    return values[std::size_t(j[0]) + n[0] * (std::size_t(j[1]) + n[1] * std::size_t(j[2]))];
  }
};

void analyze_levels(const Transform1D& t, std::vector<double>& line, int k) {
  std::size_t m = line.size();
  for (int l = 0; l < k; ++l, m = (m + 1) / 2) t.analyze(std::span<double>(line.data(), m));
  line.resize(m);
}

Expected expected_level(const openvdb::FloatGrid& grid, const Transform1D& t, int k, int top) {
  const int block = 1 << top;
  const auto floor_div = [](int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); };
  const openvdb::CoordBBox active = grid.evalActiveVoxelBoundingBox();
  openvdb::Coord lo, size;
  for (int a = 0; a < 3; ++a) {
    lo[a] = (floor_div(active.min()[a], block) - 5) * block;
    size[a] = (floor_div(active.max()[a] + block, block) + 5) * block - lo[a];
  }
  double vmin = grid.background(), vmax = grid.background();
  auto acc = grid.getConstAccessor();
  for (auto it = active.begin(); it; ++it) {
    vmin = std::min(vmin, double(acc.getValue(*it)));
    vmax = std::max(vmax, double(acc.getValue(*it)));
  }
  std::array<std::size_t, 3> n{std::size_t(size[0]), std::size_t(size[1]), std::size_t(size[2])};
  std::vector<double> v(n[0] * n[1] * n[2]);
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = acc.getValue(lo + openvdb::Coord(int(i % n[0]), int(i / n[0] % n[1]), int(i / n[0] / n[1])));
  std::array<std::vector<double>, 3> gain;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    gain[axis].assign(n[axis], 1.0);
    analyze_levels(t, gain[axis], k);
    std::array<std::size_t, 3> m = n;
    m[axis] = gain[axis].size();
    std::vector<double> out(m[0] * m[1] * m[2]);
    const std::size_t stride = axis == 0 ? 1 : axis == 1 ? n[0] : n[0] * n[1];
    const std::size_t out_stride = axis == 0 ? 1 : axis == 1 ? m[0] : m[0] * m[1];
    for (std::size_t i = 0; i < out.size(); i += 1) {
      if ((i / out_stride) % m[axis] != 0) continue;  // one pass per line, from its first sample
      const std::size_t outer = i / out_stride / m[axis], inner = i % out_stride;
      std::vector<double> line(n[axis]);
      for (std::size_t s = 0; s < n[axis]; ++s) line[s] = v[outer * stride * n[axis] + inner + s * stride];
      analyze_levels(t, line, k);
      for (std::size_t s = 0; s < m[axis]; ++s) out[i + s * out_stride] = line[s];
    }
    v.swap(out);
    n = m;
  }
  Expected e;
  e.origin = openvdb::Coord(lo[0] >> k, lo[1] >> k, lo[2] >> k);
  e.n = n;
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = std::clamp(v[i] / (gain[0][i % n[0]] * gain[1][i / n[0] % n[1]] * gain[2][i / n[0] / n[1]]), vmin,
                      vmax);
  e.values = std::move(v);
  return e;
}

// Runs `lod --levels top` and checks every level against MultiResGrid and the expected values.
void check_lod(const fs::path& in, const fs::path& out, const std::string& spec, int top) {
  const CliResult r =
      run_cli({"lod", in.string(), out.string(), "--levels", std::to_string(top), "--transform", spec});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const openvdb::GridPtrVec input = read_grids(in), output = read_grids(out);
  ASSERT_EQ(output.size(), input.size() * std::size_t(top + 1));
  const Transform1DPtr t = make_transform(spec);
  for (const auto& base : input) {
    const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
    openvdb::tools::MultiResGrid<openvdb::FloatTree> mrg(std::size_t(top + 1), *grid);
    for (int k = 0; k <= top; ++k) {
      const auto ours = find_grid(output, grid->getName() + "_level_" + std::to_string(k));
      ASSERT_TRUE(ours) << grid->getName() << " level " << k << " missing";
      expect_like_vdb_lod(*ours, mrg, std::size_t(k), *grid);
      if (k == 0) {
        EXPECT_TRUE(same_voxels(*grid, *ours));
        continue;
      }
      const Expected e = expected_level(*grid, *t, k, top);
      const double bg = grid->background(), tol = 2e-6 * (1.0 + std::abs(bg));
      std::size_t checked = 0;
      auto acc = ours->getConstAccessor();
      for (auto it = openvdb::CoordBBox(e.origin, e.origin + openvdb::Coord(int(e.n[0]) - 1, int(e.n[1]) - 1,
                                                                            int(e.n[2]) - 1))
                         .begin();
           it; ++it) {
        float value = 0;
        const double want = e.at(*it);
        if (acc.probeValue(*it, value)) {
          ASSERT_NEAR(value, want, tol * 8) << spec << " level " << k << " voxel " << *it;
          ++checked;
        } else if (grid->getGridClass() == openvdb::GRID_LEVEL_SET && std::abs(want) > 1e-6) {
          ASSERT_EQ(value, want < 0 ? -std::abs(float(bg)) : std::abs(float(bg)))
              << "inactive sign at " << *it;
        }
      }
      EXPECT_EQ(checked, ours->activeVoxelCount());
    }
  }
}

TEST_F(VolumeTest, LodLevelSetMatchesVdbLodGeometryAndIndependentLowBand) {
  check_lod(testimage("sphere_ls.vdb"), dir_ / "sphere_lod.vdb", "cdf97", 3);
}

TEST_F(VolumeTest, LodOddSparseGridsTwoTransforms) {
  auto f = random_grid<openvdb::FloatGrid>({-13, 5, 7}, {37, 29, 23}, 0.4, 11);
  f->setName("density");
  openvdb::math::Transform::Ptr xf = openvdb::math::Transform::createLinearTransform(0.3);
  xf->postTranslate(openvdb::Vec3d(1.0, 2.0, -0.5));
  f->setTransform(xf);
  auto g = random_grid<openvdb::FloatGrid>({4, -9, -3}, {5, 11, 2}, 0.8, 12);
  g->setName("small");
  write_grids({f, g}, dir_ / "in.vdb");
  check_lod(dir_ / "in.vdb", dir_ / "out97.vdb", "cdf97", 2);
  check_lod(dir_ / "in.vdb", dir_ / "out53.vdb", "cdf53", 3);
}

// The coarse band is normalised so a constant field stays that constant at every level and
// position, box edges included. Two inactive outlier voxels (+-100) widen the clamping range so
// clamping cannot hide a wrong gain; only coarse voxels beyond their footprint (half-width under
// 4 * 2^k fine voxels for the 9-tap low pass) are checked.
TEST_F(VolumeTest, LodConstantFieldStaysConstant) {
  auto c = openvdb::FloatGrid::create(2.5f);
  c->fill(openvdb::CoordBBox(openvdb::Coord(-5, 0, 3), openvdb::Coord(33, 26, 30)), 2.5f, true);
  const openvdb::Coord outliers[2] = {{-5, 0, 3}, {33, 26, 30}};
  c->tree().setValueOff(outliers[0], 100.0f);
  c->tree().setValueOff(outliers[1], -100.0f);
  c->setName("c");
  write_grids({c}, dir_ / "c.vdb");
  for (const std::string spec : {"cdf97", "cdf53"}) {
    const CliResult r = run_cli(
        {"lod", (dir_ / "c.vdb").string(), (dir_ / "o.vdb").string(), "--levels", "2", "--transform", spec});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::size_t checked = 0;
    for (const auto& base : read_grids(dir_ / "o.vdb")) {
      const auto g = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
      const int scale = int(std::lround(g->voxelSize()[0]));  // 2^k: the input voxel size is 1
      for (auto it = g->cbeginValueOn(); it; ++it) {
        const auto near = [&](const openvdb::Coord& o) {
          const openvdb::Coord d = openvdb::Coord(it.getCoord().asVec3i() * scale) - o;
          return std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])}) <= 4 * scale + 2;
        };
        if (near(outliers[0]) || near(outliers[1])) continue;
        ASSERT_NEAR(*it, 2.5f, 1e-5) << spec << ' ' << g->getName() << ' ' << it.getCoord();
        ++checked;
      }
    }
    EXPECT_GT(checked, 10000u);
  }
}

TEST_F(VolumeTest, LodRangeAndNames) {
  auto a = random_grid<openvdb::FloatGrid>({0, 0, 0}, {9, 9, 9}, 0.5, 5);
  a->setName("density");
  auto b = random_grid<openvdb::FloatGrid>({0, 0, 0}, {9, 9, 9}, 0.5, 6);
  b->setName("temperature");
  write_grids({a, b}, dir_ / "in.vdb");
  const CliResult r = run_cli({"lod", (dir_ / "in.vdb").string(), (dir_ / "o.vdb").string(), "--range",
                               "1-3:2", "--name", "density"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::vector<std::string> names;
  for (const auto& g : read_grids(dir_ / "o.vdb")) names.push_back(g->getName());
  EXPECT_EQ(names, (std::vector<std::string>{"density_level_1", "density_level_3"}));
  for (const std::vector<std::string>& bad :
       std::vector<std::vector<std::string>>{{"--range", "0-1:0.5"},
                                             {"--range", "3-1"},
                                             {"--levels", "2", "--range", "0-2"},
                                             {},
                                             {"--levels", "99"},
                                             {"--levels", "2", "--transform", "nope"},
                                             {"--levels", "2", "--name", "missing"}}) {
    std::vector<std::string> args{"lod", (dir_ / "in.vdb").string(), (dir_ / "bad.vdb").string()};
    args.insert(args.end(), bad.begin(), bad.end());
    const CliResult e = run_cli(args);
    EXPECT_NE(e.exit_code, 0) << e.output;
    EXPECT_FALSE(fs::exists(dir_ / "bad.vdb"));
  }
}

}  // namespace

namespace {

// Error of the active voxels of `level` (scale 2^k) near the box faces against the mean of the fine field
// over the 2^k box centred on its fine position (mirrored at the fine grid's box), relative to the range.
struct EdgeFidelity {
  double rms = 0.0, max = 0.0;
  std::size_t voxels = 0;
};

EdgeFidelity edge_fidelity(const openvdb::FloatGrid& fine, const openvdb::FloatGrid& level, int scale) {
  const openvdb::CoordBBox box = fine.evalActiveVoxelBoundingBox();
  const auto minmax = openvdb::tools::minMax(fine.tree());
  const float lo = minmax.min(), hi = minmax.max();
  auto acc = fine.getConstAccessor();
  EdgeFidelity f;
  double sum = 0.0;
  for (auto it = level.cbeginValueOn(); it; ++it) {
    const openvdb::Coord p = openvdb::Coord(it.getCoord().asVec3i() * scale);
    int border = std::numeric_limits<int>::max();  // fine voxels to the nearest face of the box
    for (int a = 0; a < 3; ++a) border = std::min({border, p[a] - box.min()[a], box.max()[a] - p[a]});
    if (border > 2 * scale) continue;  // the interior is the same either way
    double mean = 0.0;
    int n = 0;
    for (int dz = -scale / 2; dz <= scale / 2; ++dz)
      for (int dy = -scale / 2; dy <= scale / 2; ++dy)
        for (int dx = -scale / 2; dx <= scale / 2; ++dx) {
          openvdb::Coord q = p + openvdb::Coord(dx, dy, dz);
          for (int a = 0; a < 3; ++a) q[a] = mirror(q[a], box.min()[a], box.max()[a]);
          mean += acc.getValue(q), ++n;
        }
    const double e = std::abs(*it - mean / n) / double(hi - lo);
    sum += e * e, f.max = std::max(f.max, e), ++f.voxels;
  }
  f.rms = std::sqrt(sum / double(std::max<std::size_t>(f.voxels, 1)));
  return f;
}

}  // namespace

// Where a dense grid's data ends at its box, padding with background darkens the border of
// every level; the default (--edge auto) extends such grids symmetrically, while
// sparse grids (whose outside is background) keep background padding (the tests above).
TEST_F(VolumeTest, LodDenseGridEdgesExtendSymmetrically) {
  const fs::path raw = testimage("gray_scott64.raw"), vdb = dir_ / "gs.vdb";
  ASSERT_EQ(run_cli({"convert-volume", raw.string(), vdb.string(), "--dims", "64,64,64", "--dtype", "f32"})
                .exit_code,
            0);
  const auto fine = openvdb::gridPtrCast<openvdb::FloatGrid>(read_grids(vdb).front());
  ASSERT_EQ(fine->activeVoxelCount(), openvdb::Index64(64 * 64 * 64));
  std::map<std::string, std::array<EdgeFidelity, 3>> by_edge;
  for (const std::string edge : {"auto", "symmetric", "background"}) {
    const fs::path out = dir_ / ("lod_" + edge + ".vdb");
    const CliResult r = run_cli({"lod", vdb.string(), out.string(), "--levels", "2", "--edge", edge});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const auto& base : read_grids(out)) {
      const auto g = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
      const int scale = int(std::lround(g->voxelSize()[0]));
      if (scale > 1) by_edge[edge][std::size_t(scale / 2)] = edge_fidelity(*fine, *g, scale);
    }
  }
  for (std::size_t k : {1u, 2u}) {
    const EdgeFidelity &a = by_edge["auto"][k], &s = by_edge["symmetric"][k], &b = by_edge["background"][k];
    EXPECT_EQ(a.rms, s.rms) << "auto is symmetric for a dense grid";
    EXPECT_GT(s.voxels, 0u);
    std::printf("border RMS at scale %zu: symmetric %.3g, background %.3g of the range\n", 2 * k, s.rms,
                b.rms);
    // Background padding pulls the border toward 0; symmetric extension keeps it near the data.
    EXPECT_LT(s.rms, 0.25 * b.rms) << "scale " << 2 * k << ": symmetric " << s.rms << ", background "
                                   << b.rms;
    EXPECT_LT(s.rms, 0.03) << "scale " << 2 * k;
  }
}

namespace {

// Levels 1..top of every grid of `lod IN --levels top --edge EDGE`, by name (NAME_level_K).
std::map<std::string, openvdb::FloatGrid::Ptr> lod_levels(const fs::path& in, const fs::path& out,
                                                          const std::string& edge, int top) {
  const CliResult r =
      run_cli({"lod", in.string(), out.string(), "--levels", std::to_string(top), "--edge", edge});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  std::map<std::string, openvdb::FloatGrid::Ptr> levels;
  for (const auto& base : read_grids(out))
    if (base->metaValue<float>("MultiResGrid_Level") > 0.0f)
      levels[base->getName()] = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
  EXPECT_EQ(levels.size() % std::size_t(top), 0u);
  return levels;
}

// Mean of the active voxels on the six faces of the grid's active bounding box.
double face_mean(const openvdb::FloatGrid& g) {
  openvdb::CoordBBox inner = g.evalActiveVoxelBoundingBox();
  inner.expand(-1);
  double sum = 0.0;
  std::size_t n = 0;
  for (auto it = g.cbeginValueOn(); it; ++it)
    if (!inner.isInside(it.getCoord())) sum += *it, ++n;
  return sum / double(std::max<std::size_t>(n, 1));
}

// Share of the voxels on the faces of the active bounding box that are active and not the
// background (voxel grids without tiles, as the inputs here are).
double face_fill(const openvdb::FloatGrid& g) {
  const openvdb::CoordBBox box = g.evalActiveVoxelBoundingBox();
  openvdb::CoordBBox inner = box;
  inner.expand(-1);
  std::size_t filled = 0;
  for (auto it = g.cbeginValueOn(); it; ++it)
    if (!inner.isInside(it.getCoord()) && *it != g.background()) ++filled;
  return double(filled) / double(box.volume() - inner.volume());
}

}  // namespace

// --edge auto judges a grid by the faces of its active box. The Gray-Scott field (every voxel
// active) with one interior voxel made a background voxel (inactive, holding the background) and
// one face voxel set to the background is still dense: auto gives the levels of --edge
// symmetric, voxel for voxel, and their borders keep the field's level instead of being darkened
// toward the background. The level set and the fog volume (data touching their boxes in patches)
// keep background padding.
TEST_F(VolumeTest, LodAutoEdgeJudgesDensityByBoxFaces) {
  const fs::path raw = testimage("gray_scott64.raw"), vdb = dir_ / "gs.vdb", holed = dir_ / "holed.vdb";
  ASSERT_EQ(run_cli({"convert-volume", raw.string(), vdb.string(), "--dims", "64,64,64", "--dtype", "f32"})
                .exit_code,
            0);
  const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(read_grids(vdb).front());
  ASSERT_TRUE(grid);
  grid->tree().setValueOff(openvdb::Coord(31, 17, 40), grid->background());
  grid->tree().setValueOn(openvdb::Coord(0, 20, 30), grid->background());
  const openvdb::CoordBBox box(openvdb::Coord(0), openvdb::Coord(63));
  ASSERT_EQ(grid->evalActiveVoxelBoundingBox(), box);
  ASSERT_EQ(grid->activeVoxelCount(), box.volume() - 1);
  write_grids({grid}, holed);
  const int top = 2;
  const auto autos = lod_levels(holed, dir_ / "auto.vdb", "auto", top);
  const auto syms = lod_levels(holed, dir_ / "sym.vdb", "symmetric", top);
  const auto bgs = lod_levels(holed, dir_ / "bg.vdb", "background", top);
  ASSERT_EQ(autos.size(), std::size_t(top));
  const double fine = face_mean(*grid);
  std::printf("holed Gray-Scott: face fill %.4f\n", face_fill(*grid));
  for (const auto& [name, level] : autos) {
    ASSERT_TRUE(level && syms.count(name) && bgs.count(name)) << name;
    const openvdb::FloatGrid &s = *syms.at(name), &b = *bgs.at(name);
    const double a_mean = face_mean(*level), b_mean = face_mean(b);
    std::printf("holed Gray-Scott %s face mean: auto %.4f, symmetric %.4f, background %.4f (level 0: %.4f)\n",
                name.c_str(), a_mean, face_mean(s), b_mean, fine);
    EXPECT_TRUE(same_voxels(s, *level)) << name << ": auto is not symmetric";
    // Background padding pulls the border toward the background (0); auto must not.
    EXPECT_LT(std::abs(a_mean - fine), 0.25 * std::abs(b_mean - fine)) << name;
  }
  for (const char* file : {"sphere_ls.vdb", "dodeca_fog.vdb"}) {
    const fs::path in = testimage(file);
    const auto fine_grid = openvdb::gridPtrCast<openvdb::FloatGrid>(read_grids(in).front());
    ASSERT_TRUE(fine_grid) << file;
    std::printf("%s: face fill %.4f\n", file, face_fill(*fine_grid));
    const auto a = lod_levels(in, dir_ / "auto.vdb", "auto", top);
    const auto s = lod_levels(in, dir_ / "sym.vdb", "symmetric", top);
    const auto b = lod_levels(in, dir_ / "bg.vdb", "background", top);
    ASSERT_FALSE(a.empty()) << file;
    for (const auto& [name, level] : a) {
      ASSERT_TRUE(level && b.count(name) && s.count(name)) << file << ' ' << name;
      EXPECT_TRUE(same_voxels(*b.at(name), *level)) << file << ' ' << name;
      // The two rules differ here, so the comparison above can tell them apart.
      EXPECT_FALSE(same_voxels(*s.at(name), *level)) << file << ' ' << name;
    }
  }
}

// Active tiles count as the voxels they cover: a box filled by tiles alone (no leaf) is dense,
// so auto keeps its constant value up to the border where background padding would darken it.
TEST_F(VolumeTest, LodAutoEdgeCountsActiveTiles) {
  const auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("ones");
  grid->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(63)), 1.0f, true);
  ASSERT_EQ(grid->tree().leafCount(), 0u);
  write_grids({grid}, dir_ / "tiles.vdb");
  const auto autos = lod_levels(dir_ / "tiles.vdb", dir_ / "auto.vdb", "auto", 2);
  const auto bgs = lod_levels(dir_ / "tiles.vdb", dir_ / "bg.vdb", "background", 2);
  ASSERT_EQ(autos.size(), 2u);
  for (const auto& [name, level] : autos) {
    ASSERT_TRUE(level && bgs.count(name)) << name;
    EXPECT_NEAR(face_mean(*level), 1.0, 1e-6) << name;
    EXPECT_LT(face_mean(*bgs.at(name)), 0.9) << name;
  }
}

}  // namespace pupwave::test
