// `pupwave subdivide` end to end: output format, -o, and inputs that must be rejected.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {
namespace fs = std::filesystem;

struct CliRun {
  int exit_code = -1;
  std::string out;  // stdout only
  std::string err;  // stderr
};

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class SubdivideCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pupwave_subdivide_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  CliRun run(const std::vector<std::string>& args) {
    std::string cmd = quote(PUPWAVE_CLI) + " subdivide";
    for (const auto& a : args) cmd += " " + quote(a);
    cmd += " 2>" + quote((dir_ / "stderr.txt").string()) + " </dev/null";
    CliRun r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf{};
    for (std::size_t n; (n = fread(buf.data(), 1, buf.size(), pipe)) > 0;) r.out.append(buf.data(), n);
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.err = slurp(dir_ / "stderr.txt");
    fs::remove(dir_ / "stderr.txt");
    return r;
  }
  std::size_t files() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
  fs::path dir_;
};

std::vector<std::array<double, 2>> parse(const std::string& text) {
  std::vector<std::array<double, 2>> pts;
  std::istringstream in(text);
  for (double x, y; in >> x >> y;) pts.push_back({x, y});
  return pts;
}

const char* kPoints = "# a zig-zag\n0 0\n1 2\n\n3 3\n4 0\n6 1\n7 -2\n";

// One level of k4pt: old points kept, inner new points on the 4-point rule.
TEST_F(SubdivideCli, FourPointRuleOnStdout) {
  const fs::path in = write("p.txt", kPoints);
  const CliRun r = run({"--scheme", "k4pt", "--levels", "1", in.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto in_pts = parse("0 0 1 2 3 3 4 0 6 1 7 -2");
  const auto out = parse(r.out);
  ASSERT_EQ(out.size(), 2 * in_pts.size() - 1);
  for (std::size_t i = 0; i < in_pts.size(); ++i) EXPECT_EQ(out[2 * i], in_pts[i]);
  for (std::size_t j = 1; j + 2 < in_pts.size(); ++j) {
    for (int c = 0; c < 2; ++c) {
      const double rule =
          (-in_pts[j - 1][c] + 9 * in_pts[j][c] + 9 * in_pts[j + 1][c] - in_pts[j + 2][c]) / 16;
      EXPECT_NEAR(out[2 * j + 1][c], rule, 1e-13);
    }
  }
}

TEST_F(SubdivideCli, OutputFileMatchesStdoutAndCounts) {
  const fs::path in = write("p.txt", kPoints);
  for (const char* scheme : {"k2", "k3", "kspl", "k4pt"}) {
    const CliRun a = run({"--scheme", scheme, "--levels", "4", "--closed", in.string()});
    ASSERT_EQ(a.exit_code, 0) << a.err;
    EXPECT_EQ(parse(a.out).size(), 16u * 6u);
    const fs::path out = dir_ / "out.txt";
    const CliRun b = run({"--scheme", scheme, "--levels", "4", "--closed", in.string(), "-o", out.string()});
    ASSERT_EQ(b.exit_code, 0) << b.err;
    EXPECT_TRUE(b.out.empty());
    EXPECT_EQ(slurp(out), a.out);
  }
  const CliRun c = run({"--scheme", "k3", "--levels", "3", "--param", "centripetal", in.string()});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(parse(c.out).size(), 8u * 5u + 1u);
}

// Every rejected input: non-zero exit, a message naming the problem, no output file, and an
// existing output file left untouched.
TEST_F(SubdivideCli, RejectsBadInput) {
  const fs::path good = write("good.txt", kPoints);
  const fs::path out = write("out.txt", "keep me\n");
  struct Case {
    std::vector<std::string> args;
    std::string needle;
  };
  const std::vector<Case> cases = {
      {{(dir_ / "missing.txt").string()}, "missing.txt"},
      {{write("bad.txt", "0 0\n1 x\n").string()}, "bad.txt:2"},
      {{write("three.txt", "0 0 0\n1 1\n").string()}, "three.txt:1"},
      {{write("one.txt", "5 5\n").string()}, "at least 2 points"},
      {{write("empty.txt", "").string()}, "at least 2 points"},
      {{write("inf.txt", "0 0\n1e999 1\n").string()}, "inf.txt:2"},
      {{"--levels", "13", good.string()}, "levels"},
      {{"--levels", "-1", good.string()}, "levels"},
      {{"--scheme", "k5", good.string()}, "k4pt"},
      {{"--param", "chordal", good.string()}, "centripetal"},
      {{"--param", "centripetal", "--scheme", "k4pt", good.string()}, "k2 and k3"},
      {{write("dup.txt", "0 0\n0 0\n1 1\n").string(), "--param", "centripetal"}, "coincide"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = c.args;
    args.insert(args.end(), {"-o", out.string()});
    const std::size_t before = files();
    const CliRun r = run(args);
    EXPECT_NE(r.exit_code, 0) << c.needle;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << "expected '" << c.needle << "' in: " << r.err;
    EXPECT_EQ(slurp(out), "keep me\n") << c.needle;
    EXPECT_EQ(files(), before) << c.needle;  // no temporary file left behind
  }
  const CliRun r = run({(dir_ / "missing.txt").string(), "-o", (dir_ / "new.txt").string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_FALSE(fs::exists(dir_ / "new.txt"));
}

}  // namespace
