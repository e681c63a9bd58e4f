// What each preset is good for (coding or curve/surface design only), from its figures of
// merit; the calibration against `pupwave bench rd` is in docs/pups.md.
#include <gtest/gtest.h>

#include <string>

#include "transforms/analysis/merit.h"
#include "transforms/pups/design.h"
#include "transforms/pups/pups_transform.h"

namespace pupwave::pups {
namespace {

struct Expected {
  const char* preset;
  bool coding;
  const char* reason_part;  // a phrase the printed reason must contain ("" = none needed)
};

constexpr Expected kExpected[] = {
    {"chaikin", false, "|h||g|"},        {"cubic-bspline", false, "coarse band gain"},
    {"cinpact-c3", false, "local mean"}, {"cinpact-c3-ext", false, "local mean"},
    {"cinpact-interp-c5", true, ""},     {"cinpact-interp-c5-ext", true, ""},
    {"poly10", false, "local mean"},     {"chaikin-ext", true, ""},
    {"cinpact-interp-vm4", true, ""},    {"poly16-vm4-cg", true, ""},
};

TEST(Verdict, EveryPresetIsMarked) {
  ASSERT_EQ(std::size(kExpected), presets().size());
  for (const auto& e : kExpected) {
    const merit::Merit m = merit::figures_of_merit(*make_pups_transform_from_spec(e.preset));
    const merit::CodingVerdict v = merit::coding_verdict(m);
    EXPECT_EQ(v.coding, e.coding) << e.preset << ": " << v.reason;
    EXPECT_NE(v.reason.find(e.reason_part), std::string::npos) << e.preset << ": " << v.reason;
    if (!v.coding) {
      EXPECT_NE(v.reason.find("coding gain"), std::string::npos) << e.preset;
    }
  }
}

}  // namespace
}  // namespace pupwave::pups
