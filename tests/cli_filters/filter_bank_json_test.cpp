// The CLI's JSON form of a filter bank (tools/filter_bank_json.h) round-trips bit-exactly.
#include <gtest/gtest.h>

#include <stdexcept>

#include "tools/filter_bank_json.h"
#include "transforms/pups/design.h"

namespace pupwave::cli {
namespace {

TEST(FilterBankJson, RoundTripsEveryPresetBitExactly) {
  for (const auto& preset : pups::presets()) {
    const pups::FilterBank bank = pups::design_preset(preset.name);
    EXPECT_EQ(filter_bank_from_json(nlohmann::json::parse(to_json(bank).dump())), bank) << preset.name;
  }
}

TEST(FilterBankJson, MissingOrBadFieldsThrow) {
  nlohmann::json j = to_json(pups::design_preset("chaikin"));
  j.erase("Q");
  EXPECT_THROW(filter_bank_from_json(j), std::invalid_argument);
  j = to_json(pups::design_preset("chaikin"));
  j["P"]["taps"] = nlohmann::json::array();
  EXPECT_THROW(filter_bank_from_json(j), std::invalid_argument);
  j = to_json(pups::design_preset("chaikin"));
  j["design"]["weight"] = "no-such-weight";
  EXPECT_THROW(filter_bank_from_json(j), std::invalid_argument);
}

}  // namespace
}  // namespace pupwave::cli
