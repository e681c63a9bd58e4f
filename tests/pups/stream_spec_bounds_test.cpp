// Transform specs read from a stream are bounded before any design (docs/bitstream.md,
// Decoder bounds): every spec an encoder writes by name passes, oversized designs are refused
// with the bound they break, and the check designs nothing.
#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>

#include "transforms/spec.h"

namespace pupwave {
namespace {

std::string refusal(const std::string& spec) {
  try {
    check_stream_spec(spec);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(StreamSpecBounds, EveryNamedSpecAndItsCanonicalFormPass) {
  for (const auto& spec : transform_specs()) {
    EXPECT_EQ(refusal(spec), "") << spec;
  }
  const std::string custom = "pups:cinpact-interp(c=5,sigma=4.79,l=32)";
  EXPECT_EQ(refusal(custom), "");
  EXPECT_EQ(refusal(make_transform(custom)->spec()), "");
}

TEST(StreamSpecBounds, OversizedDesignsAreRefusedWithTheirBound) {
  EXPECT_NE(refusal("pups:cinpact(c=200,sigma=4,samples=2000000)").find("support 400 over 64"),
            std::string::npos);
  EXPECT_NE(refusal("pups:bspline(degree=20,samples=50000000)").find("samples outside 1..1000000"),
            std::string::npos);
  EXPECT_NE(refusal("pups:bspline(degree=20,samples=400000)").find("samples x (support + 1) over 2^23"),
            std::string::npos);
  EXPECT_NE(refusal("pups:bspline(degree=3,l=66)").find("extension l outside 0..64"), std::string::npos);
  EXPECT_NE(refusal("nonsense").find("unknown transform spec"), std::string::npos);
  EXPECT_NE(refusal("kobbelt:nope").find("unknown Kobbelt transform"), std::string::npos);
}

TEST(StreamSpecBounds, CheckingDesignsNothing) {
  // The largest admitted bspline design takes about a second; its check takes microseconds.
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < 100; ++i) check_stream_spec("pups:bspline(degree=20,samples=380000)");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.5);
}

}  // namespace
}  // namespace pupwave
