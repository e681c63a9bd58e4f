// `pupwave mesh ...` end to end on the real meshes of testimages/: subdivide -> decompose ->
// reconstruct round trips in every format, --level, --max-error, lod with its contact sheet,
// and the inputs that must be rejected with a clear error and no output file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/cli/run_cli.h"
#include "tools/image_io.h"
#include "tools/mesh_io.h"

namespace pupwave {
namespace {

namespace fs = std::filesystem;
using test::run_cli;

class MeshCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pupwave_mesh_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string data(const std::string& name) {
    return std::string(PUPWAVE_TESTIMAGES_DIR) + "/" + name;
  }
  void write_text(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
  }
  fs::path dir_;
};

double max_distance(const sqrt3::TriMesh& a, const sqrt3::TriMesh& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.points.size(); ++i) d = std::max(d, (a.points[i] - b.points[i]).norm());
  return d;
}

TEST_F(MeshCli, SubdivideDecomposeReconstructRoundTripsInEveryFormat) {
  for (const std::string ext : {".obj", ".off", ".ply"}) {
    const std::string fine = path("fine" + ext), pwm = path("m" + ext + ".pwm"), back = path("back" + ext);
    ASSERT_EQ(run_cli({"mesh", "subdivide", data("nefertiti.off"), fine, "--levels", "3"}).exit_code, 0);
    const auto d = run_cli({"mesh", "decompose", fine, pwm, "--levels", "3"});
    ASSERT_EQ(d.exit_code, 0) << d.output;
    EXPECT_EQ(d.output.find("note:"), std::string::npos) << "subdivide output must already be canonical";
    ASSERT_EQ(run_cli({"mesh", "reconstruct", pwm, back}).exit_code, 0);
    const sqrt3::TriMesh a = cli::read_mesh(fine), b = cli::read_mesh(back);
    ASSERT_EQ(a.points.size(), b.points.size());
    EXPECT_EQ(a.faces, b.faces) << ext;  // same vertex and face order
    EXPECT_LT(max_distance(a, b), 1e-12 * 300) << ext;
  }
}

TEST_F(MeshCli, LevelGivesTheCoarserMeshes) {
  ASSERT_EQ(run_cli({"mesh", "subdivide", data("dragknob.off"), path("f.obj"), "--levels", "2"}).exit_code,
            0);
  ASSERT_EQ(run_cli({"mesh", "decompose", path("f.obj"), path("f.pwm"), "--levels", "2"}).exit_code, 0);
  ASSERT_EQ(run_cli({"mesh", "reconstruct", path("f.pwm"), path("l2.off"), "--level", "2"}).exit_code, 0);
  const sqrt3::TriMesh base = cli::read_mesh(data("dragknob.off")), l2 = cli::read_mesh(path("l2.off"));
  ASSERT_EQ(l2.points.size(), base.points.size());
  EXPECT_LT(max_distance(l2, base), 1e-12);
  ASSERT_EQ(run_cli({"mesh", "reconstruct", path("f.pwm"), path("l1.obj"), "--level", "1"}).exit_code, 0);
  EXPECT_EQ(cli::read_mesh(path("l1.obj")).faces.size(), 3 * base.faces.size());
  const auto bad = run_cli({"mesh", "reconstruct", path("f.pwm"), path("l3.obj"), "--level", "3"});
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("out of range"), std::string::npos) << bad.output;
}

TEST_F(MeshCli, MaxErrorIsGuaranteedOnAPerturbedMesh) {
  ASSERT_EQ(run_cli({"mesh", "subdivide", data("pig.off"), path("f.ply"), "--levels", "2"}).exit_code, 0);
  sqrt3::TriMesh f = cli::read_mesh(path("f.ply"));
  for (std::size_t i = 0; i < f.points.size(); ++i) f.points[i].x() += 0.01 * std::sin(double(i) * 1.7);
  cli::write_mesh(f, path("g.ply"));
  for (const char* e : {"0.01", "0.001"}) {
    const auto r =
        run_cli({"mesh", "decompose", path("g.ply"), path("g.pwm"), "--levels", "2", "--max-error", e});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    ASSERT_EQ(run_cli({"mesh", "reconstruct", path("g.pwm"), path("h.ply")}).exit_code, 0);
    EXPECT_LE(max_distance(cli::read_mesh(path("h.ply")), f), std::stod(e)) << e;
  }
  EXPECT_LT(fs::file_size(path("g.pwm")), 24 * f.points.size() / 4);  // far below float64 size
}

TEST_F(MeshCli, LodWritesEveryLevelAndAContactSheet) {
  ASSERT_EQ(run_cli({"mesh", "subdivide", data("eight.off"), path("f.obj"), "--levels", "2"}).exit_code, 0);
  const auto r =
      run_cli({"mesh", "lod", path("f.obj"), path("eight"), "--levels", "2", "--sheet", path("s.png")});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::size_t faces = cli::read_mesh(data("eight.off")).faces.size();
  for (int j = 0; j <= 2; ++j) {
    const sqrt3::TriMesh m = cli::read_mesh(path("eight_level_" + std::to_string(j) + ".obj"));
    EXPECT_EQ(m.faces.size(), faces * (j == 0 ? 9 : j == 1 ? 3 : 1)) << j;
  }
  const Image sheet = cli::read_image(path("s.png"));
  EXPECT_EQ(sheet.width, 3 * sheet.height);
  // Every tile shows the shape: some pixels differ from the background.
  for (std::size_t t = 0; t < 3; ++t) {
    std::size_t drawn = 0;
    for (std::size_t y = 0; y < sheet.height; ++y)
      for (std::size_t x = t * sheet.height; x < (t + 1) * sheet.height; ++x)
        drawn += sheet.at(0, x, y) < 240;
    EXPECT_GT(drawn, sheet.height * sheet.height / 20) << t;
  }
}

TEST_F(MeshCli, BadMeshesAreRejectedClearly) {
  write_text("quad.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  write_text("nm.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n");
  write_text("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  write_text("nan.obj", "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const struct {
    std::vector<std::string> args;
    const char* message;
  } cases[] = {
      {{"mesh", "subdivide", path("quad.off"), path("o.obj")}, "needs triangles"},
      {{"mesh", "subdivide", path("nm.off"), path("o.obj")}, "non-manifold"},
      {{"mesh", "subdivide", path("range.obj"), path("o.obj")}, "out of range"},
      {{"mesh", "subdivide", path("nan.obj"), path("o.obj")}, "not a finite number"},
      {{"mesh", "decompose", data("dragknob.off"), path("o.pwm"), "--levels", "1"}, "not sqrt(3)-structured"},
      {{"mesh", "subdivide", path("missing.off"), path("o.obj")}, "cannot read"},
      {{"mesh", "subdivide", data("u.off"), path("o.stl")}, "unknown mesh format"},
      {{"mesh", "reconstruct", data("u.off"), path("o.obj")}, "not a .pwm"},
      {{"mesh", "subdivide", data("u.off"), path("o.obj"), "--levels", "16"}, "would give more than"},
  };
  for (const auto& c : cases) {
    const auto r = run_cli(c.args);
    EXPECT_NE(r.exit_code, 0) << c.args[2];
    EXPECT_NE(r.output.find("pupwave: error:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(path("o.obj")));
  EXPECT_FALSE(fs::exists(path("o.pwm")));
}

TEST_F(MeshCli, CorruptStreamsAreRejectedAndOutputsKept) {
  ASSERT_EQ(run_cli({"mesh", "subdivide", data("u.off"), path("f.obj"), "--levels", "2"}).exit_code, 0);
  ASSERT_EQ(
      run_cli({"mesh", "decompose", path("f.obj"), path("f.pwm"), "--levels", "2", "--max-error", "1e-3"})
          .exit_code,
      0);
  std::ifstream in(path("f.pwm"), std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
  write_text("keep.obj", "precious");
  for (std::size_t at : {std::size_t(6), bytes.size() / 2, bytes.size() - 2}) {
    std::vector<char> bad = bytes;
    bad[at] = char(bad[at] ^ 0x5a);
    std::ofstream(path("bad.pwm"), std::ios::binary).write(bad.data(), std::streamsize(bad.size()));
    const auto r = run_cli({"mesh", "reconstruct", path("bad.pwm"), path("keep.obj")});
    EXPECT_NE(r.exit_code, 0) << at;
    EXPECT_NE(r.output.find("checksum mismatch"), std::string::npos) << r.output;
  }
  std::ofstream(path("short.pwm"), std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() - 9));
  const auto r = run_cli({"mesh", "reconstruct", path("short.pwm"), path("keep.obj")});
  EXPECT_NE(r.exit_code, 0);
  std::ifstream kept(path("keep.obj"));
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(kept)), {}), "precious");
}

}  // namespace
}  // namespace pupwave
