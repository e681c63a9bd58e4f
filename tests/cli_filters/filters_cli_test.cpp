// End-to-end: the `pupwave filters` subcommands run as the real binary.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

namespace {

struct Result {
  int status = -1;
  std::string out;
};

// Runs the CLI with `args` through the shell and captures stdout (stderr folded in).
Result run_cli(const std::string& args) {
  const std::string cmd = std::string("\"") + PUPWAVE_CLI + "\" " + args + " 2>&1";
  Result r;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe.get())) r.out += buf.data();
  r.status = pclose(pipe.release());
  return r;
}

TEST(FiltersCli, DesignPrintsTheChaikinMasks) {
  const Result r = run_cli("filters design --weight bspline --degree 2");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("orthogonality error: 0.530330086"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Q (4 taps, offset -1): 0.25 0.75 -0.75 -0.25"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("A (4 taps, offset -1): -0.25 0.75 0.75 -0.25"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("shift: 0"), std::string::npos) << r.out;
}

TEST(FiltersCli, JsonOutputParses) {
  const Result r = run_cli("filters design --weight cinpact-interp --c 5 --sigma 4.79 --extend 2 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("design").at("extension").get<int>(), 2);
  EXPECT_NEAR(j.at("refinement_error").get<double>(), 0.00353701, 5e-9);
  EXPECT_EQ(j.at("P").at("taps").size(), 11u);
}

TEST(FiltersCli, ListAndShow) {
  Result r = run_cli("filters list");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("cinpact-interp-c5-ext"), std::string::npos);
  r = run_cli("filters show chaikin");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("spec: pups:chaikin"), std::string::npos) << r.out;
}

TEST(FiltersCli, BadInputFailsWithAMessage) {
  Result r = run_cli("filters show no-such-preset");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("pupwave: error: unknown PUPs preset"), std::string::npos) << r.out;
  r = run_cli("filters design --weight cinpact --c 3 --sigma 7 --extend 3");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("even"), std::string::npos) << r.out;
}

}  // namespace
