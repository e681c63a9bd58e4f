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

TEST(FiltersCli, ListMarksWhatEachPresetIsGoodFor) {
  const Result r = run_cli("filters list");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("cinpact-interp-c5-ext"), std::string::npos);
  const auto block = [&r](const std::string& name) {
    const std::size_t at = r.out.find("  " + name + "  ");
    return at == std::string::npos ? std::string()
                                   : r.out.substr(at, r.out.find("\n  ", r.out.find("use:", at)) - at);
  };
  EXPECT_NE(block("poly16-vm4-cg").find("use: coding"), std::string::npos) << r.out;
  EXPECT_NE(block("cubic-bspline").find("use: curve/surface design only: coding gain 2.19 dB"),
            std::string::npos)
      << r.out;
  EXPECT_NE(block("cinpact-c3").find("of the local mean"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("CDF 9/7: 9.837 dB"), std::string::npos) << r.out;
}

TEST(FiltersCli, ShowPrintsTheFiguresOfMerit) {
  Result r = run_cli("filters show chaikin");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("spec: pups:chaikin"), std::string::npos) << r.out;
  r = run_cli("filters show poly16-vm4-cg");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("vanishing moments: analysis 4"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("boundary: whole-sample symmetric line (wss)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("use: coding"), std::string::npos) << r.out;
  r = run_cli("filters show cinpact-c3 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j.at("figures").at("coding").get<bool>());
  EXPECT_EQ(j.at("figures").at("coarse_gain").size(), 5u);
  EXPECT_GT(j.at("figures").at("dc_leak").get<double>(), 0.04);
}

// The best design a search prints codes through the codec on a real photograph.
TEST(FiltersCli, SearchPrintsSpecsThatCompress) {
  const Result r = run_cli("filters search --weight bspline --degree 1,2 --l 0,8 --boundary hss --top 3");
  ASSERT_EQ(r.status, 0) << r.out;
  const std::size_t at = r.out.find("best: pups:");
  ASSERT_NE(at, std::string::npos) << r.out;
  const std::string spec = r.out.substr(at + 6, r.out.find('\n', at) - at - 6);
  EXPECT_EQ(spec, "pups:bspline(degree=1,l=8)") << r.out;
  const std::string in = std::string(PUPWAVE_TESTIMAGES_DIR) + "/camera.png";
  const std::string pw = testing::TempDir() + "/search_best.pw",
                    png = testing::TempDir() + "/search_best.png";
  const Result c =
      run_cli("compress \"" + in + "\" \"" + pw + "\" --bpp 0.5 --transform \"" + spec + "\" --report-psnr");
  ASSERT_EQ(c.status, 0) << c.out;
  const Result d = run_cli("decompress \"" + pw + "\" \"" + png + "\"");
  ASSERT_EQ(d.status, 0) << d.out;
}

// The best PUPs bank codes a photograph as well as CDF 9/7 (within 0.1 dB at 1 bpp).
TEST(FiltersCli, Poly16CodesLikeCdf97) {
  const std::string in = std::string(PUPWAVE_TESTIMAGES_DIR) + "/camera.png";
  const std::string pw = testing::TempDir() + "/poly16.pw";
  auto psnr_of = [&](const std::string& transform) {
    const Result r =
        run_cli("compress \"" + in + "\" \"" + pw + "\" --bpp 1 --transform " + transform + " --report-psnr");
    EXPECT_EQ(r.status, 0) << r.out;
    const std::size_t at = r.out.find("PSNR ");
    return at == std::string::npos ? 0.0 : std::stod(r.out.substr(at + 5));
  };
  const double cdf = psnr_of("cdf97"), pups = psnr_of("pups:poly16-vm4-cg");
  EXPECT_GT(pups, cdf - 0.1) << "cdf97 " << cdf << " pups " << pups;
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
